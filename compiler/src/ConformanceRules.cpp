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

// A type as a shader spells it: "vec3", "int[4]", "sampler2D", "struct Fog {float density, vec3
// colour}" (members by type and name, so that two structs of one name can be told apart).
std::string TypeText(const glslang::TType& type) {
    std::string text;
    if (type.isStruct()) {
        text = fmt::format("{} {} {{",
                           type.getBasicType() == glslang::EbtBlock ? "block" : "struct",
                           type.getTypeName().c_str());
        const char* separator = "";
        for (const glslang::TTypeLoc& member : *type.getStruct()) {
            text += fmt::format("{}{} {}", separator, TypeText(*member.type),
                                member.type->getFieldName().c_str());
            separator = ", ";
        }
        text += "}";
    } else if (type.isMatrix()) {
        text = type.getMatrixCols() == type.getMatrixRows()
                       ? fmt::format("mat{}", type.getMatrixCols())
                       : fmt::format("mat{}x{}", type.getMatrixCols(), type.getMatrixRows());
    } else if (type.isVector()) {
        const glslang::TBasicType basic = type.getBasicType();
        const char* prefix = basic == glslang::EbtInt    ? "i"
                             : basic == glslang::EbtUint ? "u"
                             : basic == glslang::EbtBool ? "b"
                                                         : "";
        text = fmt::format("{}vec{}", prefix, type.getVectorSize());
    } else {
        text = type.getBasicTypeString().c_str();  // float, int, uint, bool, or the sampler's name
    }
    if (type.isArray()) {
        for (int i = 0; i < type.getArraySizes()->getNumDims(); ++i) {
            text += fmt::format("[{}]", type.getArraySizes()->getDimSize(i));
        }
    }
    return text;
}

// Where two declarations of one interface variable first differ in type: `what` names the
// variable or member ("fog.colour"), `here` is the fragment stage's type, `there` the vertex's.
struct TypeClash {
    std::string what;
    std::string here;
    std::string there;
};

std::optional<TypeClash> FirstTypeClash(const glslang::TType& vertex,
                                        const glslang::TType& fragment, const std::string& what) {
    if (vertex == fragment || vertex.isUnsizedArray() || fragment.isUnsizedArray()) {
        return std::nullopt;  // an unsized array takes its size at link time: glslang decides
    }
    // Structs of one name, arrayness and member names: the clash is in a member.
    if (vertex.isStruct() && fragment.isStruct() && vertex.sameArrayness(fragment) &&
        vertex.getTypeName() == fragment.getTypeName() &&
        vertex.getStruct()->size() == fragment.getStruct()->size()) {
        const glslang::TTypeList& vertex_members = *vertex.getStruct();
        const glslang::TTypeList& fragment_members = *fragment.getStruct();
        bool same_names = true;
        for (std::size_t i = 0; i < vertex_members.size(); ++i) {
            same_names = same_names && vertex_members[i].type->getFieldName() ==
                                               fragment_members[i].type->getFieldName();
        }
        for (std::size_t i = 0; same_names && i < vertex_members.size(); ++i) {
            const glslang::TType& v = *vertex_members[i].type;
            if (auto clash = FirstTypeClash(v, *fragment_members[i].type,
                                            what + "." + v.getFieldName().c_str())) {
                return clash;
            }
        }
    }
    return TypeClash{what, TypeText(fragment), TypeText(vertex)};
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

// The 1-based column of the first whole-word `name` on 1-based line `line` of `text` (0 when
// it is not there): the preprocessed text glslang gives back keeps lines, not columns.
int ColumnOnLine(std::string_view text, int line, std::string_view name) {
    std::size_t start = 0;
    for (int l = 1; l < line && start != std::string_view::npos; ++l) {
        start = text.find('\n', start);
        start = start == std::string_view::npos ? start : start + 1;
    }
    if (start == std::string_view::npos) {
        return 0;
    }
    const std::size_t end = text.find('\n', start);
    const std::string_view row =
            text.substr(start, end == std::string_view::npos ? text.size() - start : end - start);
    const auto [row_line, column] = FirstMention(row, name);
    return row_line == 0 ? 0 : column;
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

std::vector<Diagnostic> CheckLinkConformance(const LinkedStage& vertex_stage,
                                             const LinkedStage& fragment_stage) {
    constexpr std::string_view kUniformRule =
            "a uniform declared in both stages must match in type and precision, members "
            "included (GLSL ES 1.00 §4.5.3, GLSL ES 3.00 §4.3.5)";
    const glslang::TIntermediate& vertex = vertex_stage.intermediate;
    const glslang::TIntermediate& fragment = fragment_stage.intermediate;
    const std::string& vertex_file = vertex_stage.file;
    const std::string& fragment_file = fragment_stage.file;
    const std::string_view fragment_source = fragment_stage.source;
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
            if (other == vertex_uniforms.end()) {
                continue;  // declared once
            }
            const glslang::TType& there = other->second->getType();
            const bool block = type.getBasicType() == glslang::EbtBlock;
            const std::string shown = block ? type.getTypeName().c_str() : name;
            if (const auto clash = FirstTypeClash(there, type, shown)) {
                report(shown, fmt::format("uniform {}'{}' is {} here but {} in the vertex shader "
                                          "{}; {}",
                                          clash->what == shown ? "" : "member ", clash->what,
                                          clash->here, clash->there, vertex_file, kUniformRule));
                continue;
            }
            if (!type.isStruct() &&
                there.getQualifier().precision != type.getQualifier().precision) {
                report(shown, fmt::format("uniform '{}' is {} here but {} in the vertex shader {}; "
                                          "{}",
                                          shown, PrecisionName(type.getQualifier().precision),
                                          PrecisionName(there.getQualifier().precision),
                                          vertex_file, kUniformRule));
                continue;
            }
            const auto clash = MemberPrecisionClash(there, type, shown);
            if (!clash) {
                continue;
            }
            report(shown,
                   fmt::format("uniform member '{}' is {} here but {} in the vertex shader {}; {}",
                               clash->member, PrecisionName(clash->fragment),
                               PrecisionName(clash->vertex), vertex_file, kUniformRule));
        } else if (type.getQualifier().storage == glslang::EvqVaryingIn) {
            const auto output = vertex_outputs.find(name);
            if (output == vertex_outputs.end()) {
                continue;  // reported by CheckLinkRules when the fragment stage reads it
            }
            const glslang::TType& there = output->second->getType();
            const bool es100 = fragment.getVersion() == 100;
            if (const auto clash = FirstTypeClash(there, type, name)) {
                report(name, fmt::format("{} {}'{}' is {} here but {} in the vertex shader {}; {}",
                                         es100 ? "varying" : "input",
                                         clash->what == name ? "" : "member ", clash->what,
                                         clash->here, clash->there, vertex_file,
                                         es100 ? "a varying declared in both stages must have "
                                                 "the same type in both (GLSL ES 1.00 §4.3.5)"
                                               : "an output and the input of the same name "
                                                 "must have the same type (GLSL ES 3.00 "
                                                 "§4.3.4)"));
            } else if (!es100 && there.getQualifier().flat != type.getQualifier().flat) {
                report(name,
                       fmt::format("input '{}' is {} here but {} in the vertex shader {}; the "
                                   "interpolation qualifiers of an output and its input must "
                                   "match (GLSL ES 3.00 §4.3.9)",
                                   name, InterpolationName(type.getQualifier()),
                                   InterpolationName(there.getQualifier()), vertex_file));
            } else if (es100) {
                // GLSL ES 1.00 §4.6.4: "The invariance of varyings that are declared in both the
                // vertex and fragment shaders must match." `#pragma STDGL invariant(all)` makes
                // "all output variables" invariant (§4.6.1): the vertex shader's varyings, not
                // the fragment shader's.
                const bool here = type.getQualifier().invariant;
                const bool invariant_there =
                        there.getQualifier().invariant || vertex_stage.invariance.all;
                if (here != invariant_there) {
                    report(name,
                           fmt::format("varying '{}' is {} here but {} in the vertex shader {}; "
                                       "the invariance of a varying declared in both stages "
                                       "must match (GLSL ES 1.00 §4.6.4)",
                                       name, here ? "invariant" : "not invariant",
                                       invariant_there ? "invariant" : "not invariant",
                                       vertex_file));
                }
            }
        }
    }
    if (fragment.getVersion() == 100) {
        // GLSL ES 1.00 §4.6.4: gl_FragCoord may be declared invariant only if gl_Position is, and
        // gl_PointCoord only if gl_PointSize is.
        auto invariant_in_vertex = [&](std::string_view name) {
            return vertex_stage.invariance.all ||
                   std::any_of(vertex_stage.invariance.builtins.begin(),
                               vertex_stage.invariance.builtins.end(),
                               [&](const InvariantBuiltIn& b) { return b.name == name; });
        };
        static const std::pair<std::string_view, std::string_view> pairs[] = {
                {"gl_FragCoord", "gl_Position"}, {"gl_PointCoord", "gl_PointSize"}};
        for (const InvariantBuiltIn& builtin : fragment_stage.invariance.builtins) {
            for (const auto& [input, output] : pairs) {
                if (builtin.name == input && !invariant_in_vertex(output)) {
                    errors.push_back(MakeError(
                            fragment_file, builtin.line, builtin.column,
                            fmt::format("'{}' is declared invariant, but '{}' is not invariant "
                                        "in the vertex shader {}; {} may be invariant only if "
                                        "{} is (GLSL ES 1.00 §4.6.4)",
                                        input, output, vertex_file, input, output)));
                }
            }
        }
    }
    return errors;
}

bool MayRedeclareInvariant(std::string_view source) {
    return source.find("invariant") != std::string_view::npos;
}

InvarianceDeclarations FindInvarianceDeclarations(std::string_view preprocessed,
                                                  std::string_view source) {
    InvarianceDeclarations found;
    std::vector<SourceToken> tokens;
    for (const std::vector<SourceToken>& line : SourceTokenLines(preprocessed)) {
        if (!line.empty() && line[0].text == "#") {
            // A directive is no declaration, but `#pragma STDGL invariant(all)` is the pragma
            // (glslang's preprocessed text may write it without blanks: "STDGLinvariant(all)").
            if (line.size() >= 2 && line[1].text == "pragma") {
                std::string words;
                for (std::size_t k = 2; k < line.size(); ++k) {
                    words += line[k].text;
                }
                found.all = found.all || words == "STDGLinvariant(all)";
            }
            continue;
        }
        tokens.insert(tokens.end(), line.begin(), line.end());
    }
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        if (tokens[i].text != "invariant") {
            continue;
        }
        // invariant NAME (, NAME)* ;  -- anything else (invariant varying ...) declares a
        // variable, whose qualifiers glslang keeps.
        std::vector<const SourceToken*> names;
        std::size_t k = i + 1;
        while (k < tokens.size() && tokens[k].identifier) {
            names.push_back(&tokens[k]);
            ++k;
            if (k < tokens.size() && tokens[k].text == ",") {
                ++k;
                continue;
            }
            break;
        }
        if (names.empty() || k >= tokens.size() || tokens[k].text != ";") {
            continue;
        }
        for (const SourceToken* name : names) {
            if (name->text.rfind("gl_", 0) == 0) {
                found.builtins.push_back(
                        InvariantBuiltIn{std::string(name->text), name->line,
                                         ColumnOnLine(source, name->line, name->text)});
            }
        }
    }
    return found;
}

std::vector<Diagnostic> CheckInvariantBuiltIns(const glslang::TIntermediate& stage,
                                               const InvarianceDeclarations& invariance,
                                               const std::string& file) {
    std::vector<Diagnostic> errors;
    if (stage.getVersion() != 100 || stage.getStage() != EShLangFragment) {
        return errors;
    }
    for (const InvariantBuiltIn& builtin : invariance.builtins) {
        if (builtin.name == "gl_FrontFacing") {
            errors.push_back(MakeError(file, builtin.line, builtin.column,
                                       "'gl_FrontFacing' cannot be declared invariant; its "
                                       "invariance is that of gl_Position (GLSL ES 1.00 §4.6.4)"));
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

constexpr std::string_view kEmptyLastCase = "last case/default label not followed by statements";

constexpr std::string_view kNonConstantGlobal = "'non-constant global initializer";

bool Mentions(const Diagnostic& d, std::string_view text) {
    return d.message.find(text) != std::string::npos;
}

// The tokens of a text outside preprocessor directives, in order.
std::vector<SourceToken> CodeTokens(std::string_view text) {
    std::vector<SourceToken> tokens;
    for (const std::vector<SourceToken>& line : SourceTokenLines(text)) {
        if (!line.empty() && line[0].text == "#") {
            continue;
        }
        tokens.insert(tokens.end(), line.begin(), line.end());
    }
    return tokens;
}

// The index of the token closing the bracket opened at tokens[open] (tokens.size() if none).
std::size_t Closing(const std::vector<SourceToken>& tokens, std::size_t open) {
    const std::string_view opener = tokens[open].text;
    const std::string_view closer = opener == "(" ? ")" : opener == "[" ? "]" : "}";
    int depth = 0;
    for (std::size_t i = open; i < tokens.size(); ++i) {
        if (tokens[i].text == opener) {
            ++depth;
        } else if (tokens[i].text == closer && --depth == 0) {
            return i;
        }
    }
    return tokens.size();
}

// Two single-character tokens written as one operator (`++`, `+=`).
bool Adjacent(const SourceToken& a, const SourceToken& b) {
    return a.line == b.line && b.column == a.column + static_cast<int>(a.text.size());
}

}  // namespace

std::set<int> SwitchesWithStatementAfterLastLabel(std::string_view preprocessed) {
    const std::vector<SourceToken> tokens = CodeTokens(preprocessed);
    std::map<int, bool> lines;  // line of a switch -> every switch there ends in a statement
    for (std::size_t i = 0; i + 1 < tokens.size(); ++i) {
        if (tokens[i].text != "switch" || tokens[i + 1].text != "(") {
            continue;
        }
        const std::size_t condition_end = Closing(tokens, i + 1);
        bool ok = false;
        if (condition_end + 1 < tokens.size() && tokens[condition_end + 1].text == "{") {
            const std::size_t body_end = Closing(tokens, condition_end + 1);
            // A label ends in `:`, and no statement or expression can end in one: the token
            // before the closing brace is that `:` exactly when the last label stands alone. An
            // empty body is left to glslang.
            ok = body_end < tokens.size() && body_end > condition_end + 2 &&
                 tokens[body_end - 1].text != ":";
        }
        const auto [entry, inserted] = lines.emplace(tokens[i].line, ok);
        if (!inserted) {
            entry->second = entry->second && ok;
        }
    }
    std::set<int> result;
    for (const auto& [line, ok] : lines) {
        if (ok) {
            result.insert(line);
        }
    }
    return result;
}

bool MentionsEmptyLastCase(const std::vector<Diagnostic>& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const Diagnostic& d) { return Mentions(d, kEmptyLastCase); });
}

namespace {

// True when every '+' in `text` is plainly binary or part of `++`/`+=`: the nearest non-blank
// character before it ends an operand (a word other than `return`, `case`, `else` or `do`, a
// number, ')', ']' or '.'). A cheap test on
// the raw text that lets most shaders, which have only binary '+', skip the token scan; anything
// else (a '+' after an operator, a comment or a line break into a directive) goes to the scan.
bool EveryPlusIsPlainlyBinary(std::string_view text) {
    for (std::size_t at = text.find('+'); at != std::string_view::npos;
         at = text.find('+', at + 1)) {
        if ((at + 1 < text.size() && (text[at + 1] == '+' || text[at + 1] == '=')) ||
            (at > 0 && text[at - 1] == '+')) {
            continue;
        }
        std::size_t before = at;
        while (before > 0 && (text[before - 1] == ' ' || text[before - 1] == '\t')) {
            --before;
        }
        if (before == 0) {
            return false;
        }
        const char c = text[before - 1];
        const auto word_char = [](char ch) {
            return std::isalnum(static_cast<unsigned char>(ch)) != 0 || ch == '_';
        };
        if (c == ')') {
            // The condition of `if`, `while` or `for` is followed by a statement, not an operand.
            int depth = 0;
            std::size_t open = before - 1;
            for (; open != std::string_view::npos; --open) {
                depth += text[open] == ')' ? 1 : text[open] == '(' ? -1 : 0;
                if (depth == 0 || open == 0) {
                    break;
                }
            }
            std::size_t word_end = open;
            while (word_end > 0 && (text[word_end - 1] == ' ' || text[word_end - 1] == '\t' ||
                                    text[word_end - 1] == '\n')) {
                --word_end;
            }
            std::size_t word_start = word_end;
            while (word_start > 0 && word_char(text[word_start - 1])) {
                --word_start;
            }
            const std::string_view keyword = text.substr(word_start, word_end - word_start);
            if (keyword == "if" || keyword == "while" || keyword == "for") {
                return false;
            }
        }
        if (!(word_char(c) || c == ')' || c == ']' || c == '.')) {
            return false;
        }
        // A word before it is an operand unless it is a keyword an expression may follow.
        std::size_t word = before;
        while (word > 0 && word_char(text[word - 1])) {
            --word;
        }
        const std::string_view previous = text.substr(word, before - word);
        if (previous == "return" || previous == "case" || previous == "else" || previous == "do") {
            return false;
        }
    }
    return true;
}

}  // namespace

std::vector<UnaryPlus> FindUnaryPluses(std::string_view text) {
    if (EveryPlusIsPlainlyBinary(text)) {
        return {};
    }
    const std::vector<SourceToken> tokens = CodeTokens(text);
    std::vector<UnaryPlus> pluses;
    // Whether tokens[i - 1] ends an operand, so that a `+` after it is binary.
    bool after_operand = false;
    // For each open `(`, whether it opens the condition of `if`, `while` or `for`: its `)` is
    // followed by a statement, where a `+` is unary.
    std::vector<bool> conditions;
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const SourceToken& token = tokens[i];
        const bool next_adjacent = i + 1 < tokens.size() && Adjacent(token, tokens[i + 1]);
        const std::string_view next = next_adjacent ? tokens[i + 1].text : std::string_view();
        if ((token.text == "+" || token.text == "-") && (next == token.text)) {
            // `++` or `--`: postfix after an operand (and still ending one), else prefix.
            ++i;
            continue;
        }
        if (token.text == "+" && next != "=" && !after_operand) {
            const bool number_follows =
                    i + 1 < tokens.size() &&
                    (std::isdigit(static_cast<unsigned char>(tokens[i + 1].text[0])) != 0 ||
                     (tokens[i + 1].text == "." && i + 2 < tokens.size() &&
                      std::isdigit(static_cast<unsigned char>(tokens[i + 2].text[0])) != 0));
            if (!number_follows) {
                pluses.push_back(
                        UnaryPlus{token.line, token.column,
                                  static_cast<std::size_t>(token.text.data() - text.data())});
            }
        }
        const bool keyword_before_expression = token.text == "return" || token.text == "case" ||
                                               token.text == "else" || token.text == "do";
        const bool name_or_number = std::isalnum(static_cast<unsigned char>(token.text[0])) != 0 ||
                                    token.text[0] == '_';
        bool closes_condition = false;
        if (token.text == "(") {
            const std::string_view before = i > 0 ? tokens[i - 1].text : std::string_view();
            conditions.push_back(before == "if" || before == "while" || before == "for");
        } else if (token.text == ")" && !conditions.empty()) {
            closes_condition = conditions.back();
            conditions.pop_back();
        }
        after_operand = (name_or_number && !keyword_before_expression) ||
                        (token.text == ")" && !closes_condition) || token.text == "]";
        // A number's exponent sign (1.5e+3) follows the "name" 5e, so it counts as binary,
        // which is right: it is no operator at all.
    }
    return pluses;
}

std::string NegateUnaryPluses(std::string_view text, const std::vector<UnaryPlus>& pluses) {
    std::string out;
    std::size_t copied = 0;
    for (const UnaryPlus& plus : pluses) {
        out.append(text.substr(copied, plus.offset - copied));
        out.append(" - ");
        copied = plus.offset + 1;
    }
    out.append(text.substr(copied));
    return out;
}

std::vector<Diagnostic> UnaryPlusErrors(const std::vector<Diagnostic>& negated_log,
                                        const std::vector<UnaryPlus>& pluses,
                                        const std::string& file) {
    std::vector<Diagnostic> errors;
    for (const Diagnostic& d : negated_log) {
        if (d.severity != Severity::kError || d.message.rfind("'-' :", 0) != 0 ||
            !Mentions(d, "wrong operand type")) {
            continue;
        }
        const auto plus = std::find_if(pluses.begin(), pluses.end(),
                                       [&](const UnaryPlus& p) { return p.line == d.line; });
        if (plus == pluses.end()) {
            continue;
        }
        // glslang names the operand's type: "... an operand of type <type> (or there is ...".
        std::string type = "this type";
        constexpr std::string_view kOfType = "operand of type";
        if (const std::size_t at = d.message.find(kOfType); at != std::string::npos) {
            const std::size_t start = d.message.find_first_not_of(' ', at + kOfType.size());
            const std::size_t end = d.message.find(" (or there", start);
            if (start != std::string::npos) {
                type = "'" + d.message.substr(start, end == std::string::npos ? end : end - start) +
                       "'";
            }
        }
        errors.push_back(MakeError(
                file, plus->line, plus->column,
                fmt::format("'+' : wrong operand type: unary '+' takes an integer or "
                            "floating-point scalar, vector or matrix, not {} (GLSL ES 1.00 §5.9, "
                            "GLSL ES 3.00 §5.9)",
                            type)));
    }
    return errors;
}

bool MacroMayHoldUnaryPlus(std::string_view text) {
    for (std::size_t at = text.find('#'); at != std::string_view::npos;
         at = text.find('#', at + 1)) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        if (line.find("define") != std::string_view::npos &&
            line.find('+') != std::string_view::npos) {
            return true;
        }
        at = end == text.size() ? end - 1 : end;
    }
    return false;
}

namespace {

// The words GLSL ES 3.00 §3.7 reserves for future use ("Using them will result in an error"),
// but for the four image...Shadow words (ImageShadowWords). glslang 12 refuses these itself; the
// whole list is checked so that the rule does not lean on which ones a glslang refuses.
const std::set<std::string_view>& Es300ReservedWords() {
    static const std::set<std::string_view> words = {"attribute",
                                                     "varying",
                                                     "coherent",
                                                     "restrict",
                                                     "readonly",
                                                     "writeonly",
                                                     "resource",
                                                     "atomic_uint",
                                                     "noperspective",
                                                     "patch",
                                                     "sample",
                                                     "subroutine",
                                                     "common",
                                                     "partition",
                                                     "active",
                                                     "asm",
                                                     "class",
                                                     "union",
                                                     "enum",
                                                     "typedef",
                                                     "template",
                                                     "this",
                                                     "goto",
                                                     "inline",
                                                     "noinline",
                                                     "volatile",
                                                     "public",
                                                     "static",
                                                     "extern",
                                                     "external",
                                                     "interface",
                                                     "long",
                                                     "short",
                                                     "double",
                                                     "half",
                                                     "fixed",
                                                     "unsigned",
                                                     "superp",
                                                     "input",
                                                     "output",
                                                     "hvec2",
                                                     "hvec3",
                                                     "hvec4",
                                                     "dvec2",
                                                     "dvec3",
                                                     "dvec4",
                                                     "fvec2",
                                                     "fvec3",
                                                     "fvec4",
                                                     "sampler3DRect",
                                                     "filter",
                                                     "image1D",
                                                     "image2D",
                                                     "image3D",
                                                     "imageCube",
                                                     "iimage1D",
                                                     "iimage2D",
                                                     "iimage3D",
                                                     "iimageCube",
                                                     "uimage1D",
                                                     "uimage2D",
                                                     "uimage3D",
                                                     "uimageCube",
                                                     "image1DArray",
                                                     "image2DArray",
                                                     "iimage1DArray",
                                                     "iimage2DArray",
                                                     "uimage1DArray",
                                                     "uimage2DArray",
                                                     "imageBuffer",
                                                     "iimageBuffer",
                                                     "uimageBuffer",
                                                     "sampler1D",
                                                     "sampler1DShadow",
                                                     "sampler1DArray",
                                                     "sampler1DArrayShadow",
                                                     "isampler1D",
                                                     "isampler1DArray",
                                                     "usampler1D",
                                                     "usampler1DArray",
                                                     "sampler2DRect",
                                                     "sampler2DRectShadow",
                                                     "isampler2DRect",
                                                     "usampler2DRect",
                                                     "samplerBuffer",
                                                     "isamplerBuffer",
                                                     "usamplerBuffer",
                                                     "sampler2DMS",
                                                     "isampler2DMS",
                                                     "usampler2DMS",
                                                     "sampler2DMSArray",
                                                     "isampler2DMSArray",
                                                     "usampler2DMSArray",
                                                     "sizeof",
                                                     "cast",
                                                     "namespace",
                                                     "using"};
    return words;
}

// image1DShadow, image2DShadow, image1DArrayShadow and image2DArrayShadow: on the §3.7 list
// too, but dEQP-GLES3 now expects a shader that names a variable after one of them to compile
// (allowed_keywords, VK-GL-CTS#431, 2023), and Mesa and glslang 12 accept them; the WebGL 2
// conformance suite still expects a failure (its copy of dEQP lists them in reserved_keywords).
const std::set<std::string_view>& ImageShadowWords() {
    static const std::set<std::string_view> words = {"image1DShadow", "image2DShadow",
                                                     "image1DArrayShadow", "image2DArrayShadow"};
    return words;
}

}  // namespace

bool MayUseEs300ReservedWord(std::string_view source) {
    for (const std::vector<SourceToken>& line : SourceTokenLines(source)) {
        for (const SourceToken& token : line) {
            if (token.identifier && (Es300ReservedWords().count(token.text) != 0 ||
                                     ImageShadowWords().count(token.text) != 0)) {
                return true;
            }
        }
    }
    return false;
}

std::vector<Diagnostic> CheckEs300ReservedWords(std::string_view preprocessed,
                                                std::string_view source, const std::string& file,
                                                bool webgl) {
    std::vector<Diagnostic> found;  // errors, and warnings for the image...Shadow words
    const std::vector<std::vector<SourceToken>> source_lines = SourceTokenLines(source);
    for (const std::vector<SourceToken>& line : SourceTokenLines(preprocessed)) {
        for (const SourceToken& token : line) {
            const bool reserved = token.identifier && Es300ReservedWords().count(token.text) != 0;
            const bool image_shadow = token.identifier && ImageShadowWords().count(token.text) != 0;
            if (!reserved && !image_shadow) {
                continue;
            }
            // The user's column, where the word stands on that line of the file; a word a macro
            // brought in keeps its column in the preprocessed text.
            int column = token.column;
            for (const std::vector<SourceToken>& written : source_lines) {
                const auto it = std::find_if(written.begin(), written.end(), [&](const auto& t) {
                    return t.line == token.line && t.text == token.text;
                });
                if (it != written.end()) {
                    column = it->column;
                    break;
                }
            }
            if (reserved || webgl) {
                found.push_back(MakeError(
                        file, token.line, column,
                        fmt::format("'{}' : reserved word; GLSL ES 3.00 reserves it for future "
                                    "use, and using it is an error (GLSL ES 3.00 §3.7{}); "
                                    "rename it",
                                    token.text, reserved ? "" : "; WebGL 2 keeps it reserved")));
            } else {
                Diagnostic warning = MakeError(
                        file, token.line, column,
                        fmt::format("'{}' : GLSL ES 3.00 §3.7 lists it as reserved, but ES 3.0 "
                                    "drivers accept it (dEQP-GLES3 expects it to compile) and "
                                    "WebGL 2 does not; rename it to run under WebGL 2",
                                    token.text));
                warning.severity = Severity::kWarning;
                found.push_back(std::move(warning));
            }
        }
    }
    return found;
}

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
                                   bool webgl, const std::set<int>& switch_lines) {
    bool any = false;
    for (const Diagnostic& d : diagnostics) {
        if (d.severity != Severity::kError) {
            continue;
        }
        const bool relaxable = (!webgl && Mentions(d, kDefinedFromMacro)) ||
                               (version == 100 && Mentions(d, kReservedMacro100)) ||
                               (version >= 300 && Mentions(d, kEmptyLastCase) &&
                                switch_lines.count(d.line) != 0) ||
                               (webgl && version == 100 && Mentions(d, kNonConstantGlobal));
        if (!relaxable) {
            return false;
        }
        any = true;
    }
    return any;
}

std::vector<Diagnostic> RestoreDemotedErrors(std::vector<Diagnostic> diagnostics,
                                             const std::set<int>& switch_lines, bool webgl1) {
    // GLSL ES 3.00 §6.2: the statement after the last label is there, glslang only lost it.
    diagnostics.erase(std::remove_if(diagnostics.begin(), diagnostics.end(),
                                     [&](const Diagnostic& d) {
                                         return d.severity == Severity::kWarning &&
                                                Mentions(d, kEmptyLastCase) &&
                                                switch_lines.count(d.line) != 0;
                                     }),
                      diagnostics.end());
    for (Diagnostic& d : diagnostics) {
        if (webgl1 && d.severity == Severity::kWarning && Mentions(d, kNonConstantGlobal)) {
            // WebGL 1.0 §6.33 asks for a warning; CheckWebGlGlobalInitializers checks the rest.
            d.message =
                    "global variable initializer is not a constant expression, as GLSL ES "
                    "1.00 §4.3 requires; WebGL 1 allows uniforms and other global variables "
                    "in it (WebGL 1.0 §6.33 \"GLSL ES Global Variable Initialization\"), "
                    "but other GLSL ES 1.00 compilers may refuse it";
            d.column = 0;
            continue;
        }
        // The reserved-name warning stays a warning: GLSL ES 3.00 §3.4 says defining or
        // undefining a macro name containing "__" "does not itself result in an error", and
        // glslang's strict verdict in 3.00 is this warning too; in 1.00 it is the relaxed form.
        if (d.severity == Severity::kWarning && !Mentions(d, kDefinedFromMacroRelaxed) &&
            !Mentions(d, kReservedMacroWarning)) {
            d.severity = Severity::kError;
        }
    }
    return diagnostics;
}

bool FailedOnlyForConstantExpressions(const std::vector<Diagnostic>& diagnostics) {
    static constexpr std::string_view kConstantWanted[] = {
            "global const initializers must be constant",
            "'non-constant initializer'",
            "'non-constant global initializer",
            "array size must be a constant integer expression",
    };
    bool any = false;
    for (const Diagnostic& d : diagnostics) {
        if (d.severity != Severity::kError) {
            continue;
        }
        if (std::none_of(std::begin(kConstantWanted), std::end(kConstantWanted),
                         [&](std::string_view text) { return Mentions(d, text); })) {
            return false;
        }
        any = true;
    }
    return any;
}

const char* const kEs100FoldingPreamble =
        "struct tp_es100_mat2 { highp mat2 m; };\n"
        "struct tp_es100_mat3 { highp mat3 m; };\n"
        "struct tp_es100_mat4 { highp mat4 m; };\n";

namespace {

// The rewriting of FoldEs100ConstantExpressions over the tokens of one text; ranges are token
// indices [begin, end).
class Es100ConstantFolder {
public:
    explicit Es100ConstantFolder(std::string_view text)
        : text_(text), tokens_(CodeTokens(text)), most_(4 * text.size() + 65536) {
        // Each bracket's partner, found once: looking for it anew at every bracket (and for the
        // commas of every group) took time quadratic in the nesting, 3 s for 40 KB of `((...`.
        partner_.assign(tokens_.size(), tokens_.size());
        std::vector<std::size_t> open;
        for (std::size_t i = 0; i < tokens_.size(); ++i) {
            const std::string_view t = tokens_[i].text;
            if (t == "(" || t == "[" || t == "{") {
                open.push_back(i);
            } else if (t == ")" || t == "]" || t == "}") {
                const std::string_view opener = open.empty() ? "" : tokens_[open.back()].text;
                if (opener != (t == ")" ? "(" : t == "]" ? "[" : "{")) {
                    balanced_ = false;
                    break;
                }
                partner_[open.back()] = i;
                open.pop_back();
            }
        }
        balanced_ = balanced_ && open.empty();
    }

    // The lines where a rewritten expression starts.
    std::set<int> lines;

    // The whole text rewritten; empty when nothing was.
    std::string Run() {
        if (tokens_.empty() || !balanced_) {  // glslang refuses such a text for its own reasons
            return {};
        }
        std::string out(text_.substr(0, Offset(0)));
        out += Rewrite(0, tokens_.size());
        out += text_.substr(End(tokens_.size() - 1));
        // Each matrixCompMult copies its operands N times and each sequence its operands twice:
        // nesting could grow without bound (Rewrite stops at `most_`).
        return changed_ && !too_long_ && out.size() <= most_ ? out : std::string();
    }

private:
    std::size_t Offset(std::size_t i) const {
        return static_cast<std::size_t>(tokens_[i].text.data() - text_.data());
    }
    std::size_t End(std::size_t i) const { return Offset(i) + tokens_[i].text.size(); }
    std::string_view Span(std::size_t begin, std::size_t end) const {
        return text_.substr(Offset(begin), End(end - 1) - Offset(begin));
    }

    // The ranges between the commas at the top level of [begin, end); none when one is empty.
    std::vector<std::pair<std::size_t, std::size_t>> Split(std::size_t begin,
                                                           std::size_t end) const {
        std::vector<std::pair<std::size_t, std::size_t>> parts;
        std::size_t start = begin;
        for (std::size_t i = begin; i <= end;) {
            if (i == end || tokens_[i].text == ",") {
                if (i == start) {
                    return {};
                }
                parts.emplace_back(start, i);
                start = i + 1;
                ++i;
                continue;
            }
            // A bracketed group holds no comma of this level: past it at once.
            i = partner_[i] < end ? partner_[i] + 1 : i + 1;
        }
        return parts;
    }

    // The N of the `matN` type of the expression [begin, end), 0 when its tokens do not say.
    int MatrixSize(std::size_t begin, std::size_t end) const {
        const std::string_view first = tokens_[begin].text;
        const bool call = begin + 1 < end && tokens_[begin + 1].text == "(";
        if (first.size() == 4 && first.substr(0, 3) == "mat" && first[3] >= '2' &&
            first[3] <= '4' && (call || begin + 1 == end)) {
            return first[3] - '0';
        }
        if (first == "matrixCompMult" && call) {
            const auto args = Split(begin + 2, Partner(begin + 1));
            return args.empty() ? 0 : MatrixSize(args[0].first, args[0].second);
        }
        if (first == "(" && Partner(begin) == end - 1 && begin + 2 < end) {
            return MatrixSize(begin + 1, end - 1);
        }
        const bool indexed =
                begin + 1 < end && tokens_[begin + 1].text == "[" && Partner(begin + 1) == end - 1;
        if (!tokens_[begin].identifier || !(begin + 1 == end || indexed)) {
            return 0;
        }
        // A name: the nearest declaration `matN name` before it (a variable, a parameter or an
        // array of matrices).
        for (std::size_t k = begin; k-- > 1;) {
            if (tokens_[k].text == first) {
                const std::string_view type = tokens_[k - 1].text;
                if (type.size() == 4 && type.substr(0, 3) == "mat" && type[3] >= '2' &&
                    type[3] <= '4') {
                    return type[3] - '0';
                }
            }
        }
        return 0;
    }

    // A `(` that groups an expression rather than opening a call or a constructor's arguments.
    bool Groups(std::size_t open) const {
        if (open == 0) {
            return true;
        }
        const std::string_view before = tokens_[open - 1].text;
        return !(tokens_[open - 1].identifier ||
                 std::isdigit(static_cast<unsigned char>(before[0])) != 0 || before == ")" ||
                 before == "]");
    }

    // Rewritten text of a part, on one line.
    std::string Flat(std::size_t begin, std::size_t end) {
        if (too_long_) {
            return {};
        }
        std::string part = Rewrite(begin, end);
        std::replace(part.begin(), part.end(), '\n', ' ');
        return part;
    }

    // The replacement of the tokens [begin, end], then the line breaks the original held.
    std::string KeepLines(std::string replacement, std::size_t begin, std::size_t end) const {
        const std::string_view original = Span(begin, end + 1);
        replacement.append(
                static_cast<std::size_t>(std::count(original.begin(), original.end(), '\n')), '\n');
        return replacement;
    }

    // Stops once any text it builds passes `most_` (too_long_): sequences nested 40 deep would
    // copy their innermost operand 2^40 times, and 22 deep took 363 MB before.
    std::string Rewrite(std::size_t begin, std::size_t end) {
        std::string out;
        for (std::size_t i = begin; i < end; ++i) {
            if (too_long_ || out.size() > most_) {
                too_long_ = true;
                return out;
            }
            if (i > begin) {
                out += text_.substr(End(i - 1), Offset(i) - End(i - 1));
            }
            const std::string_view token = tokens_[i].text;
            const bool call = i + 1 < end && tokens_[i + 1].text == "(";
            const std::size_t open = token == "(" ? i : i + 1;
            const std::size_t close =
                    token == "(" || (token == "matrixCompMult" && call) ? Partner(open) : end;
            // A directive inside the expression cannot be joined onto one line.
            if (close >= end || Span(i, close + 1).find('#') != std::string_view::npos) {
                out += token;
                continue;
            }
            const auto parts = Split(open + 1, close);
            if (token == "matrixCompMult" && parts.size() == 2) {
                const int n = std::max(MatrixSize(parts[0].first, parts[0].second),
                                       MatrixSize(parts[1].first, parts[1].second));
                if (n != 0) {
                    const std::string x = Flat(parts[0].first, parts[0].second);
                    const std::string y = Flat(parts[1].first, parts[1].second);
                    if (too_long_) {
                        return out;
                    }
                    std::string folded = fmt::format("mat{}(", n);
                    for (int column = 0; column < n; ++column) {
                        folded +=
                                fmt::format("{}tp_es100_mat{}({}).m[{}] * tp_es100_mat{}({}).m[{}]",
                                            column == 0 ? "" : ", ", n, x, column, n, y, column);
                    }
                    out += KeepLines(folded + ")", i, close);
                    changed_ = true;
                    lines.insert(tokens_[i].line);
                    i = close;
                    continue;
                }
            }
            if (token == "(" && parts.size() >= 2 && Groups(i)) {
                std::string folded = "(";
                for (std::size_t p = 0; p + 1 < parts.size(); ++p) {
                    const std::string operand = Flat(parts[p].first, parts[p].second);
                    folded += fmt::format("{}({}) == ({})", p == 0 ? "" : " && ", operand, operand);
                }
                const std::string value = Flat(parts.back().first, parts.back().second);
                if (too_long_) {
                    return out;
                }
                folded += fmt::format(" ? ({}) : ({}))", value, value);
                out += KeepLines(folded, i, close);
                changed_ = true;
                lines.insert(tokens_[i].line);
                i = close;
                continue;
            }
            out += token;
        }
        too_long_ = too_long_ || out.size() > most_;
        return out;
    }

    // The bracket that closes the one at `open`; tokens_.size() when it closes none.
    std::size_t Partner(std::size_t open) const { return partner_[open]; }

    std::string_view text_;
    std::vector<SourceToken> tokens_;
    std::vector<std::size_t> partner_;  // Partner of each token: tokens_.size() but for openers
    bool balanced_ = true;
    std::size_t most_;  // the longest text the rewrite may make
    bool changed_ = false;
    bool too_long_ = false;
};

}  // namespace

std::string FoldEs100ConstantExpressions(std::string_view preprocessed,
                                         std::set<int>* rewritten_lines) {
    if (preprocessed.find("matrixCompMult") == std::string_view::npos &&
        preprocessed.find(',') == std::string_view::npos) {
        return {};
    }
    Es100ConstantFolder folder(preprocessed);
    std::string folded = folder.Run();
    *rewritten_lines = std::move(folder.lines);
    return folded;
}

}  // namespace tidepool
