#include "tidepool/stagefiles/WrongTypeMessage.h"

#include <fmt/format.h>

namespace tidepool::stagefiles {
namespace {

const char* TypeName(const nlohmann::json& value) {
    switch (value.type()) {
        case nlohmann::json::value_t::null:
            return "null";
        case nlohmann::json::value_t::boolean:
            return "bool";
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned:
        case nlohmann::json::value_t::number_float:
            return "number";
        case nlohmann::json::value_t::string:
            return "string";
        case nlohmann::json::value_t::array:
            return "array";
        case nlohmann::json::value_t::object:
            return "object";
        default:
            return "binary";
    }
}

}  // namespace

std::string WrongTypeMessage(std::string_view path, std::string_view expected,
                             const nlohmann::json& found) {
    return fmt::format("'{}' has the wrong type (expected {}, found {})",
                       path.empty() ? std::string_view("(the document)") : path, expected,
                       TypeName(found));
}

}  // namespace tidepool::stagefiles
