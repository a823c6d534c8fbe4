// What every stage file shares: how a read fails, the one JSON serialiser every writer goes
// through, and reading a file as JSON.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tidepool {

/// Serialises `json` like json.dump(indent), but bytes that are not UTF-8 (a diagnostic quoting a
/// Latin-1 identifier of a shader, a file name) become U+FFFD instead of throwing: shader text is
/// bytes, and a writer must never abort on it. Every JSON writer of tidepool goes through here.
std::string JsonText(const nlohmann::json& json, int indent = -1);

}  // namespace tidepool

namespace tidepool::stagefiles {

/// The one key every stage file carries its schema version under.
inline constexpr const char* kVersionKey = "version";

/// Why a stage file could not be read, from "not there" to "damaged".
enum class ReadFailure {
    kNone,
    kUnreadable,    // missing, unreadable or not JSON
    kForeign,       // JSON of another schema or version: not this stage's file
    kMissingField,  // of this schema, but a field the reader needs is absent
    kWrongType,     // of this schema, but a field has the wrong JSON type: a damaged stage file
    kBadValue,      // of this schema, but a number no writer gives: a damaged stage file
};

/// A stage file as read: the value, or why not.
template <typename T>
struct ReadResult {
    std::optional<T> value;
    ReadFailure failure = ReadFailure::kNone;
    // "" on success, else "<file>: <what>", e.g. "run/plans.json: 'plans[0].met' has the wrong
    // type (expected bool, found string)".
    std::string error;
};

/// Reads `path` as JSON. Fails (nullopt, `error` "<path>: no such file" / "cannot read" / "not
/// valid JSON (corrupt or truncated)") otherwise. Never throws.
std::optional<nlohmann::json> ReadJsonFile(const std::filesystem::path& path, std::string* error);

}  // namespace tidepool::stagefiles
