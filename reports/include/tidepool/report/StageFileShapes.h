// The shape of each stage file the report reads whose typed reader is still to come
// (tidepool.manifest, tidepool.render-results; plans.json and stability.json have theirs in
// stagefiles/): the JSON type of every field its writer emits. The report checks a file against
// its shape before reading anything from it, so a wrongly typed field is an error naming the
// file and the field, never a crash or a silently wrong report.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tidepool::report {

/// The stage files the report checks by shape.
enum class StageFile { kManifest, kResults };

/// Checks every field of `document` that `file`'s writer emits against the type the writer
/// gives it. Returns "" when all agree, else "'path' has the wrong type (expected T, found U)"
/// for the first that does not, with `path` in the form `configurations[0].statistics.median_ms`.
/// Numbers may be null (NaN is written as null). Fields the shape does not name (a newer
/// writer's) and absent fields (an older writer's; the reader decides what it requires) pass.
/// Never throws.
std::string CheckStageFileShape(StageFile file, const nlohmann::json& document);

/// Checks `document` against `shape`, a JSON template: a string names a type ("number",
/// "string", "bool", "any"; a trailing "?" also allows null); `[S]` is an array whose every item
/// has shape S (`[]`: any array); an object lists its fields' shapes, or is `{"*": S}` for a map
/// whose every value has shape S. Returns "" or the first mismatch as CheckStageFileShape does;
/// `path` prefixes the paths. Never throws.
std::string CheckJsonShape(const nlohmann::json& document, const nlohmann::json& shape,
                           const std::string& path = "");

}  // namespace tidepool::report
