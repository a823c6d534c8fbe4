// Which of a stage's defines can change glslang's preprocessed text of a file, worked out from the
// file's conditional directives without running the preprocessor. The validator groups a
// configuration's stage slots by it, so that each distinct stage program is parsed once and no
// slot has to be preprocessed first to find its duplicates. Private to the compiler library.
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace tidepool {

/// Every identifier-like token of `text` outside its comments, read as glslang's preprocessor
/// reads comments, strings and lines (comments too when a `\` may join lines), and
/// kPastesTokens when the text holds `##`. The preprocessor drops comments before it expands
/// anything, so without token pasting a define can only change the preprocessed text if its
/// name is spelled out here; the shaders' header comments name every define they understand.
/// With `##` any define may: glslang refuses it for ES, and pastes all the same
/// (`CAT(ENABLE_,FOG)` reads ENABLE_FOG, whose definition changes the messages). Never fails.
std::set<std::string> MentionedIdentifiers(const std::string& text);

/// In MentionedIdentifiers' answer when the text pastes tokens, so that every define counts.
inline constexpr const char* kPastesTokens = "##";

/// Whether glslang takes `define` (NAME or NAME=VALUE, as DefinePreamble writes it) in its
/// preamble without a word, so that it can change a text only where the text spells NAME: NAME a
/// plain identifier of at most 1024 characters that glslang does not reserve (GL_..., "__",
/// `defined`), VALUE absent or a decimal number of at most nine digits each side of an optional
/// dot, with no leading zero. Any other define may break the preamble alone.
bool IsPlainDefine(const std::string& define);

/// Lines of a file, 1-based, first to last inclusive.
struct LineSpan {
    int first = 0;
    int last = 0;
    bool operator==(const LineSpan&) const = default;
};

/// The conditional structure of one shader file: its directives and the identifiers of its code,
/// read once, walked for each define list.
class DefineRelevance {
public:
    /// Reads `text` (a shader file as written). Never fails: a text the walk does not follow (a
    /// `##` anywhere outside comments, a `\` line continuation, a lone carriage return, a NUL, a
    /// form feed or vertical tab, an unbalanced or misordered #if, #if nested deeper than
    /// kMaxNesting, a directive that a block comment spanning lines precedes or carries on, a line
    /// starting with `##` or `# #`) makes Relevant answer nullopt for every define list.
    explicit DefineRelevance(const std::string& text);

    /// A digest of what decides glslang's preprocessed text of the file (and the preprocessor's
    /// messages) under `defines` (NAME or NAME=VALUE, as DefinePreamble writes them, with no
    /// other preamble): the lines glslang reads and the entries of `defines` those lines can see.
    /// Two define lists with the same answer give glslang the same preprocessed text, so the
    /// same parse. nullopt when the walk cannot tell: the text is beyond it, a define is not
    /// plain (IsPlainDefine) or names what another does, a define holds a word the ES 1.00
    /// keyword renaming renames, or an undecided block would read more definitions than the walk
    /// keeps (kMostKept).
    ///
    /// With `skipped`, also the lines of code (no directive) that the walk finds in a branch
    /// glslang skips under `defines`, in order; left empty when the answer is nullopt. A block
    /// whose branch the walk could not decide is never among them.
    std::optional<std::string> Relevant(const std::vector<std::string>& defines,
                                        std::vector<LineSpan>* skipped = nullptr) const;

private:
    enum class Kind { kCode, kIf, kIfdef, kIfndef, kElif, kElse, kEndif, kDefine, kUndef, kOther };
    struct Item {
        Kind kind = Kind::kCode;
        std::vector<std::string> condition;  // kIf, kElif: the expression's tokens
        int name = -1;           // kIfdef, kIfndef, kDefine, kUndef: the one name; -1 when not one
        bool plain = false;      // kDefine, kUndef: a line glslang takes without a word
        std::string body;        // kDefine: what the name stands for, spaces made single
        std::vector<int> names;  // every identifier of the line (of the lines, for kCode)
        std::size_t end = 0;     // kIf, kIfdef, kIfndef: the index of the matching kEndif
        LineSpan lines;          // where it is: one line, or for kCode the run of code lines
    };
    enum class Truth { kFalse, kTrue, kUnknown };

    class Evaluation;  // of one #if or #elif expression

    // Deeper #if nesting is not followed (glslang's own limit is 64, counted differently in
    // skipped text).
    static constexpr std::size_t kMaxNesting = 50;
    // The most definitions a walk records for its undecided blocks: a bound on its time and
    // memory whatever the text.
    static constexpr std::size_t kMostKept = 100000;

    int Id(const std::string& name);

    bool followed_ = true;  // false: the walk cannot follow this text
    std::vector<Item> items_;
    std::unordered_map<std::string, int> ids_;
    std::vector<std::string> names_;  // by id
    std::vector<Truth> undefined_;    // by id: each name's state when no define is given
    std::vector<bool> expanded_;      // by id: whether a line may expand the name as a macro
};

}  // namespace tidepool
