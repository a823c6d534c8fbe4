#include "ConformanceRules.h"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <set>

#include "GlslEsRules.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

// ---- Static recursion (GLSL ES 1.00 §6.1, 3.00 §6.1) ------------------------------------------

// glslang names functions by their mangled signature, "f(f1;"; people know them as "f".
std::string PlainName(const std::string& mangled) {
    return mangled.substr(0, mangled.find('('));
}

struct Call {
    std::string callee;  // mangled
    glslang::TSourceLoc loc;
};

// Every function the stage defines, in order, with the user functions each one calls.
class CallGraphBuilder : public glslang::TIntermTraverser {
public:
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->getOp() == glslang::EOpFunction) {
            current_ = node->getName().c_str();
            if (calls.emplace(current_, std::vector<Call>{}).second) {
                order.push_back(current_);
            }
        } else if (node->getOp() == glslang::EOpFunctionCall && !current_.empty()) {
            calls[current_].push_back(Call{node->getName().c_str(), node->getLoc()});
        }
        return true;
    }
    std::vector<std::string> order;
    std::map<std::string, std::vector<Call>> calls;

private:
    std::string current_;
};

// Depth-first search for cycles; each call that closes one (a back edge) is reported once.
class CycleFinder {
public:
    CycleFinder(const CallGraphBuilder& graph, const std::string& file,
                std::vector<Diagnostic>* errors)
        : graph_(graph), file_(file), errors_(errors) {}

    void Visit(const std::string& function) {
        state_[function] = kOnPath;
        path_.push_back(function);
        for (const Call& call : graph_.calls.at(function)) {
            if (graph_.calls.count(call.callee) == 0) {
                continue;  // declared here, defined nowhere in this stage: no edge to follow
            }
            const State state = state_[call.callee];
            if (state == kOnPath) {
                Report(call);
            } else if (state == kUnseen) {
                Visit(call.callee);
            }
        }
        path_.pop_back();
        state_[function] = kDone;
    }
    void VisitAll() {
        for (const std::string& function : graph_.order) {
            if (state_[function] == kUnseen) {
                Visit(function);
            }
        }
    }

private:
    enum State { kUnseen, kOnPath, kDone };

    void Report(const Call& call) {
        const auto start = std::find(path_.begin(), path_.end(), call.callee);
        std::vector<std::string> cycle;
        for (auto it = start; it != path_.end(); ++it) {
            cycle.push_back(PlainName(*it));
        }
        cycle.push_back(PlainName(call.callee));
        errors_->push_back(MakeError(
                file_, call.loc.line, std::max(call.loc.column, 0),
                fmt::format("'{}' is called recursively ({}); GLSL ES allows no recursion, not "
                            "even in code that never runs (GLSL ES 1.00 §6.1, GLSL ES 3.00 "
                            "§6.1)",
                            cycle.front(), fmt::join(cycle, " -> "))));
    }

    const CallGraphBuilder& graph_;
    const std::string& file_;
    std::vector<Diagnostic>* errors_;
    std::map<std::string, State> state_;
    std::vector<std::string> path_;
};

// ---- gl_FragColor and gl_FragData (GLSL ES 1.00 §7.2) ------------------------------------------

bool IsAssignment(glslang::TOperator op) {
    return op >= glslang::EOpAssign && op <= glslang::EOpRightShiftAssign;
}

// The first place each built-in fragment output is written (assigned, incremented, or passed
// as an out or inout argument), whether or not that code ever runs.
class FragmentOutputWrites : public glslang::TIntermTraverser {
public:
    bool visitBinary(glslang::TVisit, glslang::TIntermBinary* node) override {
        if (IsAssignment(node->getOp())) {
            Note(node->getLeft(), node->getLoc());
        }
        return true;
    }
    bool visitUnary(glslang::TVisit, glslang::TIntermUnary* node) override {
        switch (node->getOp()) {
            case glslang::EOpPostIncrement:
            case glslang::EOpPostDecrement:
            case glslang::EOpPreIncrement:
            case glslang::EOpPreDecrement:
                Note(node->getOperand(), node->getLoc());
                break;
            default:
                break;
        }
        return true;
    }
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->getOp() == glslang::EOpFunctionCall) {
            const glslang::TQualifierList& qualifiers = node->getQualifierList();
            const glslang::TIntermSequence& arguments = node->getSequence();
            for (std::size_t i = 0; i < qualifiers.size() && i < arguments.size(); ++i) {
                if (qualifiers[i] == glslang::EvqOut || qualifiers[i] == glslang::EvqInOut) {
                    Note(arguments[i]->getAsTyped(), node->getLoc());
                }
            }
        }
        return true;
    }
    std::map<std::string, glslang::TSourceLoc> first_write;

private:
    void Note(glslang::TIntermTyped* target, const glslang::TSourceLoc& loc) {
        // Down through indexing, swizzles and member selection to the variable written.
        while (target != nullptr && target->getAsBinaryNode() != nullptr) {
            target = target->getAsBinaryNode()->getLeft();
        }
        const glslang::TIntermSymbol* symbol =
                target != nullptr ? target->getAsSymbolNode() : nullptr;
        if (symbol == nullptr) {
            return;
        }
        const std::string name = symbol->getName().c_str();
        if (name == "gl_FragColor" || name == "gl_FragData") {
            first_write.emplace(name, loc);
        }
    }
};

bool Before(const glslang::TSourceLoc& a, const glslang::TSourceLoc& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
}

// ---- Uniform precision, interpolation ----------------------------------------------------------

const char* PrecisionName(glslang::TPrecisionQualifier precision) {
    switch (precision) {
        case glslang::EpqLow:
            return "lowp";
        case glslang::EpqMedium:
            return "mediump";
        case glslang::EpqHigh:
            return "highp";
        default:
            return "no precision";
    }
}

// The first member (as "a.b.c") whose precision differs between two types glslang already
// found equal in shape, with both precisions.
struct PrecisionClash {
    std::string member;
    glslang::TPrecisionQualifier vertex = glslang::EpqNone;
    glslang::TPrecisionQualifier fragment = glslang::EpqNone;
};

std::optional<PrecisionClash> MemberPrecisionClash(const glslang::TType& vertex,
                                                   const glslang::TType& fragment,
                                                   const std::string& prefix) {
    if (!vertex.isStruct() || !fragment.isStruct()) {
        return std::nullopt;
    }
    const glslang::TTypeList& vertex_members = *vertex.getStruct();
    const glslang::TTypeList& fragment_members = *fragment.getStruct();
    if (vertex_members.size() != fragment_members.size()) {
        return std::nullopt;  // a shape mismatch: glslang's own link reports it
    }
    for (std::size_t i = 0; i < vertex_members.size(); ++i) {
        const glslang::TType& v = *vertex_members[i].type;
        const glslang::TType& f = *fragment_members[i].type;
        const std::string member = prefix + "." + v.getFieldName().c_str();
        if (v.getFieldName() != f.getFieldName()) {
            return std::nullopt;
        }
        if (v.isStruct()) {
            if (auto clash = MemberPrecisionClash(v, f, member)) {
                return clash;
            }
        } else if (v.getQualifier().precision != f.getQualifier().precision) {
            return PrecisionClash{member, v.getQualifier().precision, f.getQualifier().precision};
        }
    }
    return std::nullopt;
}

// How an interface variable is matched across stages: a block by its block name (GLSL ES 3.00
// §4.3.7), anything else by its own name.
std::string InterfaceKey(const glslang::TIntermSymbol& symbol) {
    const glslang::TType& type = symbol.getType();
    if (type.getBasicType() == glslang::EbtBlock) {
        return std::string("block ") + type.getTypeName().c_str();
    }
    return symbol.getName().c_str();
}

const char* InterpolationName(const glslang::TQualifier& qualifier) {
    return qualifier.flat ? "flat" : "smooth";
}

}  // namespace

std::vector<Diagnostic> CheckStageConformance(const glslang::TIntermediate& stage,
                                              const std::string& file) {
    std::vector<Diagnostic> errors;
    TIntermNode* root = stage.getTreeRoot();
    if (root == nullptr) {
        return errors;
    }
    CallGraphBuilder graph;
    root->traverse(&graph);
    CycleFinder(graph, file, &errors).VisitAll();

    if (stage.getStage() == EShLangFragment) {
        FragmentOutputWrites writes;
        root->traverse(&writes);
        const auto color = writes.first_write.find("gl_FragColor");
        const auto data = writes.first_write.find("gl_FragData");
        if (color != writes.first_write.end() && data != writes.first_write.end()) {
            // Reported at whichever write came second: that is the one the rule forbids.
            const bool data_later = Before(color->second, data->second);
            const auto& later = data_later ? *data : *color;
            const auto& earlier = data_later ? *color : *data;
            errors.push_back(MakeError(
                    file, later.second.line, std::max(later.second.column, 0),
                    fmt::format("'{}' is written, but this shader also writes '{}' (line {}); a "
                                "fragment shader may write gl_FragColor or gl_FragData, not "
                                "both (GLSL ES 1.00 §7.2)",
                                later.first, earlier.first, earlier.second.line)));
        }
    }
    return errors;
}

std::vector<Diagnostic> CheckLinkConformance(const glslang::TIntermediate& vertex,
                                             const std::string& vertex_file,
                                             const glslang::TIntermediate& fragment,
                                             const std::string& fragment_file,
                                             std::string_view fragment_source) {
    std::vector<Diagnostic> errors;
    // Reported at the fragment stage's declaration: the vertex side is named in the message.
    auto report = [&](std::string_view name, std::string message) {
        const auto [line, column] = FirstMention(fragment_source, name);
        errors.push_back(MakeError(fragment_file, line, column, std::move(message)));
    };
    std::map<std::string, const glslang::TIntermSymbol*> vertex_uniforms;
    std::map<std::string, const glslang::TIntermSymbol*> vertex_outputs;
    for (const glslang::TIntermSymbol* symbol : LinkerObjects(vertex)) {
        const glslang::TStorageQualifier storage = symbol->getType().getQualifier().storage;
        if (storage == glslang::EvqUniform) {
            vertex_uniforms.emplace(InterfaceKey(*symbol), symbol);
        } else if (storage == glslang::EvqVaryingOut) {
            vertex_outputs.emplace(symbol->getName().c_str(), symbol);
        }
    }
    for (const glslang::TIntermSymbol* symbol : LinkerObjects(fragment)) {
        const glslang::TType& type = symbol->getType();
        const std::string name = symbol->getName().c_str();
        if (type.getQualifier().storage == glslang::EvqUniform) {
            const auto other = vertex_uniforms.find(InterfaceKey(*symbol));
            if (other == vertex_uniforms.end() || !(other->second->getType() == type)) {
                continue;  // declared once, or a type clash glslang's own link reports
            }
            const bool block = type.getBasicType() == glslang::EbtBlock;
            const std::string shown = block ? type.getTypeName().c_str() : name;
            const auto clash = MemberPrecisionClash(other->second->getType(), type, shown);
            if (!clash) {
                continue;
            }
            report(shown,
                   fmt::format("uniform member '{}' is {} here but {} in the vertex shader {}; a "
                               "uniform declared in both stages must match in type and "
                               "precision, members included (GLSL ES 1.00 §4.5.3, GLSL ES 3.00 "
                               "§4.3.5)",
                               clash->member, PrecisionName(clash->fragment),
                               PrecisionName(clash->vertex), vertex_file));
        } else if (type.getQualifier().storage == glslang::EvqVaryingIn &&
                   fragment.getVersion() >= 300) {
            const auto output = vertex_outputs.find(name);
            if (output == vertex_outputs.end() ||
                output->second->getType().getQualifier().flat == type.getQualifier().flat) {
                continue;
            }
            report(name,
                   fmt::format("input '{}' is {} here but {} in the vertex shader {}; the "
                               "interpolation qualifiers of an output and its input must match "
                               "(GLSL ES 3.00 §4.3.9)",
                               name, InterpolationName(type.getQualifier()),
                               InterpolationName(output->second->getType().getQualifier()),
                               vertex_file));
        }
    }
    return errors;
}

namespace {

// Logical lines of a text with `//` and `/* */` comments blanked (a comment spanning lines keeps
// its newlines), for the directive scans below; a backslash-newline is not joined, which only
// makes MayHaveLateExtension answer "maybe" more often.
std::vector<std::string> CommentFreeLines(std::string_view text) {
    std::vector<std::string> lines(1);
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text.compare(i, 2, "//") == 0) {
            while (i + 1 < text.size() && text[i + 1] != '\n') {
                ++i;
            }
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            const std::size_t stop = end == std::string_view::npos ? text.size() : end + 2;
            for (; i < stop; ++i) {
                if (text[i] == '\n') {
                    lines.emplace_back();
                }
            }
            --i;
            lines.back() += ' ';
        } else if (text[i] == '\n') {
            lines.emplace_back();
        } else {
            lines.back() += text[i];
        }
    }
    return lines;
}

// The directive a line holds ("extension" for "  #  extension x : y"), "" for a line of ordinary
// tokens, and nullopt for a blank line.
std::optional<std::string> DirectiveOf(const std::string& line) {
    const std::size_t first = line.find_first_not_of(" \t\r\f\v");
    if (first == std::string::npos) {
        return std::nullopt;
    }
    if (line[first] != '#') {
        return std::string();
    }
    const std::size_t word = line.find_first_not_of(" \t", first + 1);
    if (word == std::string::npos) {
        return std::string("#");
    }
    std::size_t end = word;
    while (end < line.size() &&
           (std::isalnum(static_cast<unsigned char>(line[end])) != 0 || line[end] == '_')) {
        ++end;
    }
    return line.substr(word, end - word);
}

constexpr std::string_view kDefinedFromMacro =
        "cannot use in preprocessor expression when expanded from macros";
constexpr std::string_view kDefinedFromMacroRelaxed = "nonportable when expanded from macros";
constexpr std::string_view kReservedMacro100 =
        "names containing consecutive underscores are reserved, and an error if version < 300";
constexpr std::string_view kReservedMacroWarning =
        "names containing consecutive underscores are reserved:";

bool Mentions(const Diagnostic& d, std::string_view text) {
    return d.message.find(text) != std::string::npos;
}

}  // namespace

bool MayHaveLateExtension(std::string_view source) {
    bool tokens_seen = false;
    for (const std::string& line : CommentFreeLines(source)) {
        const std::optional<std::string> directive = DirectiveOf(line);
        if (!directive) {
            continue;
        }
        if (directive->empty()) {
            tokens_seen = true;
        } else if (*directive == "extension" && tokens_seen) {
            return true;
        }
    }
    return false;
}

std::vector<Diagnostic> CheckExtensionPlacement(std::string_view preprocessed,
                                                const std::string& file) {
    std::vector<Diagnostic> errors;
    int tokens_line = 0;
    int line_number = 0;
    for (const std::string& line : CommentFreeLines(preprocessed)) {
        ++line_number;
        const std::optional<std::string> directive = DirectiveOf(line);
        if (!directive) {
            continue;
        }
        if (directive->empty()) {
            tokens_line = tokens_line == 0 ? line_number : tokens_line;
        } else if (*directive == "extension" && tokens_line != 0) {
            errors.push_back(MakeError(
                    file, line_number, static_cast<int>(line.find('#')) + 1,
                    fmt::format("'#extension' after the first non-preprocessor token (line {}); "
                                "extension directives must come before any of them (GLSL ES "
                                "1.00 §3.4, GLSL ES 3.00 §3.4)",
                                tokens_line)));
        }
    }
    return errors;
}

bool FailedOnlyForRelaxableReasons(const std::vector<Diagnostic>& diagnostics, int version,
                                   bool webgl) {
    bool any = false;
    for (const Diagnostic& d : diagnostics) {
        if (d.severity != Severity::kError) {
            continue;
        }
        const bool relaxable = (!webgl && Mentions(d, kDefinedFromMacro)) ||
                               (version == 100 && Mentions(d, kReservedMacro100));
        if (!relaxable) {
            return false;
        }
        any = true;
    }
    return any;
}

std::vector<Diagnostic> RestoreDemotedErrors(std::vector<Diagnostic> diagnostics) {
    for (Diagnostic& d : diagnostics) {
        // In 3.00 the reserved-name warning is glslang's strict verdict too (and is made an
        // error by PromoteReservedMacroNames); in 1.00 it is the relaxed form of the error.
        if (d.severity == Severity::kWarning && !Mentions(d, kDefinedFromMacroRelaxed) &&
            !Mentions(d, kReservedMacroWarning)) {
            d.severity = Severity::kError;
        }
    }
    return diagnostics;
}

std::vector<Diagnostic> PromoteReservedMacroNames(std::vector<Diagnostic> diagnostics,
                                                  int version) {
    if (version < 300) {
        return diagnostics;
    }
    for (Diagnostic& d : diagnostics) {
        if (d.severity == Severity::kWarning && Mentions(d, kReservedMacroWarning)) {
            const std::size_t colon = d.message.rfind(':');
            const std::string name =
                    colon == std::string::npos ? std::string("?") : d.message.substr(colon + 2);
            d.severity = Severity::kError;
            d.message = fmt::format(
                    "macro name '{}' contains '__'; GLSL ES 3.00 reserves such names, so a "
                    "'#version 300 es' shader may not define or undefine them (GLSL ES 3.00 "
                    "§3.4)",
                    name);
        }
    }
    return diagnostics;
}

}  // namespace tidepool
