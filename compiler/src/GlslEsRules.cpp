#include "GlslEsRules.h"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

namespace tidepool {
// ---- Source text -----------------------------------------------------------------------------

std::vector<std::vector<SourceToken>> SourceTokenLines(std::string_view text) {
    std::vector<std::vector<SourceToken>> lines(1);
    int line = 1;
    int column = 1;
    std::size_t i = 0;
    auto advance = [&](std::size_t n) {
        for (std::size_t k = 0; k < n && i < text.size(); ++k, ++i) {
            if (text[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
    };
    auto is_ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\\' && i + 1 < text.size() && text[i + 1] == '\n') {
            advance(2);
        } else if (c == '\n') {
            lines.emplace_back();
            advance(1);
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n') {
                advance(1);
            }
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            const std::size_t end = text.find("*/", i + 2);
            const std::size_t stop = end == std::string_view::npos ? text.size() : end + 2;
            while (i < stop) {
                advance(1);  // a block comment's newlines still end lines for line numbers
            }
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            advance(1);
        } else {
            std::size_t length = 1;
            if (is_ident(c)) {
                while (i + length < text.size() && is_ident(text[i + length])) {
                    ++length;
                }
            }
            const bool identifier = std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_';
            lines.back().push_back(SourceToken{text.substr(i, length), line, column, identifier});
            advance(length);
        }
    }
    return lines;
}

namespace {

// Adds and multiplies token counts, saturating at kMaxExpandedTokens + 1 so that nothing
// overflows and a 1000-level bomb costs no more to estimate than a small one.
long long CappedSum(long long a, long long b) {
    return std::min(a + b, kMaxExpandedTokens + 1);
}
long long CappedProduct(long long a, long long b) {
    return a == 0 || b == 0 ? 0 : a > (kMaxExpandedTokens + 1) / b ? kMaxExpandedTokens + 1 : a * b;
}

// The size of some tokens once expanded, as an affine function of the sizes of the arguments of
// the function-like macro they are the body of: constant + Σ per_param[p] × |argument p|. A
// function-like macro that uses its parameter twice doubles it, so `#define B(x) A(A(x))` over
// `#define A(x) x x` is 4 × |x|: nesting such macros 30 levels is 2^30 tokens, which this
// estimate sees without expanding anything.
struct Expansion {
    long long constant = 0;
    std::vector<long long> per_param;
};

// Object-like and function-like macros with their replacement lists; the expansion of each is
// memoised, so even a 1000-level bomb is estimated in linear time. The estimate follows the
// rules that matter for size (arguments are expanded before substitution, a macro is not
// expanded inside its own expansion, C99 §6.10.3.1 and §6.10.3.4) and ignores the rest; it is
// an upper estimate for the bombs that matter (repeated parameters and repeated names).
class MacroTable {
public:
    void Define(const std::vector<SourceToken>& directive) {
        // # define NAME [ ( params ) ] body
        if (directive.size() < 3 || !directive[2].identifier) {
            return;
        }
        Macro macro;
        std::size_t body = 3;
        if (directive.size() > 3 && directive[3].text == "(" &&
            directive[3].column ==
                    directive[2].column + static_cast<int>(directive[2].text.size())) {
            macro.function_like = true;
            while (body < directive.size() && directive[body].text != ")") {
                if (directive[body].identifier) {
                    macro.params.emplace_back(directive[body].text);
                }
                ++body;
            }
            ++body;
        }
        for (std::size_t k = body; k < directive.size(); ++k) {
            macro.body.push_back(directive[k].text);
        }
        macros_[std::string(directive[2].text)] = std::move(macro);
        expansions_.clear();
    }
    void Undefine(const std::vector<SourceToken>& directive) {
        if (directive.size() >= 3) {
            macros_.erase(std::string(directive[2].text));
            expansions_.clear();
        }
    }
    // Tokens that tokens[*at] stands for once expanded (1 for a non-macro), advancing *at past
    // the token and, for a function-like macro invoked there, past its arguments.
    long long SizeAt(const std::vector<std::string_view>& tokens, std::size_t* at) {
        return ExpandAt(tokens, at, {}).constant;
    }

private:
    struct Macro {
        bool function_like = false;
        std::vector<std::string> params;
        std::vector<std::string_view> body;
    };

    // The expansion of tokens[*at] (and of its arguments, when it invokes a function-like
    // macro) inside the body of a macro with parameters `params`.
    Expansion ExpandAt(const std::vector<std::string_view>& tokens, std::size_t* at,
                       const std::vector<std::string>& params) {
        const std::string_view token = tokens[*at];
        ++*at;
        Expansion result{0, std::vector<long long>(params.size(), 0)};
        // Each level of macros within macros, or of invocations within arguments, is a level
        // of recursion here (and in glslang): a file of 100,000 nested ones would overflow the
        // stack, so deeper nesting than any shader needs counts as too large.
        if (depth_ >= kMaxNesting) {
            result.constant = kMaxExpandedTokens + 1;
            return result;
        }
        ++depth_;
        const struct Leave {
            int& depth;
            ~Leave() { --depth; }
        } leave{depth_};
        if (const auto param = std::find(params.begin(), params.end(), token);
            param != params.end()) {
            result.per_param[static_cast<std::size_t>(param - params.begin())] = 1;
            return result;
        }
        const std::string name(token);
        const auto macro = macros_.find(name);
        const bool invoked = *at < tokens.size() && tokens[*at] == "(";
        if (macro == macros_.end() || expanding_.count(name) != 0 ||
            (macro->second.function_like && !invoked)) {
            result.constant = 1;  // not a macro, a name inside its own expansion, or no call
            return result;
        }
        const Expansion& own = Of(name, macro->second);
        if (!macro->second.function_like) {
            result.constant = own.constant;
            return result;
        }
        // The arguments: each is expanded, then copied once per use of its parameter.
        ++*at;  // (
        result.constant = own.constant;
        std::size_t arg = 0;
        int depth = 0;
        while (*at < tokens.size()) {
            const std::string_view next = tokens[*at];
            if (depth == 0 && (next == ")" || next == ",")) {
                ++*at;
                if (next == ")") {
                    break;
                }
                ++arg;
                continue;
            }
            depth += next == "(" ? 1 : next == ")" ? -1 : 0;
            const long long copies = arg < own.per_param.size() ? own.per_param[arg] : 0;
            const Expansion piece = ExpandAt(tokens, at, params);
            result.constant = CappedSum(result.constant, CappedProduct(copies, piece.constant));
            for (std::size_t p = 0; p < params.size(); ++p) {
                result.per_param[p] =
                        CappedSum(result.per_param[p], CappedProduct(copies, piece.per_param[p]));
            }
        }
        return result;
    }

    // The expansion of a macro's body in terms of its own parameters.
    const Expansion& Of(const std::string& name, const Macro& macro) {
        if (auto known = expansions_.find(name); known != expansions_.end()) {
            return known->second;
        }
        expanding_.insert(name);
        Expansion total{0, std::vector<long long>(macro.params.size(), 0)};
        for (std::size_t at = 0; at < macro.body.size();) {
            const Expansion piece = ExpandAt(macro.body, &at, macro.params);
            total.constant = CappedSum(total.constant, piece.constant);
            for (std::size_t p = 0; p < total.per_param.size(); ++p) {
                total.per_param[p] = CappedSum(total.per_param[p], piece.per_param[p]);
            }
        }
        expanding_.erase(name);
        return expansions_[name] = std::move(total);
    }

    static constexpr int kMaxNesting = 1000;

    std::unordered_map<std::string, Macro> macros_;
    std::unordered_map<std::string, Expansion> expansions_;
    std::set<std::string> expanding_;
    int depth_ = 0;
};

// The most members a structure may hold once the structures in it are expanded. glslang walks
// a structure's members anew wherever it asks what a type contains (TType::contains and the
// like), so structures that each hold the one before twice cost it 2^n steps: 22 levels took it
// 0.45 s and 368 MB, 28 ran past any limit. 2^16 is far past any real shader's structures.
constexpr long long kMaxStructMembers = 1LL << 16;

// The first structure declared in `tokens` (the code of a shader, no directive lines) that holds
// more than kMaxStructMembers members once the structures in it are expanded, or nothing. A member
// of a structure type declared before counts that structure's members, one of another type 1, each
// name in a declaration once (an array of structures is walked as one). What the scan does not
// follow (a structure declared inside another) counts 1: it may miss a bomb, never call a real
// shader one.
const SourceToken* FirstStructBomb(const std::vector<SourceToken>& tokens) {
    // Counts stop just past the bound, so that nothing overflows.
    auto sum = [](long long a, long long b) { return std::min(a + b, kMaxStructMembers + 1); };
    std::unordered_map<std::string_view, long long> members_of;
    for (std::size_t i = 0; i + 2 < tokens.size(); ++i) {
        if (tokens[i].text != "struct" || !tokens[i + 1].identifier || tokens[i + 2].text != "{") {
            continue;
        }
        long long members = 0;
        long long per_name = 1;  // of the declaration being read
        bool typed = false;      // its type has been read
        int depth = 0;
        std::size_t k = i + 3;
        for (; k < tokens.size(); ++k) {
            const std::string_view t = tokens[k].text;
            if (t == "{" || t == "(" || t == "[") {
                ++depth;
            } else if (t == ")" || t == "]" || (t == "}" && depth > 0)) {
                --depth;
            } else if (t == "}") {
                break;
            } else if (depth == 0 && (t == ";" || t == ",")) {
                members = sum(members, typed ? per_name : 0);
                if (t == ";") {
                    typed = false;
                    per_name = 1;
                }
            } else if (depth == 0 && !typed && tokens[k].identifier && t != "lowp" &&
                       t != "mediump" && t != "highp" && t != "precise") {
                const auto found = members_of.find(t);
                per_name = found != members_of.end() ? found->second : 1;
                typed = true;
            }
        }
        members = std::max(members, 1LL);
        members_of[tokens[i + 1].text] = members;
        if (members > kMaxStructMembers) {
            return &tokens[i + 1];
        }
        i = k;
    }
    return nullptr;
}

}  // namespace

std::vector<Diagnostic> CheckSourceText(std::string_view text, std::string_view preamble,
                                        const std::string& file) {
    std::vector<Diagnostic> errors;
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        const std::string_view before = text.substr(0, nul);
        const int line = 1 + static_cast<int>(std::count(before.begin(), before.end(), '\n'));
        const std::size_t line_start = before.rfind('\n');
        const int column = static_cast<int>(
                nul - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1);
        errors.push_back(MakeError(file, line, column,
                                   "NUL byte in the shader source; GLSL ES source is text "
                                   "(GLSL ES §3.1) and glslang would stop reading here"));
        return errors;
    }
    MacroTable macros;
    long long total = 0;
    // Tokens of the lines since the last directive: a macro's arguments may span lines.
    std::vector<SourceToken> run;
    // Adds up one run; false (with the error added) once the shader is too large.
    auto measure = [&](bool in_file) {
        std::vector<std::string_view> texts;
        texts.reserve(run.size());
        for (const SourceToken& token : run) {
            texts.push_back(token.text);
        }
        for (std::size_t at = 0; at < run.size();) {
            const SourceToken& token = run[at];
            const long long size = macros.SizeAt(texts, &at);
            total = CappedSum(total, size);
            if (size > kMaxExpandedTokens || total > kMaxExpandedTokens) {
                const std::string message =
                        size > kMaxExpandedTokens
                                ? fmt::format(
                                          "macro '{}' expands to more than {} tokens (a "
                                          "macro bomb); tidepool refuses shaders that large: "
                                          "{}",
                                          token.text, kMaxExpandedTokens, kTooLargeFix)
                                : fmt::format(
                                          "the shader has more than {} tokens once its macros "
                                          "are expanded; tidepool refuses shaders that large: "
                                          "{}",
                                          kMaxExpandedTokens, kTooLargeFix);
                errors.push_back(MakeError(file, in_file ? token.line : 0,
                                           in_file ? token.column : 0, message));
                return false;
            }
        }
        run.clear();
        return true;
    };
    for (const std::string_view part : {preamble, text}) {
        const bool in_file = part.data() == text.data();
        for (const std::vector<SourceToken>& line : SourceTokenLines(part)) {
            if (line.empty() || line[0].text != "#") {
                run.insert(run.end(), line.begin(), line.end());
                continue;
            }
            if (!measure(in_file)) {
                return errors;
            }
            if (line.size() >= 2 && line[1].text == "define") {
                macros.Define(line);
            } else if (line.size() >= 2 && line[1].text == "undef") {
                macros.Undefine(line);
            } else if (line.size() >= 3 && (line[1].text == "if" || line[1].text == "elif")) {
                // The preprocessor expands an #if's expression as it does code: a bomb there
                // took glslang 3.3 s at 22 levels and past the 20 s limit at 40. The name after
                // `defined` is not expanded.
                for (std::size_t i = 2; i < line.size(); ++i) {
                    if (line[i].text == "defined") {
                        const bool parenthesised = i + 1 < line.size() && line[i + 1].text == "(";
                        i += parenthesised ? 3 : 1;
                        continue;
                    }
                    run.push_back(line[i]);
                }
                if (!measure(in_file)) {
                    return errors;
                }
            }
        }
        if (!measure(in_file)) {
            return errors;
        }
    }
    std::vector<SourceToken> code;
    for (const std::vector<SourceToken>& line : SourceTokenLines(text)) {
        if (!line.empty() && line[0].text != "#") {
            code.insert(code.end(), line.begin(), line.end());
        }
    }
    if (const SourceToken* name = FirstStructBomb(code); name != nullptr) {
        errors.push_back(MakeError(
                file, name->line, name->column,
                fmt::format("struct '{}' holds more than {} members once the structures in it "
                            "are expanded, the most tidepool lets glslang walk (glslang walks a "
                            "structure's members anew for every question it asks of a type); "
                            "hold fewer structures in one another, or use arrays",
                            name->text, kMaxStructMembers)));
    }
    return errors;
}

// ---- Parsed stages ---------------------------------------------------------------------------

std::vector<glslang::TIntermSymbol*> LinkerObjects(const glslang::TIntermediate& stage) {
    std::vector<glslang::TIntermSymbol*> symbols;
    glslang::TIntermAggregate* root =
            stage.getTreeRoot() != nullptr ? stage.getTreeRoot()->getAsAggregate() : nullptr;
    if (root == nullptr) {
        return symbols;
    }
    for (TIntermNode* child : root->getSequence()) {
        glslang::TIntermAggregate* aggregate = child->getAsAggregate();
        if (aggregate == nullptr || aggregate->getOp() != glslang::EOpLinkerObjects) {
            continue;
        }
        for (TIntermNode* object : aggregate->getSequence()) {
            if (glslang::TIntermSymbol* symbol = object->getAsSymbolNode()) {
                symbols.push_back(symbol);
            }
        }
    }
    return symbols;
}

namespace {

// The symbols code reads or writes (linker objects are declarations, not uses), each with the
// place of its first use.
class UseCollector : public glslang::TIntermTraverser {
public:
    void visitSymbol(glslang::TIntermSymbol* symbol) override {
        used.emplace(symbol->getName().c_str(), symbol->getLoc());
    }
    std::map<std::string, glslang::TSourceLoc> used;
};

}  // namespace

std::map<std::string, glslang::TSourceLoc> StaticallyUsed(const glslang::TIntermediate& stage) {
    UseCollector collector;
    glslang::TIntermAggregate* root =
            stage.getTreeRoot() != nullptr ? stage.getTreeRoot()->getAsAggregate() : nullptr;
    if (root == nullptr) {
        return {};
    }
    for (TIntermNode* child : root->getSequence()) {
        glslang::TIntermAggregate* aggregate = child->getAsAggregate();
        if (aggregate == nullptr || aggregate->getOp() != glslang::EOpLinkerObjects) {
            child->traverse(&collector);
        }
    }
    return collector.used;
}

std::pair<int, int> FirstMention(std::string_view source, std::string_view name) {
    auto is_ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = source.find(name); at != std::string_view::npos;
         at = source.find(name, at + 1)) {
        const bool starts = at == 0 || !is_ident(source[at - 1]);
        const bool ends = at + name.size() >= source.size() || !is_ident(source[at + name.size()]);
        if (starts && ends) {
            const std::string_view before = source.substr(0, at);
            const std::size_t line_start = before.rfind('\n');
            const std::size_t column =
                    at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
            return {1 + static_cast<int>(std::count(before.begin(), before.end(), '\n')),
                    static_cast<int>(column)};
        }
    }
    return {0, 0};
}

namespace {

bool IsBuiltIn(const glslang::TIntermSymbol& symbol) {
    return std::string_view(symbol.getName().c_str()).rfind("gl_", 0) == 0;
}

// Counts of vectors and array elements stop growing here: far past any limit they are checked
// against, and products of two such counts still fit in a long long.
constexpr long long kCountCap = 1LL << 40;

long long CountSum(long long a, long long b) {
    return std::min(a + b, kCountCap);
}

long long CountProduct(long long a, long long b) {
    return (b != 0 && a > kCountCap / b) ? kCountCap : std::min(a * b, kCountCap);
}

// The elements of every dimension of an array type (1 for no array), at most kCountCap.
long long ElementsOf(const glslang::TType& type) {
    long long elements = 1;
    if (type.isArray()) {
        const glslang::TArraySizes* sizes = type.getArraySizes();
        for (int d = 0; d < sizes->getNumDims(); ++d) {
            elements = CountProduct(elements, std::max(sizes->getDimSize(d), 1));
        }
    }
    return elements;
}

// A count over a type's struct members, worked out once per struct: a struct may hold another
// twice, that one a third twice, and so on, so a walk that did each member anew would take 2^n
// steps for n nested structs (59 of them, in 2.5 KB of shader, ran past the 20 s limit).
class StructCounts {
public:
    // `per_struct(members, self)` counts one element of a struct; `self` counts a member type.
    using PerStruct = long long (*)(const glslang::TTypeList& members, StructCounts& self);
    explicit StructCounts(PerStruct per_struct) : per_struct_(per_struct) {}

    long long Of(const glslang::TTypeList& members) {
        if (const auto found = counted_.find(&members); found != counted_.end()) {
            return found->second;
        }
        const long long count = per_struct_(members, *this);
        counted_.emplace(&members, count);
        return count;
    }

private:
    PerStruct per_struct_;
    std::map<const glslang::TTypeList*, long long> counted_;
};

// Uniform vectors one declaration takes (GLSL ES 1.00 Appendix A §7 packs each array element
// and each matrix column into at least one vector; a struct counts one vector per member), at
// most kCountCap.
long long UniformVectors(const glslang::TType& type, StructCounts& structs) {
    long long per_element = 1;
    if (type.isMatrix()) {
        per_element = type.getMatrixCols();
    } else if (type.isStruct()) {
        per_element = structs.Of(*type.getStruct());
    }
    return CountProduct(per_element, ElementsOf(type));
}

long long UniformVectors(const glslang::TType& type) {
    StructCounts structs([](const glslang::TTypeList& members, StructCounts& self) {
        long long vectors = 0;
        for (const glslang::TTypeLoc& member : members) {
            vectors = CountSum(vectors, UniformVectors(*member.type, self));
        }
        return vectors;
    });
    return UniformVectors(type, structs);
}

// Array elements one declaration of `type` holds: every dimension, times the elements of each
// struct member for an array of structs (1 for a type with no array in it), at most kCountCap.
long long ArrayElements(const glslang::TType& type, StructCounts& structs) {
    const long long per_element = type.isStruct() ? structs.Of(*type.getStruct()) : 1;
    return CountProduct(per_element, ElementsOf(type));
}

long long ArrayElements(const glslang::TType& type) {
    StructCounts structs([](const glslang::TTypeList& members, StructCounts& self) {
        long long elements = 0;
        for (const glslang::TTypeLoc& member : members) {
            elements = CountSum(elements, ArrayElements(*member.type, self));
        }
        return std::max(elements, 1LL);
    });
    return ArrayElements(type, structs);
}

bool HasArray(const glslang::TType& type, StructCounts& structs) {
    return type.isArray() || (type.isStruct() && structs.Of(*type.getStruct()) != 0);
}

bool HasArray(const glslang::TType& type) {
    StructCounts structs([](const glslang::TTypeList& members, StructCounts& self) {
        return static_cast<long long>(std::any_of(
                members.begin(), members.end(),
                [&](const glslang::TTypeLoc& member) { return HasArray(*member.type, self); }));
    });
    return HasArray(type, structs);
}

// A count for a message: at kCountCap, "over" the largest count below it.
std::string CountText(long long count) {
    return count >= kCountCap ? fmt::format("over {}", kCountCap - 1) : std::to_string(count);
}

// Every symbol the tree mentions (declarations with initialisers, parameters, uses), once each,
// in the order first met.
class SymbolCollector : public glslang::TIntermTraverser {
public:
    void visitSymbol(glslang::TIntermSymbol* symbol) override {
        if (seen_.insert(symbol->getId()).second) {
            symbols.push_back(symbol);
        }
    }
    std::vector<glslang::TIntermSymbol*> symbols;

private:
    std::set<long long> seen_;
};

}  // namespace

std::vector<Diagnostic> CheckStageRules(const glslang::TIntermediate& stage,
                                        const TBuiltInResource& resources, const std::string& file,
                                        std::string_view source) {
    std::vector<Diagnostic> errors;
    // Arrays: globals are linker objects, and the tree holds every other declaration that
    // matters (an unused local without an initialiser costs nothing and leaves no trace).
    SymbolCollector symbols;
    if (stage.getTreeRoot() != nullptr) {
        stage.getTreeRoot()->traverse(&symbols);
    }
    std::set<std::string> reported;
    for (glslang::TIntermSymbol* symbol : symbols.symbols) {
        const glslang::TType& type = symbol->getType();
        const std::string name = symbol->getName().c_str();
        // A uniform has the tighter bound of the stage's uniform vectors, checked below.
        if (type.getQualifier().storage == glslang::EvqUniform || IsBuiltIn(*symbol) ||
            !HasArray(type) || reported.count(name) != 0) {
            continue;
        }
        const long long elements = ArrayElements(type);
        if (elements > kMaxArrayElements) {
            reported.insert(name);
            const auto [line, column] = FirstMention(source, name);
            errors.push_back(MakeError(
                    file, line, column,
                    fmt::format("'{}' holds {} array elements, more than the {} one declaration "
                                "may hold; no GPU gives a shader invocation that much memory",
                                name, CountText(elements), kMaxArrayElements)));
        }
    }
    const bool vertex = stage.getStage() == EShLangVertex;
    const long long limit =
            vertex ? resources.maxVertexUniformVectors : resources.maxFragmentUniformVectors;
    for (glslang::TIntermSymbol* symbol : LinkerObjects(stage)) {
        const glslang::TType& type = symbol->getType();
        if (type.getQualifier().storage != glslang::EvqUniform || IsBuiltIn(*symbol) ||
            type.getBasicType() == glslang::EbtSampler) {
            continue;
        }
        const long long vectors = UniformVectors(type);
        if (vectors > limit) {
            const auto [line, column] = FirstMention(source, symbol->getName().c_str());
            errors.push_back(MakeError(
                    file, line, column,
                    fmt::format("uniform '{}' needs {} uniform vectors, more than the {} a {} "
                                "shader has (gl_Max{}UniformVectors; GLSL ES 1.00 Appendix A "
                                "§7, GLSL ES 3.00 §4.3.5)",
                                symbol->getName().c_str(), CountText(vectors), limit,
                                vertex ? "vertex" : "fragment", vertex ? "Vertex" : "Fragment")));
        }
    }
    return errors;
}

std::vector<Diagnostic> CheckLinkRules(const glslang::TIntermediate& vertex,
                                       const std::string& vertex_file,
                                       const glslang::TIntermediate& fragment,
                                       const std::string& fragment_file) {
    std::vector<Diagnostic> errors;
    if (vertex.getVersion() != fragment.getVersion()) {
        errors.push_back(MakeError(
                fragment_file, 0, 0,
                fmt::format("cannot link a '#version {}' fragment shader with the "
                            "'#version {}' vertex shader {}; both stages of a program must use "
                            "the same GLSL ES version (GLSL ES 3.00 §3.3)",
                            fragment.getVersion() == 100 ? "100" : "300 es",
                            vertex.getVersion() == 100 ? "100" : "300 es", vertex_file)));
        return errors;
    }
    std::set<std::string> outputs;
    for (glslang::TIntermSymbol* symbol : LinkerObjects(vertex)) {
        if (symbol->getType().getQualifier().storage == glslang::EvqVaryingOut) {
            outputs.insert(symbol->getName().c_str());
        }
    }
    std::vector<std::string> undeclared;  // fragment inputs the vertex stage does not write
    for (glslang::TIntermSymbol* symbol : LinkerObjects(fragment)) {
        const std::string name = symbol->getName().c_str();
        if (symbol->getType().getQualifier().storage == glslang::EvqVaryingIn &&
            !IsBuiltIn(*symbol) && outputs.count(name) == 0) {
            undeclared.push_back(name);
        }
    }
    if (undeclared.empty()) {
        return errors;  // the usual case: no walk of the fragment tree for its uses
    }
    const std::map<std::string, glslang::TSourceLoc> used = StaticallyUsed(fragment);
    for (const std::string& name : undeclared) {
        const auto use = used.find(name);
        if (use == used.end()) {
            continue;
        }
        // Reported where the fragment stage first reads it: that is the use the rule forbids.
        errors.push_back(MakeError(
                fragment_file, use->second.line, std::max(use->second.column, 0),
                fmt::format("'{}' is read by the fragment shader but the vertex shader {} does "
                            "not declare it; declare it there as a {} (GLSL ES 1.00 §4.3.5, "
                            "GLSL ES 3.00 §4.3.4)",
                            name, vertex_file,
                            fragment.getVersion() == 100 ? "varying" : "'out' variable")));
    }
    return errors;
}

}  // namespace tidepool
