#include "YamlReader.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

namespace tidepool {

std::optional<std::pair<int, int>> FindInvalidUtf8(std::string_view text) {
    int line = 1;
    int column = 1;
    std::size_t i = 0;
    while (i < text.size()) {
        const auto byte = static_cast<unsigned char>(text[i]);
        std::size_t length = 0;
        std::uint32_t code = 0;
        std::uint32_t minimum = 0;
        if (byte < 0x80) {
            length = 1;
            code = byte;
        } else if ((byte & 0xE0) == 0xC0) {
            length = 2;
            code = byte & 0x1Fu;
            minimum = 0x80;
        } else if ((byte & 0xF0) == 0xE0) {
            length = 3;
            code = byte & 0x0Fu;
            minimum = 0x800;
        } else if ((byte & 0xF8) == 0xF0) {
            length = 4;
            code = byte & 0x07u;
            minimum = 0x10000;
        } else {
            return std::make_pair(line, column);
        }
        if (i + length > text.size()) {
            return std::make_pair(line, column);
        }
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(text[i + k]);
            if ((next & 0xC0) != 0x80) {
                return std::make_pair(line, column);
            }
            code = (code << 6) | (next & 0x3Fu);
        }
        // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
        if (code < minimum || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) {
            return std::make_pair(line, column);
        }
        if (byte == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
        i += length;
    }
    return std::nullopt;
}

namespace {

// The tag a node was written with, as written (`!!str` for yaml-cpp's
// "tag:yaml.org,2002:str"); none for a node written without one. yaml-cpp gives "?" to a plain
// node, "!" to a quoted scalar (and to one written with the non-specific `!`, which means the
// same: text), and "" to a null.
std::optional<std::string> ExplicitTag(const std::string& tag) {
    if (tag.empty() || tag == "?" || tag == "!") {
        return std::nullopt;
    }
    constexpr std::string_view kCore = "tag:yaml.org,2002:";
    if (tag.rfind(kCore, 0) == 0) {
        return "!!" + tag.substr(kCore.size());
    }
    return tag;
}

// Reports a node written with a tag at `mark`, once a document (`*reported`): tidepool reads
// every value by its key's type, so a tag would be ignored: `max_variants: !!str 16` would still
// be read as 16, and `!include other.yaml` as the text "other.yaml".
void ReportTag(YamlReader& reader, const std::string& file, const YAML::Mark& mark,
               const std::string& tag, bool* reported) {
    const std::optional<std::string> written = ExplicitTag(tag);
    if (!written || *reported) {
        return;
    }
    reader.Diagnostics().push_back(MakeError(
            file, mark.line + 1, mark.column + 1,
            fmt::format("the YAML tag '{}' would be ignored: tidepool reads each value by its "
                        "key's type, and its files use no tags; remove it (to keep a value as "
                        "text, quote it)",
                        *written)));
    *reported = true;
}

// The error for a document past kMaxYamlExpandedNodes: through aliases, or written out (a
// document without an alias, which is no bomb but the wrong file or a generated one).
std::string TooManyNodes(bool through_aliases) {
    return through_aliases ? fmt::format(
                                     "the document expands through its aliases to more than {} "
                                     "nodes; write the repeated parts out or use fewer nested "
                                     "aliases",
                                     kMaxYamlExpandedNodes)
                           : fmt::format(
                                     "the document holds more than {} nodes, where a configuration "
                                     "has a few hundred; check that this is the file meant",
                                     kMaxYamlExpandedNodes);
}

// Walks yaml-cpp's event stream, in which every node of the file appears exactly once and an
// alias is one event: cycles, the expanded size and repeated keys are all decided in one pass,
// before yaml-cpp builds a tree that a recursive walk could follow forever or exponentially.
class AliasChecker : public YAML::EventHandler {
public:
    explicit AliasChecker(YamlReader& reader, const std::string& file)
        : reader_(reader), file_(file) {}

    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnAnchor(const YAML::Mark&, const std::string& name) override { pending_name_ = name; }
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { Leaf(mark, anchor, "~"); }
    void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  const std::string& value) override {
        Tagged(mark, tag);
        Leaf(mark, anchor, value);
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        saw_alias_ = true;
        const std::string name = names_.count(anchor) != 0 ? names_[anchor] : "?";
        if (open_anchors_.count(anchor) != 0) {
            Fail(mark, fmt::format("alias '*{}' refers to the node that contains it, a cycle; "
                                   "an alias may only repeat a node that is complete",
                                   name));
            return;
        }
        auto scalar = scalars_.find(anchor);
        Key(mark, scalar != scalars_.end() ? &scalar->second : nullptr);
        Count(mark, sizes_.count(anchor) != 0 ? sizes_[anchor] : 1);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        Tagged(mark, tag);
        Open(mark, anchor, false);
    }
    void OnSequenceEnd() override { Close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        Tagged(mark, tag);
        Open(mark, anchor, true);
    }
    void OnMapEnd() override { Close(); }

    bool Failed() const { return failed_ || tagged_; }

private:
    struct Frame {
        YAML::anchor_t anchor = YAML::NullAnchor;
        bool is_map = false;
        bool expecting_key = true;
        std::uint64_t size = 1;           // this node and everything under it, aliases expanded
        std::map<std::string, int> keys;  // key → line it was first written at
    };

    void Fail(const YAML::Mark& mark, std::string message) {
        if (!failed_) {
            reader_.Diagnostics().push_back(
                    MakeError(file_, mark.line + 1, mark.column + 1, std::move(message)));
        }
        failed_ = true;
    }
    // The first tagged node is reported, and the document refused.
    void Tagged(const YAML::Mark& mark, const std::string& tag) {
        ReportTag(reader_, file_, mark, tag, &tagged_);
    }
    void Name(YAML::anchor_t anchor) {
        if (anchor != YAML::NullAnchor) {
            names_[anchor] = pending_name_;
        }
        pending_name_.clear();
    }
    // A node in key position of the innermost mapping; `scalar` is its text when it is one.
    void Key(const YAML::Mark& mark, const std::string* scalar) {
        if (stack_.empty() || !stack_.back().is_map) {
            return;
        }
        Frame& map = stack_.back();
        const bool is_key = map.expecting_key;
        map.expecting_key = !map.expecting_key;
        if (!is_key || scalar == nullptr) {
            return;
        }
        auto [it, inserted] = map.keys.emplace(*scalar, mark.line + 1);
        if (!inserted) {
            // yaml-cpp keeps only the first of two equal keys when looked up, silently.
            reader_.Diagnostics().push_back(
                    MakeError(file_, mark.line + 1, mark.column + 1,
                              fmt::format("duplicate key '{}' (first written at line {}); "
                                          "remove one of them",
                                          *scalar, it->second)));
        }
    }
    void Count(const YAML::Mark& mark, std::uint64_t size) {
        if (!stack_.empty()) {
            stack_.back().size = std::min(stack_.back().size + size, kMaxYamlExpandedNodes + 1);
        }
        total_ = std::min(total_ + size, kMaxYamlExpandedNodes + 1);
        if (total_ > kMaxYamlExpandedNodes) {
            Fail(mark, TooManyNodes(saw_alias_));
        }
    }
    void Leaf(const YAML::Mark& mark, YAML::anchor_t anchor, const std::string& value) {
        Name(anchor);
        if (anchor != YAML::NullAnchor) {
            scalars_[anchor] = value;
            sizes_[anchor] = 1;
        }
        Key(mark, &value);
        Count(mark, 1);
    }
    void Open(const YAML::Mark& mark, YAML::anchor_t anchor, bool is_map) {
        Name(anchor);
        Key(mark, nullptr);
        // The node itself is counted now; its children are added to it as they arrive.
        total_ = std::min(total_ + 1, kMaxYamlExpandedNodes + 1);
        if (anchor != YAML::NullAnchor) {
            open_anchors_.insert(anchor);
        }
        Frame frame;
        frame.anchor = anchor;
        frame.is_map = is_map;
        stack_.push_back(std::move(frame));
    }
    void Close() {
        const Frame frame = std::move(stack_.back());
        stack_.pop_back();
        if (frame.anchor != YAML::NullAnchor) {
            open_anchors_.erase(frame.anchor);
            sizes_[frame.anchor] = frame.size;
        }
        if (!stack_.empty()) {
            stack_.back().size =
                    std::min(stack_.back().size + frame.size, kMaxYamlExpandedNodes + 1);
        }
    }

    YamlReader& reader_;
    const std::string& file_;
    std::vector<Frame> stack_;
    std::unordered_set<YAML::anchor_t> open_anchors_;
    std::unordered_map<YAML::anchor_t, std::uint64_t> sizes_;
    std::unordered_map<YAML::anchor_t, std::string> scalars_;
    std::unordered_map<YAML::anchor_t, std::string> names_;
    std::string pending_name_;
    std::uint64_t total_ = 0;
    bool saw_alias_ = false;
    bool failed_ = false;
    bool tagged_ = false;
};

// AliasChecker's findings for a document that has no anchors, from the tree yaml-cpp built:
// without an anchor there is no alias (yaml-cpp refuses one that names no anchor), so the tree
// is no bigger than the text and walking it is safe. It visits the nodes in the order of
// AliasChecker's events and reports the same errors at the same places: reading the text only
// once saves a whole second parse of every configuration (about a fifth of a warm validation).
class TreeChecker {
public:
    TreeChecker(YamlReader& reader, const std::string& file) : reader_(reader), file_(file) {}

    void Check(const YAML::Node& root) { Visit(root); }
    bool Failed() const { return failed_ || tagged_; }

private:
    void CheckTag(const YAML::Node& node) {
        ReportTag(reader_, file_, node.Mark(), node.Tag(), &tagged_);
    }
    // A key's tag is checked before its repetition, as AliasChecker's events check them.
    void Visit(const YAML::Node& node, bool tag_checked = false) {
        // Counted as AliasChecker counts: every node once, the bound checked at leaves.
        total_ = std::min(total_ + 1, kMaxYamlExpandedNodes + 1);
        if (!tag_checked) {
            CheckTag(node);
        }
        if (node.IsMap()) {
            std::map<std::string, int> keys;  // key → line it was first written at
            for (const auto& pair : node) {
                const YAML::Node& key = pair.first;
                CheckTag(key);
                if (key.IsScalar() || key.IsNull()) {
                    const std::string text = key.IsNull() ? "~" : key.Scalar();
                    const YAML::Mark mark = key.Mark();
                    auto [it, inserted] = keys.emplace(text, mark.line + 1);
                    if (!inserted) {
                        reader_.Diagnostics().push_back(
                                MakeError(file_, mark.line + 1, mark.column + 1,
                                          fmt::format("duplicate key '{}' (first written at line "
                                                      "{}); remove one of them",
                                                      text, it->second)));
                    }
                }
                Visit(key, /*tag_checked=*/true);
                Visit(pair.second);
            }
        } else if (node.IsSequence()) {
            for (const YAML::Node& item : node) {
                Visit(item);
            }
        } else if (total_ > kMaxYamlExpandedNodes && !failed_) {
            const YAML::Mark mark = node.Mark();
            reader_.Diagnostics().push_back(MakeError(file_, mark.line + 1, mark.column + 1,
                                                      TooManyNodes(/*through_aliases=*/false)));
            failed_ = true;
        }
    }

    YamlReader& reader_;
    const std::string& file_;
    std::uint64_t total_ = 0;
    bool failed_ = false;
    bool tagged_ = false;
};

// Where a document's first node that is not null starts; none for an empty document.
class FirstNodeRecorder : public YAML::EventHandler {
public:
    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark& at, YAML::anchor_t) override { Record(at); }
    void OnScalar(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                  const std::string&) override {
        Record(at);
    }
    void OnSequenceStart(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {
        Record(at);
    }
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {
        Record(at);
    }
    void OnMapEnd() override {}

    std::optional<YAML::Mark> mark;

private:
    void Record(const YAML::Mark& at) {
        if (!mark) {
            mark = at;
        }
    }
};

// Whether a line after the first one with content starts with a document marker (`---` or
// `...` at column 0, alone or before a blank): without one the text holds one document, and
// the event pass that would look for a second one is skipped.
bool MayHoldASecondDocument(std::string_view text) {
    bool content = false;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        const bool marker =
                (line.rfind("---", 0) == 0 || line.rfind("...", 0) == 0) &&
                (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
        if (marker && content) {
            return true;
        }
        const std::size_t first = line.find_first_not_of(" \t\r");
        content = content || (!marker && first != std::string_view::npos && line[first] != '#');
        at = end + 1;
    }
    return false;
}

SourceLocation LocationOf(const std::string& file, const YAML::Mark& mark) {
    // yaml-cpp marks are 0-based; a null mark (-1) means the position is unknown.
    return SourceLocation{file, mark.line >= 0 ? mark.line + 1 : 0,
                          mark.column >= 0 ? mark.column + 1 : 0};
}

// The place of byte `offset` of `text`: 1-based line and column, columns counting characters
// as FindInvalidUtf8's do (UTF-8 continuation bytes are none).
SourceLocation LocationAt(const std::string& file, std::string_view text, std::size_t offset) {
    const std::string_view before = text.substr(0, offset);
    const std::size_t line_start = before.rfind('\n') + 1;  // npos + 1 is 0
    const auto column =
            std::count_if(before.begin() + static_cast<long>(line_start), before.end(),
                          [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; });
    return SourceLocation{file,
                          1 + static_cast<int>(std::count(before.begin(), before.end(), '\n')),
                          1 + static_cast<int>(column)};
}

// Whether a scalar may start at `i` of `text`: first on its line, or after '[', '{', ',', ':'
// or '-' and blanks (a quote inside a plain scalar, as in "it's", starts nothing).
bool StartsAScalar(std::string_view text, std::size_t i) {
    while (i > 0 && (text[i - 1] == ' ' || text[i - 1] == '\t')) {
        --i;
    }
    return i == 0 || std::string_view("\n[{,:-").find(text[i - 1]) != std::string_view::npos;
}

// Where the `depth`-th unclosed '[' or '{' of `text` opens, outside quoted scalars and comments;
// none when the brackets never nest that deep (the nesting is then of indentation, or mixed).
std::optional<std::size_t> OffsetOfFlowDepth(std::string_view text, int depth) {
    int open = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if ((c == '"' || c == '\'') && StartsAScalar(text, i)) {
            // Past the quoted scalar: in double quotes a backslash escapes the next character, in
            // single quotes '' is a quote.
            for (++i; i < text.size(); ++i) {
                const bool escape =
                        (c == '"' && text[i] == '\\') ||
                        (c == '\'' && text[i] == c && i + 1 < text.size() && text[i + 1] == c);
                if (escape) {
                    ++i;
                } else if (text[i] == c) {
                    break;
                }
            }
        } else if (c == '#' &&
                   (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n')) {
            i = std::min(text.find('\n', i), text.size());
        } else if (c == '[' || c == '{') {
            if (++open == depth) {
                return i;
            }
        } else if ((c == ']' || c == '}') && open > 0) {
            --open;
        }
    }
    return std::nullopt;
}

}  // namespace

std::optional<YAML::Node> YamlReader::Load(std::string_view text) {
    if (const auto bad = FindInvalidUtf8(text)) {
        Error(SourceLocation{file_, bad->first, bad->second},
              "this byte is not UTF-8; YAML files are Unicode text: save the file as UTF-8");
        return std::nullopt;
    }
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        Error(LocationAt(file_, text, nul),
              "a NUL byte, which YAML text may not hold: remove it (a file saved as UTF-16 has "
              "one in every other byte; save it as UTF-8)");
        return std::nullopt;
    }
    const std::string owned(text);
    try {
        if (owned.find('&') == std::string::npos) {
            // No anchor, so no alias: one parse, checked on its tree (TreeChecker).
            YAML::Node root = YAML::Load(owned);
            TreeChecker checker(*this, file_);
            checker.Check(root);
            if (checker.Failed()) {
                return std::nullopt;
            }
            if (MayHoldASecondDocument(owned)) {
                std::istringstream events(owned);
                YAML::Parser parser(events);
                FirstNodeRecorder first;
                parser.HandleNextDocument(first);
                if (!OnlyOneDocument(parser)) {
                    return std::nullopt;
                }
            }
            NoteEmptyValues(root);
            return root;
        }
        std::istringstream events(owned);
        YAML::Parser parser(events);
        AliasChecker checker(*this, file_);
        parser.HandleNextDocument(checker);
        if (checker.Failed() || !OnlyOneDocument(parser)) {
            return std::nullopt;
        }
        YAML::Node root = YAML::Load(owned);
        NoteEmptyValues(root);
        return root;
    } catch (const YAML::DeepRecursion& e) {
        // yaml-cpp's own words for it are "bad file"; its mark for '[' nesting is where its
        // scanner had read to, the end of all the brackets.
        const std::optional<std::size_t> opening = OffsetOfFlowDepth(text, e.depth());
        Error(opening ? LocationAt(file_, text, *opening) : LocationOf(file_, e.mark),
              fmt::format("the YAML nests {} levels deep here, past what yaml-cpp reads, where a "
                          "configuration needs a few: look for an unclosed '[' or '{{', or "
                          "indentation that keeps growing",
                          e.depth()));
        return std::nullopt;
    } catch (const YAML::Exception& e) {
        Error(LocationOf(file_, e.mark), fmt::format("malformed YAML: {}", e.msg));
        return std::nullopt;
    }
}

bool YamlReader::OnlyOneDocument(YAML::Parser& parser) {
    // One more document, not every one: yaml-cpp's own loop over them (YAML::LoadAll) never ends
    // on some malformed texts, whose every further document reads as an empty one.
    FirstNodeRecorder second;
    if (!parser.HandleNextDocument(second) || !second.mark) {
        return true;  // none, or an empty one (a stray `---` at the end): nothing to lose
    }
    Error(At(*second.mark),
          "a second YAML document starts here, after a '---' line, and tidepool reads only the "
          "first: move its keys into the first document and remove the '---'");
    return false;
}

void YamlReader::NoteEmptyValues(const YAML::Node& root) {
    // The checkers before bounded the nodes this walks, aliases expanded, and refused cycles.
    std::vector<YAML::Node> open{root};
    while (!open.empty()) {
        const YAML::Node node = open.back();
        open.pop_back();
        if (node.IsMap()) {
            for (const auto& pair : node) {
                if (pair.second.IsNull()) {
                    empty_values_.emplace(pair.second.Mark().pos,
                                          std::make_pair(pair.second, pair.first.Mark()));
                } else {
                    open.push_back(pair.second);
                }
            }
        } else if (node.IsSequence()) {
            for (const YAML::Node& item : node) {
                open.push_back(item);
            }
        }
    }
}

SourceLocation YamlReader::At(const YAML::Node& node) const {
    if (node.IsNull()) {
        const auto [first, last] = empty_values_.equal_range(node.Mark().pos);
        for (auto it = first; it != last; ++it) {
            if (it->second.first.is(node)) {
                return LocationOf(file_, it->second.second);
            }
        }
    }
    return LocationOf(file_, node.Mark());
}

SourceLocation YamlReader::At(const YAML::Mark& mark) const {
    return LocationOf(file_, mark);
}

void YamlReader::Error(const SourceLocation& where, std::string message) {
    diagnostics_.push_back(MakeError(where.file, where.line, where.column, std::move(message)));
}

bool YamlReader::ExpectMap(const YAML::Node& node, std::string_view what) {
    if (node.IsMap()) {
        return true;
    }
    Error(node, node.IsNull()
                        ? fmt::format("{} has no value; give it a mapping of keys to values", what)
                        : fmt::format("{} must be a mapping of keys to values", what));
    return false;
}

bool YamlReader::ExpectScalar(const YAML::Node& node, std::string_view what) {
    if (node.IsScalar()) {
        return true;
    }
    Error(node, node.IsNull()
                        ? fmt::format("{} has no value; write one after its ':'", what)
                        : fmt::format("{} must be a single value, not a list or mapping", what));
    return false;
}

void YamlReader::CheckKeys(const YAML::Node& map, std::string_view what,
                           const std::vector<std::string>& allowed) {
    for (auto it = map.begin(); it != map.end(); ++it) {
        const std::string key = it->first.Scalar();
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            Error(it->first, fmt::format("unknown key '{}' in {}; allowed keys: {}", key, what,
                                         fmt::join(allowed, ", ")));
        }
    }
}

}  // namespace tidepool
