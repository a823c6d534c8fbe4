#include "DefineRelevance.h"

#include "tidepool/SourceAssembler.h"
#include "tidepool/base/Sha256.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string_view>

#include "KeywordRenaming.h"

namespace tidepool {
namespace {

bool IsIdentifierStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_';
}

bool IsIdentifierPart(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

bool IsIdentifier(std::string_view word) {
    return !word.empty() && IsIdentifierStart(word[0]) &&
           std::all_of(word.begin(), word.end(), IsIdentifierPart);
}

// Names glslang may define itself: GLSL ES reserves every macro name that starts with "GL_" or
// holds "__" (1.00 and 3.00 §3.4), and glslang's own (GL_ES, GL_FRAGMENT_PRECISION_HIGH, the
// extensions' names, __VERSION__, __LINE__, __FILE__) are all of that form. The walk does not
// know which of them are defined for a stage, so a condition on one is undecided.
bool IsReserved(std::string_view name) {
    return name.substr(0, 3) == "GL_" || name.find("__") != std::string_view::npos ||
           name == "defined";  // refused as a macro name, and an operator in #if
}

// One line of the text with its comments gone, and whether a block comment that began on an
// earlier line ends on it (a `#` after it may or may not start a directive for glslang).
struct Line {
    std::string text;
    bool after_open_comment = false;
    bool opens_comment = false;  // a block comment starts on it and ends on a later line
};

// The text's lines without comments, as glslang's preprocessor reads them: a comment is one
// space and a block comment's line breaks still end lines; a `"` starts a string that runs to the
// next `"` or the end of the line, in which `//` and `/*` start nothing (GLSL has no strings, but
// glslang's preprocessor scans them, in skipped text too); `\r\n` and a lone `\r` end a line.
std::vector<Line> LinesWithoutComments(const std::string& text) {
    std::vector<Line> lines(1);
    auto line_end = [&](std::size_t i) {
        return text[i] == '\n' ||
               (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
    };
    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && !line_end(i)) {
                ++i;
            }
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            lines.back().text += ' ';
            i += 2;
            while (i < text.size() &&
                   !(text[i] == '*' && i + 1 < text.size() && text[i + 1] == '/')) {
                if (line_end(i)) {
                    lines.back().opens_comment = true;
                    lines.push_back(Line{{}, true});
                }
                ++i;
            }
            i = std::min(i + 2, text.size());
        } else if (c == '"') {
            do {
                lines.back().text += text[i++];
            } while (i < text.size() && text[i] != '"' && !line_end(i));
            if (i < text.size() && text[i] == '"') {
                lines.back().text += text[i++];
            }
        } else if (line_end(i)) {
            lines.emplace_back();
            ++i;
        } else {
            lines.back().text += c;
            ++i;
        }
    }
    return lines;
}

// The preprocessing tokens of a line: identifiers, numbers and punctuation, the two-character
// operators of an #if expression kept whole. A number is its digits and dots only, so a letter
// after it starts a name (`10A` is 10 and A to glslang); `1.0e5` then holds a name `e5` too,
// which only makes the walk count one more name.
std::vector<std::string> Tokens(std::string_view line) {
    std::vector<std::string> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        const char c = line[i];
        const std::size_t start = i;
        if (std::isspace(static_cast<unsigned char>(c)) != 0) {
            ++i;
            continue;
        }
        if (IsIdentifierStart(c)) {
            while (i < line.size() && IsIdentifierPart(line[i])) {
                ++i;
            }
        } else if (std::isdigit(static_cast<unsigned char>(c)) != 0 ||
                   (c == '.' && i + 1 < line.size() &&
                    std::isdigit(static_cast<unsigned char>(line[i + 1])) != 0)) {
            while (i < line.size() &&
                   (std::isdigit(static_cast<unsigned char>(line[i])) != 0 || line[i] == '.')) {
                ++i;
            }
        } else {
            static constexpr std::string_view kPairs[] = {
                    "&&", "||", "==", "!=", "<=", ">=", "<<", ">>", "##"};
            const std::string_view two = line.substr(i, 2);
            i += std::find(std::begin(kPairs), std::end(kPairs), two) != std::end(kPairs)
                         ? std::size_t{2}
                         : std::size_t{1};
        }
        tokens.emplace_back(line.substr(start, i - start));
    }
    return tokens;
}

}  // namespace

bool IsPlainDefine(const std::string& define) {
    // glslang refuses a token over 1024 characters (MaxTokenLength).
    constexpr std::size_t kLongestName = 1024;
    const std::size_t equals = define.find('=');
    const std::string_view name = std::string_view(define).substr(0, equals);
    if (!IsIdentifier(name) || IsReserved(name) || name.size() > kLongestName) {
        return false;
    }
    if (equals == std::string::npos) {
        return true;
    }
    const std::string_view value = std::string_view(define).substr(equals + 1);
    // A number glslang reads without a word: an integer below 2^31 with no leading zero (`08` is
    // a bad octal literal, 2^32 too big), or such an integer, a dot and at most nine digits.
    auto integer = [](std::string_view digits) {
        return !digits.empty() && digits.size() <= 9 && (digits == "0" || digits[0] != '0') &&
               std::all_of(digits.begin(), digits.end(),
                           [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
    };
    const std::size_t dot = value.find('.');
    if (dot == std::string_view::npos) {
        return integer(value);
    }
    const std::string_view fraction = value.substr(dot + 1);
    return integer(value.substr(0, dot)) && !fraction.empty() && fraction.size() <= 9 &&
           std::all_of(fraction.begin(), fraction.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

std::set<std::string> MentionedIdentifiers(const std::string& text) {
    std::set<std::string> names;
    // A `\` line continuation (ES 3.00) may join `*` and `/` into the end of a comment, so with
    // one anywhere the comments are read as code: more names, never fewer.
    const std::vector<Line> lines = text.find('\\') == std::string::npos
                                            ? LinesWithoutComments(text)
                                            : std::vector<Line>{Line{text, false}};
    for (const Line& line : lines) {
        for (std::string& token : Tokens(line.text)) {
            if (IsIdentifierStart(token[0])) {
                names.insert(std::move(token));
            } else if (token == kPastesTokens) {
                names.insert(kPastesTokens);
            }
        }
    }
    return names;
}

int DefineRelevance::Id(const std::string& name) {
    const auto [it, inserted] = ids_.emplace(name, static_cast<int>(names_.size()));
    if (inserted) {
        names_.push_back(name);
    }
    return it->second;
}

DefineRelevance::DefineRelevance(const std::string& text) {
    // A `\` line continuation can join a directive to the next line (GLSL ES 3.00 §3.2); the walk
    // reads line by line, so it does not follow such a text at all.
    if (text.find('\\') != std::string::npos) {
        followed_ = false;
        return;
    }
    // glslang reads a text only up to a NUL. A lone `\r` ends a line for glslang; whether `\n\r`
    // is one line end or two is not worth the walk's guess either. A form feed or vertical tab is
    // no white space to glslang's preprocessor, as it is to the walk's reading.
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\0' || text[i] == '\f' || text[i] == '\v' ||
            (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) {
            followed_ = false;
            return;
        }
    }
    std::vector<std::size_t> open;  // the kIf, kIfdef or kIfndef items not yet ended
    std::vector<bool> had_else;     // for each of them, whether its #else came
    int line_number = 0;
    for (const Line& line : LinesWithoutComments(text)) {
        ++line_number;
        std::vector<std::string> tokens = Tokens(line.text);
        if (tokens.empty()) {
            continue;
        }
        Item item;
        item.lines = LineSpan{line_number, line_number};
        // A directive's own word (`define`, `ifdef`) is no name it reads.
        const std::size_t first_name = tokens[0] == "#" ? 2 : 0;
        for (std::size_t t = first_name; t < tokens.size(); ++t) {
            if (IsIdentifierStart(tokens[t][0])) {
                item.names.push_back(Id(tokens[t]));
            }
        }
        // Pasting makes names the text never spells (`CAT(ENABLE_,FOG)`): anywhere on a line,
        // not only at its start (`## endif`), the walk cannot tell which defines matter.
        if (std::find(tokens.begin(), tokens.end(), kPastesTokens) != tokens.end()) {
            followed_ = false;
            return;
        }
        if (tokens[0] != "#") {
            if (!items_.empty() && items_.back().kind == Kind::kCode) {
                std::vector<int>& names = items_.back().names;
                names.insert(names.end(), item.names.begin(), item.names.end());
                items_.back().lines.last = line_number;
            } else {
                items_.push_back(std::move(item));
            }
            continue;
        }
        // glslang reads a directive on through a block comment's line breaks, and in skipped
        // text takes a second `#` (`##endif`) for the directive's own: texts the walk does not
        // follow.
        if (line.after_open_comment || line.opens_comment ||
            (tokens.size() > 1 && tokens[1][0] == '#')) {
            followed_ = false;
            return;
        }
        const std::string directive = tokens.size() > 1 ? tokens[1] : "";
        const std::vector<std::string> rest(
                tokens.begin() +
                        std::min<std::ptrdiff_t>(2, static_cast<std::ptrdiff_t>(tokens.size())),
                tokens.end());
        const bool one_name = rest.size() == 1 && IsIdentifier(rest[0]);
        if (directive == "if" || directive == "ifdef" || directive == "ifndef") {
            item.kind = directive == "if" ? Kind::kIf
                                          : (directive == "ifdef" ? Kind::kIfdef : Kind::kIfndef);
            item.condition = rest;
            item.name = item.kind != Kind::kIf && one_name ? Id(rest[0]) : -1;
            open.push_back(items_.size());
            had_else.push_back(false);
            // glslang limits the nesting of #if, counting skipped text otherwise than read text:
            // past a depth well inside its limit the walk gives up rather than model that.
            if (open.size() > kMaxNesting) {
                followed_ = false;
                return;
            }
        } else if (directive == "elif" || directive == "else" || directive == "endif") {
            if (open.empty() || (directive != "endif" && had_else.back())) {
                followed_ = false;  // glslang refuses it; the walk does not guess past the error
                return;
            }
            if (directive == "elif") {
                item.kind = Kind::kElif;
                item.condition = rest;
            } else if (directive == "else") {
                item.kind = Kind::kElse;
                had_else.back() = true;
            } else {
                item.kind = Kind::kEndif;
                items_[open.back()].end = items_.size();
                open.pop_back();
                had_else.pop_back();
            }
        } else if (directive == "define" || directive == "undef") {
            item.kind = directive == "define" ? Kind::kDefine : Kind::kUndef;
            item.name = !rest.empty() && IsIdentifier(rest[0]) ? Id(rest[0]) : -1;
            // A line glslang takes without a word: an object-like #define without `#` or `##` in
            // its body (a function-like one's parameters may be refused), an #undef of one name;
            // neither of a name glslang reserves.
            const bool body_has_hash =
                    std::any_of(rest.begin(), rest.end(),
                                [](const std::string& t) { return t == "#" || t == "##"; });
            item.plain = item.name >= 0 && !IsReserved(rest[0]) &&
                         (item.kind == Kind::kDefine
                                  ? (rest.size() == 1 || rest[1] != "(") && !body_has_hash
                                  : rest.size() == 1);
            if (item.kind == Kind::kDefine && item.name >= 0) {
                // The body as written, each run of spaces one space: two bodies alike so are one
                // token list to glslang, which takes such a redefinition without a word. A name
                // not followed by a space (`#define X-1`) gets a warning and defines nothing; a
                // string in the body would lose its spaces here.
                const std::size_t after_name =
                        line.text.find(rest[0], line.text.find("define") + 6) + rest[0].size();
                item.plain = item.plain &&
                             (after_name == line.text.size() || line.text[after_name] == ' ' ||
                              line.text[after_name] == '\t') &&
                             line.text.find('"') == std::string::npos;
                std::istringstream words(line.text.substr(after_name));
                for (std::string word; words >> word;) {
                    item.body += (item.body.empty() ? "" : " ") + word;
                }
            }
        } else {
            item.kind = Kind::kOther;  // #version, #extension, #pragma, #line, #error, `#` alone
        }
        items_.push_back(std::move(item));
    }
    if (!open.empty()) {
        followed_ = false;
    }
    for (const std::string& name : names_) {
        undefined_.push_back(IsReserved(name) ? Truth::kUnknown : Truth::kFalse);
    }
    expanded_.assign(names_.size(), false);
    for (const Item& item : items_) {
        const bool expands =
                item.kind == Kind::kCode || item.kind == Kind::kOther || item.kind == Kind::kDefine;
        // A #define's first name is the one it defines; the rest are its body's.
        const std::size_t first = item.kind == Kind::kDefine && item.name >= 0 ? 1 : 0;
        for (std::size_t k = first; expands && k < item.names.size(); ++k) {
            expanded_[static_cast<std::size_t>(item.names[k])] = true;
        }
    }
}

// A recursive descent over `defined`, `!`, `&&`, `||`, parentheses and decimal integers, in three
// values; anything else (a macro, a comparison) is undecided, and so is the whole expression.
class DefineRelevance::Evaluation {
public:
    Evaluation(const DefineRelevance& file, const std::vector<std::string>& tokens,
               const std::vector<Truth>& defined)
        : file_(file), tokens_(tokens), defined_(defined) {}

    Truth Run() {
        const Truth truth = tokens_.empty() ? Truth::kUnknown : Disjunction();
        return malformed_ || at_ != tokens_.size() ? Truth::kUnknown : truth;
    }

private:
    bool Peek(std::string_view token) const {
        return at_ < tokens_.size() && tokens_[at_] == token;
    }
    void Expect(std::string_view token) {
        malformed_ = malformed_ || !Peek(token);
        ++at_;
    }
    // `operand (op operand)*`, where `absorbing` (true for ||, false for &&) on either side
    // decides the whole; otherwise two equal sides do, and anything else is undecided.
    Truth Chain(std::string_view op, Truth (Evaluation::*operand)(), Truth absorbing) {
        Truth truth = (this->*operand)();
        while (!malformed_ && Peek(op)) {
            ++at_;
            const Truth right = (this->*operand)();
            truth = truth == absorbing || right == absorbing
                            ? absorbing
                            : (truth == right ? truth : Truth::kUnknown);
        }
        return truth;
    }
    Truth Disjunction() { return Chain("||", &Evaluation::Conjunction, Truth::kTrue); }
    Truth Conjunction() { return Chain("&&", &Evaluation::Unary, Truth::kFalse); }
    Truth Unary() {
        // Hostile nesting ("!!!!…", "((((…") is undecided rather than a deep recursion.
        if (++depth_ > kMaxDepth) {
            malformed_ = true;
            return Truth::kUnknown;
        }
        const Truth truth = Primary();
        --depth_;
        return truth;
    }
    Truth Primary() {
        if (Peek("!")) {
            ++at_;
            const Truth inner = Unary();
            return inner == Truth::kUnknown
                           ? inner
                           : (inner == Truth::kTrue ? Truth::kFalse : Truth::kTrue);
        }
        if (Peek("(")) {
            ++at_;
            const Truth inner = Disjunction();
            Expect(")");
            return inner;
        }
        if (Peek("defined")) {
            ++at_;
            const bool parenthesised = Peek("(");
            at_ += parenthesised ? 1 : 0;
            if (at_ >= tokens_.size() || !IsIdentifier(tokens_[at_])) {
                malformed_ = true;
                return Truth::kUnknown;
            }
            const auto it = file_.ids_.find(tokens_[at_++]);
            const Truth truth = it != file_.ids_.end()
                                        ? defined_[static_cast<std::size_t>(it->second)]
                                        : Truth::kUnknown;
            if (parenthesised) {
                Expect(")");
            }
            return truth;
        }
        if (at_ < tokens_.size() &&
            std::all_of(tokens_[at_].begin(), tokens_[at_].end(),
                        [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
            const bool zero = tokens_[at_].find_first_not_of('0') == std::string::npos;
            ++at_;
            return zero ? Truth::kFalse : Truth::kTrue;
        }
        malformed_ = true;
        return Truth::kUnknown;
    }

    const DefineRelevance& file_;
    const std::vector<std::string>& tokens_;
    const std::vector<Truth>& defined_;
    std::size_t at_ = 0;
    bool malformed_ = false;
    static constexpr int kMaxDepth = 200;
    int depth_ = 0;
};

std::optional<std::string> DefineRelevance::Relevant(const std::vector<std::string>& defines,
                                                     std::vector<LineSpan>* skipped) const {
    if (skipped != nullptr) {
        skipped->clear();
    }
    if (!followed_) {
        return std::nullopt;
    }
    // The defines' names, as DefinePreamble gives them to glslang. A define glslang may refuse
    // in the preamble, or whose value holds a name (expanded wherever the define is), is beyond
    // the walk (IsPlainDefine); so is a name given twice.
    std::vector<std::string> define_names;
    for (const std::string& define : defines) {
        define_names.push_back(define.substr(0, define.find('=')));
        if (!IsPlainDefine(define) ||
            std::count(define_names.begin(), define_names.end(), define_names.back()) > 1) {
            return std::nullopt;
        }
    }
    // The renaming is planned over the preamble too; a define it touches could change the plan.
    const RenamingScan renaming = ScanForRenaming(DefinePreamble(defines));
    if (!renaming.es100_tokens.empty() || renaming.spells_length_stand_in ||
        renaming.declares_length_member) {
        return std::nullopt;
    }

    // Whether each name of the file is defined at the current line, as far as the walk knows, and
    // where that definition comes from: as given (the user's define, or none), an #undef of the
    // file's, a #define of the file's (the item's index), or a block the walk did not decide.
    constexpr int kAsGiven = -1;
    constexpr int kUndefinedHere = -2;
    constexpr int kUndecided = -3;
    std::vector<Truth> defined = undefined_;
    for (const std::string& name : define_names) {
        if (const auto it = ids_.find(name); it != ids_.end()) {
            defined[static_cast<std::size_t>(it->second)] = Truth::kTrue;
        }
    }
    std::vector<int> source(names_.size(), kAsGiven);
    auto set_source = [&](int id, int from) {
        source[static_cast<std::size_t>(id)] = from;
        defined[static_cast<std::size_t>(id)] =
                from == kUndecided ? Truth::kUnknown
                                   : (from == kUndefinedHere ? Truth::kFalse : Truth::kTrue);
    };
    // The items whose text reaches glslang's output or its messages ('1': code, a directive that
    // tells glslang something, a #define or #undef that can fail or changes a name some line
    // expands), those of blocks whose branch the walk could not decide ('u'), and the names whose
    // definition the preprocessor may read on those lines. The lines of #if and its kin decide
    // which lines are read, and the path records what they decided; a #define or #undef whose
    // only effect is on later conditions shows there. `undecided` holds, for each undecided
    // block, where every name's definition came from when glslang read it.
    std::string path(items_.size(), '0');
    std::string undecided;
    std::vector<bool> consulted(names_.size(), false);
    auto consult = [&](std::size_t k) {
        for (int id : items_[k].names) {
            consulted[static_cast<std::size_t>(id)] = true;
        }
    };
    auto read = [&](std::size_t k, char mark) {
        path[k] = mark;
        consult(k);
    };
    // A block whose branch the walk cannot decide: glslang may read any line of it, with the
    // definition in force of any name in it, and of any name in the bodies of the file's own
    // definitions among those (they expand too); a name it defines or undefines is undecided
    // after it. `kept` counts what the walk recorded, to give up past kMostKept.
    std::size_t kept = 0;
    std::vector<int> seen(names_.size(), -1);  // the block (its first item) that recorded a name
    auto read_all = [&](std::size_t first, std::size_t last) {
        undecided += std::to_string(first) + ":";
        std::vector<int> pending;
        auto reach = [&](const Item& item) {
            for (int id : item.names) {
                if (seen[static_cast<std::size_t>(id)] != static_cast<int>(first)) {
                    seen[static_cast<std::size_t>(id)] = static_cast<int>(first);
                    pending.push_back(id);
                }
            }
        };
        for (std::size_t k = first; k <= last; ++k) {
            reach(items_[k]);
        }
        while (!pending.empty() && kept <= kMostKept) {
            const auto id = static_cast<std::size_t>(pending.back());
            pending.pop_back();
            consulted[id] = true;
            if (source[id] != kAsGiven) {
                undecided += std::to_string(id) + "=" + std::to_string(source[id]) + ",";
                ++kept;
            }
            if (source[id] >= 0) {
                reach(items_[static_cast<std::size_t>(source[id])]);
            }
        }
        undecided += ";";
        for (std::size_t k = first; k <= last; ++k) {
            path[k] = 'u';
            const Item& item = items_[k];
            if ((item.kind == Kind::kDefine || item.kind == Kind::kUndef) && item.name >= 0) {
                set_source(item.name, kUndecided);
            }
        }
        kept += last - first + 1;
    };
    struct Frame {
        std::size_t start;   // the construct's kIf, kIfdef or kIfndef
        bool parent_active;  // whether the construct is read at all
        bool active;         // whether the current branch is
        bool taken;          // whether a branch was taken already
    };
    std::vector<Frame> frames;
    auto active = [&] { return frames.empty() || frames.back().active; };
    for (std::size_t i = 0; i < items_.size(); ++i) {
        const Item& item = items_[i];
        switch (item.kind) {
            case Kind::kIf:
            case Kind::kIfdef:
            case Kind::kIfndef: {
                if (!active()) {
                    // Skipped text: glslang follows its nesting and evaluates nothing in it.
                    frames.push_back(Frame{i, false, false, true});
                    break;
                }
                Truth truth = Truth::kUnknown;
                if (item.kind == Kind::kIf) {
                    truth = Evaluation(*this, item.condition, defined).Run();
                } else if (item.name >= 0) {
                    truth = defined[static_cast<std::size_t>(item.name)];
                    if (item.kind == Kind::kIfndef && truth != Truth::kUnknown) {
                        truth = truth == Truth::kTrue ? Truth::kFalse : Truth::kTrue;
                    }
                }
                if (truth == Truth::kUnknown) {
                    read_all(i, item.end);
                    if (kept > kMostKept) {
                        return std::nullopt;
                    }
                    i = item.end;
                    break;
                }
                frames.push_back(Frame{i, true, truth == Truth::kTrue, truth == Truth::kTrue});
                break;
            }
            case Kind::kElif: {
                Frame& frame = frames.back();
                if (!frame.parent_active) {
                    break;
                }
                if (frame.taken) {
                    frame.active = false;  // glslang does not evaluate it
                    break;
                }
                const Truth truth = Evaluation(*this, item.condition, defined).Run();
                if (truth == Truth::kUnknown) {
                    const std::size_t start = frame.start;
                    frames.pop_back();
                    read_all(start, items_[start].end);
                    if (kept > kMostKept) {
                        return std::nullopt;
                    }
                    i = items_[start].end;
                    break;
                }
                frame.active = frame.taken = truth == Truth::kTrue;
                break;
            }
            case Kind::kElse:
                frames.back().active = frames.back().parent_active && !frames.back().taken;
                frames.back().taken = true;
                break;
            case Kind::kEndif:
                frames.pop_back();
                break;
            case Kind::kDefine:
            case Kind::kUndef: {
                if (!active()) {
                    break;
                }
                // Quiet: glslang takes the line without a word (a #define of a name not defined
                // here, or defined by the file with the same body: no redefinition), and no line
                // expands the name.
                auto same_definition = [&] {
                    const int from = source[static_cast<std::size_t>(item.name)];
                    return from >= 0 && items_[static_cast<std::size_t>(from)].body == item.body;
                };
                const bool quiet = item.plain && !expanded_[static_cast<std::size_t>(item.name)] &&
                                   (item.kind == Kind::kUndef ||
                                    defined[static_cast<std::size_t>(item.name)] == Truth::kFalse ||
                                    same_definition());
                if (!quiet) {
                    read(i, '1');
                    // Whether glslang takes the line depends on the name's definition before it,
                    // which a quiet line earlier may have set without a trace on the path.
                    if (item.name >= 0) {
                        undecided += std::to_string(i) + "<" +
                                     std::to_string(source[static_cast<std::size_t>(item.name)]) +
                                     ";";
                    }
                }
                if (item.name >= 0) {
                    // A line glslang may refuse may leave the name as it was: undecided.
                    set_source(item.name,
                               !item.plain ? kUndecided
                                           : (item.kind == Kind::kDefine ? static_cast<int>(i)
                                                                         : kUndefinedHere));
                }
                break;
            }
            case Kind::kCode:
            case Kind::kOther:
                if (active()) {
                    read(i, '1');
                }
                break;
        }
    }

    // Code the walk decided glslang skips: on no path, and in no undecided block ('u').
    for (std::size_t k = 0; skipped != nullptr && k < items_.size(); ++k) {
        if (items_[k].kind == Kind::kCode && path[k] == '0') {
            skipped->push_back(items_[k].lines);
        }
    }
    // Hashed: a key as long as the file has lines, kept for every program, would cost memory.
    base::Sha256 key;
    key.Update(path).Update("|").Update(undecided).Update("|");
    for (std::size_t d = 0; d < defines.size(); ++d) {
        const auto it = ids_.find(define_names[d]);
        if (it != ids_.end() && consulted[static_cast<std::size_t>(it->second)]) {
            key.Update(defines[d]).Update(",");
        }
    }
    return key.FinishHex();
}

}  // namespace tidepool
