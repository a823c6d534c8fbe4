// The one wording of a stage file's type errors, shared by the typed readers (FieldReader) and
// the report's shape check of the files that have no reader yet.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

/// "'path' has the wrong type (expected T, found U)", U the JSON type of `found` ("number" for
/// any number), `path` "(the document)" when empty. Never fails.
std::string WrongTypeMessage(std::string_view path, std::string_view expected,
                             const nlohmann::json& found);

}  // namespace tidepool::stagefiles
