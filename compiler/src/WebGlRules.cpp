#include "WebGlRules.h"

#include <glslang/Include/ResourceLimits.h>
#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <set>

#include "GlslEsRules.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

bool IsNameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// GLSL ES 1.00 §3.1 and 3.00 §3.1: letters, digits, `_`, the punctuation below, space, tab,
// vertical tab, form feed, carriage return and line feed. A backslash is in the 3.00 set only
// (line continuation); glslang reports it in a 1.00 shader itself.
bool InSourceCharacterSet(char c) {
    if (IsNameChar(c)) {
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

std::string JoinContinuedLines(std::string_view text) {
    std::string joined;
    joined.reserve(text.size());
    int owed_newlines = 0;  // the newlines of joined lines, given back after the logical line
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '\\') {
            const std::size_t after = i + 1;
            const std::size_t crlf = text.compare(after, 2, "\r\n") == 0 ? 2 : 0;
            if (crlf != 0 || (after < text.size() && text[after] == '\n')) {
                i = after + (crlf != 0 ? crlf : 1) - 1;
                ++owed_newlines;
                continue;
            }
        }
        joined += ch;
        if (ch == '\n') {
            joined.append(static_cast<std::size_t>(owed_newlines), '\n');
            owed_newlines = 0;
        }
    }
    joined.append(static_cast<std::size_t>(owed_newlines), '\n');
    return joined;
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

// How many levels of structures `type` nests (0 for a type with no structure in it). Each struct
// is worked out once (`known`): one that holds another twice, that one a third twice and so on
// took 2^n steps for n levels, and 59 levels ran past the 20 s limit.
int StructNesting(const glslang::TType& type, std::map<const glslang::TTypeList*, int>& known) {
    if (!type.isStruct()) {
        return 0;
    }
    const glslang::TTypeList* members = type.getStruct();
    if (const auto found = known.find(members); found != known.end()) {
        return found->second;
    }
    int deepest = 0;
    for (const glslang::TTypeLoc& member : *members) {
        deepest = std::max(deepest, StructNesting(*member.type, known));
    }
    known.emplace(members, deepest + 1);
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
    std::map<const glslang::TTypeList*, int> nesting_of;
    for (const glslang::TType* type : collector.types) {
        const int nesting = StructNesting(*type, nesting_of);
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

namespace {

// The place of a type in Appendix A §7's packing order: mat4, mat2, vec4, mat3, vec3, vec2,
// scalars.
int PackingOrder(const PackingVariable& v) {
    if (v.rows > 1) {
        return v.rows == 4 ? 0 : v.rows == 2 ? 1 : 3;
    }
    return v.columns == 4 ? 2 : v.columns == 3 ? 4 : v.columns == 2 ? 5 : 6;
}

// Appends the packing variables of `type` (structures member by member, each element of an
// array of structures apart) named `name`, while `out` holds at most `most`: each takes a cell of
// the grid at least, so past its cells the packing fails whatever comes after (and structures
// that hold others twice over, level after level, have 2^n members for n levels).
void AddPackingVariables(const glslang::TType& type, const std::string& name, long long elements,
                         std::size_t most, std::vector<PackingVariable>* out) {
    constexpr long long kMostElements = 1LL << 40;  // far past any grid; no product overflows
    long long count = elements;
    if (type.isArray()) {
        const glslang::TArraySizes* sizes = type.getArraySizes();
        for (int d = 0; d < sizes->getNumDims(); ++d) {
            const long long size = std::max(sizes->getDimSize(d), 1);
            count = count > kMostElements / size ? kMostElements : count * size;
        }
    }
    if (type.isStruct()) {
        for (const glslang::TTypeLoc& member : *type.getStruct()) {
            if (out->size() > most) {
                return;
            }
            AddPackingVariables(*member.type,
                                fmt::format("{}.{}", name, member.type->getFieldName().c_str()),
                                count, most, out);
        }
        return;
    }
    if (out->size() > most) {
        return;
    }
    PackingVariable v;
    v.name = name;
    v.elements = count;
    if (type.isMatrix()) {
        v.rows = type.getMatrixCols();
        v.columns = v.rows == 2 ? 4 : v.rows;  // a mat2 takes two full rows
    } else {
        v.columns = type.isVector() ? type.getVectorSize() : 1;
    }
    out->push_back(std::move(v));
}

// The grid of Appendix A §7: one bit per column of each row, set when taken.
class PackingGrid {
public:
    explicit PackingGrid(int rows) : taken_(static_cast<std::size_t>(rows), 0U) {}
    int Rows() const { return static_cast<int>(taken_.size()); }
    void Take(int top, int count, int column, int width) {
        for (int r = top; r < top + count; ++r) {
            for (int c = column; c < column + width; ++c) {
                taken_[static_cast<std::size_t>(r)] |= 1U << c;
            }
        }
    }
    // The top row of the smallest gap of free rows in `column` that holds `count` rows, and its
    // size; {-1, 0} when there is none.
    std::pair<int, int> SmallestGap(int column, int count) const {
        std::pair<int, int> best{-1, 0};
        int start = -1;
        for (int r = 0; r <= Rows(); ++r) {
            const bool free =
                    r < Rows() && (taken_[static_cast<std::size_t>(r)] & (1U << column)) == 0;
            if (free && start < 0) {
                start = r;
            } else if (!free && start >= 0) {
                const int size = r - start;
                if (size >= count && (best.first < 0 || size < best.second)) {
                    best = {start, size};
                }
                start = -1;
            }
        }
        return best;
    }

private:
    std::vector<unsigned> taken_;
};

}  // namespace

std::optional<std::string> FirstUnpackedVariable(std::vector<PackingVariable> variables, int rows) {
    std::stable_sort(variables.begin(), variables.end(),
                     [](const PackingVariable& a, const PackingVariable& b) {
                         const int ao = PackingOrder(a);
                         const int bo = PackingOrder(b);
                         return ao != bo ? ao < bo : a.elements > b.elements;
                     });
    auto rows_of = [](const PackingVariable& v) {
        return std::min(v.elements * v.rows, 1LL << 40);
    };
    PackingGrid grid(rows);
    long long top = 0;  // the first row below the 4- and 3-component rows
    std::size_t i = 0;
    for (; i < variables.size() && variables[i].columns >= 3; ++i) {
        const long long needed = rows_of(variables[i]);
        if (top + needed > rows) {
            return variables[i].name;
        }
        grid.Take(static_cast<int>(top), static_cast<int>(needed), 0, variables[i].columns);
        top += needed;
    }
    // 2-component rows: columns 0-1 from the top down, else columns 2-3 from the bottom up.
    long long left = top;
    long long right = rows;
    for (; i < variables.size() && variables[i].columns == 2; ++i) {
        const long long needed = rows_of(variables[i]);
        if (left + needed <= rows) {
            grid.Take(static_cast<int>(left), static_cast<int>(needed), 0, 2);
            left += needed;
        } else if (right - needed >= top) {
            right -= needed;
            grid.Take(static_cast<int>(right), static_cast<int>(needed), 2, 2);
        } else {
            return variables[i].name;
        }
    }
    for (; i < variables.size(); ++i) {
        const long long needed = rows_of(variables[i]);
        int column = -1;
        std::pair<int, int> gap{-1, 0};
        for (int c = 0; c < 4 && needed <= rows; ++c) {
            const std::pair<int, int> found = grid.SmallestGap(c, static_cast<int>(needed));
            if (found.first >= 0 && (column < 0 || found.second < gap.second)) {
                column = c;
                gap = found;
            }
        }
        if (column < 0) {
            return variables[i].name;
        }
        grid.Take(gap.first, static_cast<int>(needed), column, 1);
    }
    return std::nullopt;
}

namespace {

// The packing check of WebGL 1.0 §6.26 over the statically used variables of `storage`.
std::vector<Diagnostic> CheckPacking(const glslang::TIntermediate& stage,
                                     glslang::TStorageQualifier storage, int rows,
                                     const std::string& file, std::string_view source,
                                     std::string_view what, std::string_view limit) {
    const std::map<std::string, glslang::TSourceLoc> used = StaticallyUsed(stage);
    std::vector<PackingVariable> variables;
    for (glslang::TIntermSymbol* symbol : LinkerObjects(stage)) {
        const glslang::TType& type = symbol->getType();
        const std::string name = symbol->getName().c_str();
        if (type.getQualifier().storage != storage || name.rfind("gl_", 0) == 0 ||
            type.getBasicType() == glslang::EbtSampler || used.count(name) == 0) {
            continue;
        }
        // One more than the grid's cells: enough for the packing to fail where it must.
        AddPackingVariables(type, name, 1, 4 * static_cast<std::size_t>(std::max(rows, 0)),
                            &variables);
    }
    const std::optional<std::string> unpacked = FirstUnpackedVariable(variables, rows);
    if (!unpacked) {
        return {};
    }
    const std::string declared = unpacked->substr(0, unpacked->find('.'));
    const auto [line, column] = FirstMention(source, declared);
    return {MakeError(file, line, column,
                      fmt::format("the {} do not fit in {} vectors ({}): '{}' finds no room by "
                                  "the packing of GLSL ES 1.00 Appendix A §7, which WebGL "
                                  "requires (WebGL 1.0 §6.26 \"Packing Restrictions for "
                                  "Uniforms and Varyings\")",
                                  what, rows, limit, *unpacked))};
}

}  // namespace

std::vector<Diagnostic> CheckWebGlUniformPacking(const glslang::TIntermediate& stage,
                                                 const TBuiltInResource& resources,
                                                 const std::string& file, std::string_view source) {
    const bool vertex = stage.getStage() == EShLangVertex;
    return CheckPacking(
            stage, glslang::EvqUniform,
            vertex ? resources.maxVertexUniformVectors : resources.maxFragmentUniformVectors, file,
            source, vertex ? "uniforms of the vertex shader" : "uniforms of the fragment shader",
            vertex ? "gl_MaxVertexUniformVectors" : "gl_MaxFragmentUniformVectors");
}

std::vector<Diagnostic> CheckWebGlVaryingPacking(const glslang::TIntermediate& fragment,
                                                 const TBuiltInResource& resources,
                                                 const std::string& file, std::string_view source) {
    return CheckPacking(fragment, glslang::EvqVaryingIn, resources.maxVaryingVectors, file, source,
                        "varyings the fragment shader reads", "gl_MaxVaryingVectors");
}

namespace {

// A type WebGL 2.0 §5.26 keeps away from `,` and `?:`.
std::string_view DisallowedOperandKind(const glslang::TType& type) {
    if (type.getBasicType() == glslang::EbtVoid) {
        return "void";
    }
    if (type.isArray()) {
        return "an array";
    }
    return type.isStruct() && type.containsArray() ? "a structure containing an array" : "";
}

class Webgl2OperatorChecker : public glslang::TIntermTraverser {
public:
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->getOp() != glslang::EOpComma) {
            return true;
        }
        for (TIntermNode* operand : node->getSequence()) {
            const glslang::TIntermTyped* typed = operand->getAsTyped();
            const std::string_view kind =
                    typed != nullptr ? DisallowedOperandKind(typed->getType()) : "";
            if (!kind.empty()) {
                Forbid(node->getLoc(), "sequence operator ','", kind);
                break;
            }
        }
        return true;
    }
    bool visitSelection(glslang::TVisit, glslang::TIntermSelection* node) override {
        const std::string_view kind = DisallowedOperandKind(node->getType());
        // A void selection is an if-statement (placed at its `if`) or a `?:` (at its `?`).
        if (!kind.empty() && (node->getType().getBasicType() != glslang::EbtVoid ||
                              IsQuestionMark(node->getLoc()))) {
            Forbid(node->getLoc(), "ternary operator '?:'", kind);
        }
        return true;
    }

    std::string file;
    std::string_view source;
    std::vector<Diagnostic> errors;

private:
    // True when `loc` (1-based line and column) is a `?` of `source`. The lines' starts are
    // found once, so a shader of many lines and many if-statements costs their sum, not product.
    bool IsQuestionMark(const glslang::TSourceLoc& loc) {
        if (line_starts_.empty()) {
            line_starts_.push_back(0);
            for (std::size_t at = source.find('\n'); at != std::string_view::npos;
                 at = source.find('\n', at + 1)) {
                line_starts_.push_back(at + 1);
            }
        }
        if (loc.line < 1 || static_cast<std::size_t>(loc.line) > line_starts_.size()) {
            return false;
        }
        const std::size_t line = static_cast<std::size_t>(loc.line) - 1;
        const std::size_t at =
                line_starts_[line] + static_cast<std::size_t>(std::max(loc.column, 1)) - 1;
        const std::size_t end =
                line + 1 < line_starts_.size() ? line_starts_[line + 1] : source.size();
        return at < end && source[at] == '?';
    }

    std::vector<std::size_t> line_starts_;

    void Forbid(const glslang::TSourceLoc& loc, std::string_view op, std::string_view kind) {
        errors.push_back(
                MakeError(file, loc.line, std::max(loc.column, 0),
                          fmt::format("the {} applied to {}: WebGL 2 forbids it (WebGL 2.0 §5.26 "
                                      "\"Disallowed variants of GLSL ES 3.00 operators\")",
                                      op, kind)));
    }
};

}  // namespace

std::vector<Diagnostic> CheckWebGl2Operators(const glslang::TIntermediate& stage,
                                             const std::string& file, std::string_view source) {
    Webgl2OperatorChecker checker;
    checker.file = file;
    checker.source = source;
    if (stage.getTreeRoot() != nullptr) {
        stage.getTreeRoot()->traverse(&checker);
    }
    return checker.errors;
}

}  // namespace tidepool
