// The one wording of a stage file's type errors, used by the typed readers (FieldReader).
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
