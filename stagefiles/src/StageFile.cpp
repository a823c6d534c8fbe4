#include "tidepool/stagefiles/StageFile.h"

#include "tidepool/base/FileKind.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace tidepool {

std::string JsonText(const nlohmann::json& json, int indent) {
    return json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace tidepool

namespace tidepool::stagefiles {
namespace {

// Where and why `bytes` (not JSON) stop being JSON, as "PATH:LINE:COLUMN: not valid JSON: WHY",
// from the parser's own account of it (parsed again with exceptions, only on this path).
std::string JsonSyntaxError(const std::filesystem::path& path, const std::string& bytes) {
    std::size_t offset = bytes.size();
    std::string why = "corrupt or truncated";
    try {
        const nlohmann::json parsed = nlohmann::json::parse(bytes);  // throws, as it failed
        static_cast<void>(parsed);
    } catch (const nlohmann::json::parse_error& e) {
        offset = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, bytes.size());
        // e.what(): "[json.exception.parse_error.101] parse error at line 1, column 9: WHY"
        const std::string what = e.what();
        const std::size_t column = what.find("column ");
        const std::size_t colon = column == std::string::npos ? column : what.find(": ", column);
        if (colon != std::string::npos) {
            why = what.substr(colon + 2);
        }
    } catch (const nlohmann::json::exception&) {
        // Another failure of the same bytes: the plain words stand.
    }
    // The offending byte's line and column, 1-based, the column in characters (UTF-8
    // continuation bytes are none), as the YAML diagnostics count them.
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        if (bytes[i] == '\n') {
            ++line;
            column = 1;
        } else if ((static_cast<unsigned char>(bytes[i]) & 0xC0) != 0x80) {
            ++column;
        }
    }
    return fmt::format("{}:{}:{}: not valid JSON: {}", path.string(), line, column, why);
}

}  // namespace

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
    const std::string bytes = text.str();
    nlohmann::json json = nlohmann::json::parse(bytes, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) {
        *error = JsonSyntaxError(path, bytes);
        return std::nullopt;
    }
    return json;
}

}  // namespace tidepool::stagefiles
