#include "WebGlRules.h"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <set>

#include "GlslEsRules.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

bool IsIdentifierChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// GLSL ES 1.00 §3.1 and 3.00 §3.1: letters, digits, `_`, the punctuation below, space, tab,
// vertical tab, form feed, carriage return and line feed. A backslash is in the 3.00 set only
// (line continuation); glslang reports it in a 1.00 shader itself.
bool InSourceCharacterSet(char c) {
    if (IsIdentifierChar(c)) {
        return true;
    }
    return c != '\0' && std::strchr(".+-/*%<>[](){}^|&~=!:;,?# \t\v\f\r\n\\", c) != nullptr;
}

// Line `line` (1-based) of `text`, "" when there is none.
std::string_view SourceLine(std::string_view text, int line) {
    std::size_t start = 0;
    for (int l = 1; l < line; ++l) {
        start = text.find('\n', start);
        if (start == std::string_view::npos) {
            return {};
        }
        ++start;
    }
    const std::size_t end = text.find('\n', start);
    return text.substr(start, end == std::string_view::npos ? text.size() - start : end - start);
}

std::string Shown(char c) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x21 && byte < 0x7f) {
        return fmt::format("'{}'", c);
    }
    return fmt::format("byte 0x{:02X}", byte);
}

}  // namespace

int MaxWebGlTokenLength(GlslTarget target) {
    return target == GlslTarget::kWebGl2 ? 1024 : 256;
}

std::vector<Diagnostic> CheckWebGlTokens(std::string_view text, GlslTarget target,
                                         const std::string& file) {
    std::vector<Diagnostic> errors;
    const std::size_t max_length = static_cast<std::size_t>(MaxWebGlTokenLength(target));
    for (const std::vector<SourceToken>& line : SourceTokenLines(text)) {
        for (const SourceToken& token : line) {
            if (token.text.size() > max_length) {
                errors.push_back(MakeError(
                        file, token.line, token.column,
                        fmt::format("a token of {} characters ('{}...'); {} accepts at most {} "
                                    "(WebGL 1.0 §6.20 \"Maximum GLSL Token Size\"{})",
                                    token.text.size(), token.text.substr(0, 16), TargetName(target),
                                    max_length,
                                    target == GlslTarget::kWebGl2 ? "; GLSL ES 3.00 §3.8" : "")));
            } else if (token.identifier && (token.text.rfind("webgl_", 0) == 0 ||
                                            token.text.rfind("_webgl_", 0) == 0)) {
                errors.push_back(MakeError(
                        file, token.line, token.column,
                        fmt::format("'{}': identifiers starting with 'webgl_' or '_webgl_' are "
                                    "reserved for use by WebGL (WebGL 1.0 §6.17 \"GLSL "
                                    "Constructs\"); rename it",
                                    token.text)));
            }
        }
    }
    return errors;
}

std::vector<Diagnostic> CheckWebGlCharacters(std::string_view preprocessed, std::string_view source,
                                             const std::string& file) {
    std::vector<Diagnostic> errors;
    // The user's lines, to find the character's column in what the user wrote.
    std::vector<std::string_view> source_lines;
    for (std::size_t start = 0; start <= source.size();) {
        const std::size_t end = std::min(source.find('\n', start), source.size());
        source_lines.push_back(source.substr(start, end - start));
        start = end + 1;
    }
    int line = 1;
    for (std::size_t i = 0; i < preprocessed.size(); ++i) {
        const char c = preprocessed[i];
        if (c == '\n') {
            ++line;
            continue;
        }
        if (InSourceCharacterSet(c)) {
            continue;
        }
        int column = 0;
        if (line >= 1 && static_cast<std::size_t>(line) <= source_lines.size()) {
            const std::size_t at = source_lines[static_cast<std::size_t>(line) - 1].find(c);
            column = at == std::string_view::npos ? 0 : static_cast<int>(at) + 1;
        }
        errors.push_back(MakeError(
                file, line, column,
                fmt::format("{} is outside the GLSL ES source character set (GLSL ES §3.1); "
                            "WebGL accepts it only in comments and in blocks the preprocessor "
                            "leaves out (WebGL 1.0 §6.21)",
                            Shown(c))));
        // One message per line is enough: the rest of a UTF-8 sequence is the same mistake.
        while (i + 1 < preprocessed.size() && preprocessed[i + 1] != '\n') {
            ++i;
        }
    }
    return errors;
}

std::vector<Diagnostic> CheckWebGl2BlockLayouts(std::string_view preprocessed,
                                                std::string_view source, const std::string& file) {
    std::vector<Diagnostic> errors;
    std::vector<SourceToken> tokens;
    for (const std::vector<SourceToken>& line : SourceTokenLines(preprocessed)) {
        if (line.empty() || line[0].text != "#") {
            tokens.insert(tokens.end(), line.begin(), line.end());
        }
    }
    for (std::size_t i = 0; i + 1 < tokens.size(); ++i) {
        if (tokens[i].text != "layout" || tokens[i + 1].text != "(") {
            continue;
        }
        for (std::size_t k = i + 2; k < tokens.size() && tokens[k].text != ")"; ++k) {
            if (tokens[k].text != "shared" && tokens[k].text != "packed") {
                continue;
            }
            const auto [row, column] =
                    FirstMention(SourceLine(source, tokens[k].line), tokens[k].text);
            errors.push_back(MakeError(
                    file, tokens[k].line, row == 0 ? 0 : column,
                    fmt::format("layout qualifier '{}': WebGL 2 supports only the std140 layout "
                                "for uniform blocks (WebGL 2.0 \"Only std140 layout supported in "
                                "uniform blocks\"); use layout(std140) or leave the layout out",
                                tokens[k].text)));
        }
    }
    return errors;
}

namespace {

// How many levels of structures `type` nests (0 for a type with no structure in it).
int StructNesting(const glslang::TType& type) {
    if (!type.isStruct()) {
        return 0;
    }
    int deepest = 0;
    for (const glslang::TTypeLoc& member : *type.getStruct()) {
        deepest = std::max(deepest, StructNesting(*member.type));
    }
    return deepest + 1;
}

// Every structure type the tree's symbols, constructors, calls and functions have.
class StructTypeCollector : public glslang::TIntermTraverser {
public:
    void visitSymbol(glslang::TIntermSymbol* node) override { Note(node->getType()); }
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        Note(node->getType());
        return true;
    }
    std::vector<const glslang::TType*> types;

private:
    void Note(const glslang::TType& type) {
        if (type.isStruct()) {
            types.push_back(&type);
        }
    }
};

}  // namespace

std::vector<Diagnostic> CheckWebGlStructNesting(const glslang::TIntermediate& stage,
                                                const std::string& file, std::string_view source) {
    std::vector<Diagnostic> errors;
    if (stage.getTreeRoot() == nullptr) {
        return errors;
    }
    StructTypeCollector collector;
    stage.getTreeRoot()->traverse(&collector);
    std::set<std::string> reported;
    for (const glslang::TType* type : collector.types) {
        const int nesting = StructNesting(*type);
        const std::string name = type->getTypeName().c_str();
        if (nesting <= kMaxWebGlStructNesting || !reported.insert(name).second) {
            continue;
        }
        const auto [line, column] = FirstMention(source, name);
        errors.push_back(MakeError(
                file, line, column,
                fmt::format("struct '{}' nests structures {} levels deep; WebGL allows at most {} "
                            "(WebGL 1.0 §6.22 \"Maximum Nesting of Structures\")",
                            name, nesting, kMaxWebGlStructNesting)));
    }
    return errors;
}

namespace {

// What a WebGL 1 global initializer may not use (WebGL 1.0 §6.33), each with its place.
class GlobalInitializerChecker : public glslang::TIntermTraverser {
public:
    void visitSymbol(glslang::TIntermSymbol* node) override {
        const glslang::TStorageQualifier storage = node->getType().getQualifier().storage;
        const std::string name = node->getName().c_str();
        const bool built_in = name.rfind("gl_", 0) == 0;
        if (storage == glslang::EvqConst ||
            (!built_in && (storage == glslang::EvqGlobal || storage == glslang::EvqUniform))) {
            return;
        }
        const char* what = built_in                                     ? "the built-in variable"
                           : storage == glslang::EvqVaryingIn && vertex ? "the attribute"
                                                                        : "the varying";
        Forbid(node->getLoc(), fmt::format("{} '{}'", what, name));
    }
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->isTexture()) {
            Forbid(node->getLoc(), "a texture lookup");
        } else if (node->getOp() == glslang::EOpFunctionCall) {
            Forbid(node->getLoc(), fmt::format("the user-defined function '{}'",
                                               PlainFunctionName(node->getName().c_str())));
        }
        return true;
    }
    bool visitBinary(glslang::TVisit, glslang::TIntermBinary* node) override {
        if (node->getOp() >= glslang::EOpAssign && node->getOp() <= glslang::EOpRightShiftAssign) {
            Forbid(node->getLoc(), "an assignment");
        }
        return true;
    }
    bool visitUnary(glslang::TVisit, glslang::TIntermUnary* node) override {
        if (node->getOp() >= glslang::EOpPostIncrement &&
            node->getOp() <= glslang::EOpPreDecrement) {
            Forbid(node->getLoc(), "an increment or decrement");
        }
        return true;
    }

    bool vertex = false;
    std::vector<std::pair<glslang::TSourceLoc, std::string>> forbidden;

private:
    static std::string PlainFunctionName(const std::string& mangled) {
        return mangled.substr(0, mangled.find('('));
    }
    void Forbid(const glslang::TSourceLoc& loc, std::string what) {
        forbidden.emplace_back(loc, std::move(what));
    }
};

}  // namespace

std::vector<Diagnostic> CheckWebGlGlobalInitializers(const glslang::TIntermediate& stage,
                                                     const std::string& file) {
    std::vector<Diagnostic> errors;
    glslang::TIntermAggregate* root =
            stage.getTreeRoot() != nullptr ? stage.getTreeRoot()->getAsAggregate() : nullptr;
    if (root == nullptr) {
        return errors;
    }
    // glslang keeps each global declaration with an initializer as a sequence of assignments
    // beside the function definitions.
    for (TIntermNode* child : root->getSequence()) {
        glslang::TIntermAggregate* sequence = child->getAsAggregate();
        if (sequence == nullptr || sequence->getOp() != glslang::EOpSequence) {
            continue;
        }
        for (TIntermNode* node : sequence->getSequence()) {
            glslang::TIntermBinary* assign = node->getAsBinaryNode();
            if (assign == nullptr || assign->getOp() != glslang::EOpAssign ||
                assign->getLeft()->getAsSymbolNode() == nullptr) {
                continue;
            }
            GlobalInitializerChecker checker;
            checker.vertex = stage.getStage() == EShLangVertex;
            assign->getRight()->traverse(&checker);
            const std::string name = assign->getLeft()->getAsSymbolNode()->getName().c_str();
            for (const auto& [loc, what] : checker.forbidden) {
                errors.push_back(MakeError(
                        file, loc.line, std::max(loc.column, 0),
                        fmt::format("the initializer of the global variable '{}' uses {}; "
                                    "WebGL 1 allows only constant expressions, uniforms and "
                                    "other global variables there (WebGL 1.0 §6.33 \"GLSL ES "
                                    "Global Variable Initialization\")",
                                    name, what)));
            }
        }
    }
    return errors;
}

}  // namespace tidepool
