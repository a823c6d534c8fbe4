#include "FieldReader.h"

#include "tidepool/stagefiles/WrongTypeMessage.h"

#include <fmt/format.h>

namespace tidepool::stagefiles {

void FieldReader::Value(const nlohmann::json& value, const std::string& path, std::string* out) {
    if (Expect(value.is_string(), value, path, "string")) {
        *out = value.get<std::string>();
    }
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, bool* out) {
    if (Expect(value.is_boolean(), value, path, "bool")) {
        *out = value.get<bool>();
    }
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, double* out) {
    Number(value, path, out);
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, int* out) {
    if (double number = 0; Number(value, path, &number) && !value.is_null()) {
        *out = value.get<int>();
    }
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, long* out) {
    if (double number = 0; Number(value, path, &number) && !value.is_null()) {
        *out = value.get<long>();
    }
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, long long* out) {
    if (double number = 0; Number(value, path, &number) && !value.is_null()) {
        *out = value.get<long long>();
    }
}

void FieldReader::Fail(ReadFailure failure, std::string problem) {
    if (Ok()) {
        failure_ = failure;
        problem_ = std::move(problem);
    }
}

void FieldReader::FailMissing(std::string_view path, std::string_view key) {
    Fail(ReadFailure::kMissingField, fmt::format("'{}' is missing", Join(path, key)));
}

std::string FieldReader::Join(std::string_view path, std::string_view key) {
    return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

std::string FieldReader::Index(std::string_view path, std::size_t i) {
    return fmt::format("{}[{}]", path, i);
}

bool FieldReader::Expect(bool ok, const nlohmann::json& value, const std::string& path,
                         std::string_view expected) {
    if (!ok) {
        Fail(ReadFailure::kWrongType, WrongTypeMessage(path, expected, value));
    }
    return Ok();
}

bool FieldReader::Number(const nlohmann::json& value, const std::string& path, double* out) {
    if (!Expect(value.is_number() || value.is_null(), value, path, "number")) {
        return false;
    }
    *out = value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
    return true;
}

}  // namespace tidepool::stagefiles
