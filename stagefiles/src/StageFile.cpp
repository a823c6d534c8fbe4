#include "tidepool/stagefiles/StageFile.h"

#include "tidepool/base/FileKind.h"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace tidepool {

std::string JsonText(const nlohmann::json& json, int indent) {
    return json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace tidepool

namespace tidepool::stagefiles {

std::optional<nlohmann::json> ReadJsonFile(const std::filesystem::path& path, std::string* error) {
    if (const std::string why = base::WhyNotARegularFile(path); !why.empty()) {
        *error = fmt::format("{}: {}", path.string(), why);
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) {
        *error = fmt::format("{}: cannot read", path.string());
        return std::nullopt;
    }
    nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) {
        *error = fmt::format("{}: not valid JSON (corrupt or truncated)", path.string());
        return std::nullopt;
    }
    return json;
}

}  // namespace tidepool::stagefiles
