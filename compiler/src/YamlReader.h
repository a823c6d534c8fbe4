// The YAML reading layer shared by variants.yaml and scenes/*.yaml: yaml-cpp is wrapped here so
// that no exception leaves the library, hostile documents (non-UTF-8 bytes, cyclic aliases,
// alias bombs) are refused before any tree walk, and every position becomes a 1-based
// file:line:col. Private to the compiler library.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tidepool {

/// A document may expand through its aliases to at most this many nodes. The shipped
/// variants.yaml has about 300 nodes and a scene about 40, so this is hundreds of times any real
/// file, while a checker that walks the expanded tree still finishes in milliseconds; a
/// "billion laughs" file of a few hundred bytes expands to billions.
inline constexpr std::uint64_t kMaxYamlExpandedNodes = 100'000;

/// Collects diagnostics about one YAML file; the config and scene parsers derive from it.
class YamlReader {
public:
    explicit YamlReader(std::string file_name) : file_(std::move(file_name)) {}

    /// Parses the document of `text` after checking that it is UTF-8, that no alias names a node
    /// containing it, and that its alias expansion stays within kMaxYamlExpandedNodes; reports
    /// every repeated mapping key. Returns no node when the text cannot be used (the reason is in
    /// Diagnostics()), among them a text of two documents, whose second one would otherwise be
    /// dropped unread; a repeated key is reported but the node is still returned.
    std::optional<YAML::Node> Load(std::string_view text);

    std::vector<Diagnostic>& Diagnostics() { return diagnostics_; }
    const std::string& FileName() const { return file_; }

protected:
    SourceLocation At(const YAML::Node& node) const;
    SourceLocation At(const YAML::Mark& mark) const;
    void Error(const SourceLocation& where, std::string message);
    void Error(const YAML::Node& node, std::string message) { Error(At(node), std::move(message)); }

    bool ExpectMap(const YAML::Node& node, std::string_view what);
    bool ExpectScalar(const YAML::Node& node, std::string_view what);
    /// Reports every key of `map` that is not in `allowed`.
    void CheckKeys(const YAML::Node& map, std::string_view what,
                   const std::vector<std::string>& allowed);

    std::vector<Diagnostic> diagnostics_;

private:
    /// False, with an error at its first node, when the document after the one `parser` has
    /// just handled is not empty.
    bool OnlyOneDocument(YAML::Parser& parser);
    /// Notes every mapping value of `root` that is null with its key's mark, for At.
    void NoteEmptyValues(const YAML::Node& root);

    std::string file_;
    // Null mapping values by the offset of their own mark, with the marks of their keys. Why:
    // yaml-cpp marks a value left empty (`vertex:` and nothing after it) where the next token
    // starts, often a line below under another key or past the end of the file; an error about
    // the value belongs on its key's line.
    std::multimap<int, std::pair<YAML::Node, YAML::Mark>> empty_values_;
};

/// The first byte of `text` that is not part of valid UTF-8 (overlong forms and surrogates
/// included), as a 1-based line and column counted in characters; nullopt when all is UTF-8.
std::optional<std::pair<int, int>> FindInvalidUtf8(std::string_view text);

}  // namespace tidepool
