#include "FieldReader.h"

#include "tidepool/stagefiles/WrongTypeMessage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

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
    Integer(value, path, out);
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, long* out) {
    Integer(value, path, out);
}

void FieldReader::Value(const nlohmann::json& value, const std::string& path, long long* out) {
    Integer(value, path, out);
}

namespace {

// Whether `path` holds a duration: one of its names, indices left out, ends in "_ms" or
// "_seconds" ("samples_ms[2][0]", "pass_ms.reflection").
bool IsDuration(std::string_view path) {
    std::string names;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] == '[') {
            i = std::min(path.find(']', i), path.size());
        } else {
            names += path[i];
        }
    }
    for (std::size_t begin = 0; begin <= names.size();) {
        const std::size_t end = std::min(names.find('.', begin), names.size());
        const std::string_view name = std::string_view(names).substr(begin, end - begin);
        if (name.ends_with("_ms") || name.ends_with("_seconds")) {
            return true;
        }
        begin = end + 1;
    }
    return false;
}

}  // namespace

template <typename T>
void FieldReader::Integer(const nlohmann::json& value, const std::string& path, T* out) {
    if (double number = 0; !Number(value, path, &number) || value.is_null()) {
        return;
    }
    const double number = value.get<double>();
    const bool counts = path.find("_saved") == std::string::npos;
    if (number != std::floor(number) ||
        number < (counts ? 0.0 : static_cast<double>(std::numeric_limits<T>::min())) ||
        number >= -static_cast<double>(std::numeric_limits<T>::min())) {
        Fail(ReadFailure::kBadValue,
             fmt::format("'{}' is {}, which is not a {}", path, value.dump(),
                         counts ? "count (a whole number from 0)" : "whole number in range"));
        return;
    }
    *out = value.is_number_float() ? static_cast<T>(number) : value.get<T>();
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
    if (!value.is_null() && IsDuration(path) && !(*out >= 0 && *out <= kLongestDuration)) {
        Fail(ReadFailure::kBadValue,
             fmt::format("'{}' is {}, which is not a duration: from 0 to {:.0f}", path,
                         value.dump(), kLongestDuration));
        return false;
    }
    return true;
}

}  // namespace tidepool::stagefiles
