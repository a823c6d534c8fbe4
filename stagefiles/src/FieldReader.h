// Reads a stage file's JSON into its C++ type, naming every field by its path from the
// document's root ("plans[0].candidates[2].psnr_db"), so that each reader states its fields once
// and the type check lives in one place.
#pragma once

#include "tidepool/stagefiles/StageFile.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

/// Reads fields into typed values. An absent field keeps its value (an older writer's file); a
/// field the type does not name is never looked at (a newer writer's). The first field of the
/// wrong type, or the first required one that is absent, is kept as the problem, and every later
/// read does nothing, so a parser reads straight through and checks once at the end. A number
/// may be null: JSON has no NaN, so writers write NaN as null, read back as NaN (an integer
/// keeps its value). Every number is also held to what its writers can give, or the first
/// that is not is the problem (kBadValue): an integer is whole, fits its type and is a count,
/// so at least 0 (but a "..._saved" difference); a duration (any field or map whose name ends
/// in "_ms" or "_seconds", and its items) is at least 0 and at most kLongestDuration. Never
/// throws.
class FieldReader {
public:
    /// The longest duration a stage file holds, in its unit: no frame, pass or run tidepool
    /// times takes 3,600,000 ms (an hour) or seconds (41 days). Times past it would overflow
    /// the ratios the report works out of them.
    static constexpr double kLongestDuration = 3.6e6;

    bool Ok() const { return failure_ == ReadFailure::kNone; }
    ReadFailure Failure() const { return failure_; }
    /// "'path' has the wrong type (expected T, found U)" or "'path' is missing"; "" when Ok.
    const std::string& Problem() const { return problem_; }

    /// Reads `object`[`key`] into `out` when present; `path` is the path of `object`.
    template <typename T>
    void Field(const nlohmann::json& object, std::string_view path, std::string_view key, T* out) {
        if (!Ok()) {
            return;
        }
        const auto it = object.find(key);
        if (it != object.end()) {
            Value(*it, Join(path, key), out);
        }
    }

    /// Field, but an absent `key` is a problem (kMissingField).
    template <typename T>
    void Required(const nlohmann::json& object, std::string_view path, std::string_view key,
                  T* out) {
        if (Ok() && !object.contains(key)) {
            FailMissing(path, key);
        }
        Field(object, path, key, out);
    }

    /// Reads a whole value at `path`: a scalar, a list, a map, an optional, a fixed-size array,
    /// or a struct S, read by a `void ReadFields(FieldReader&, const nlohmann::json& object,
    /// const std::string& path, S*)` that ADL finds, after checking that it is an object.
    void Value(const nlohmann::json& value, const std::string& path, std::string* out);
    void Value(const nlohmann::json& value, const std::string& path, bool* out);
    void Value(const nlohmann::json& value, const std::string& path, double* out);
    void Value(const nlohmann::json& value, const std::string& path, int* out);
    void Value(const nlohmann::json& value, const std::string& path, long* out);
    void Value(const nlohmann::json& value, const std::string& path, long long* out);

    template <typename T>
    void Value(const nlohmann::json& value, const std::string& path, std::optional<T>* out) {
        T item{};
        Value(value, path, &item);
        if (Ok()) {
            *out = std::move(item);
        }
    }

    template <typename T>
    void Value(const nlohmann::json& value, const std::string& path, std::vector<T>* out) {
        if (!Expect(value.is_array(), value, path, "array")) {
            return;
        }
        out->clear();
        for (std::size_t i = 0; i < value.size() && Ok(); ++i) {
            out->emplace_back();
            Value(value[i], Index(path, i), &out->back());
        }
    }

    template <typename T, std::size_t N>
    void Value(const nlohmann::json& value, const std::string& path, std::array<T, N>* out) {
        if (!Expect(value.is_array() && value.size() == N, value, path,
                    std::to_string(N) + " items")) {
            return;
        }
        for (std::size_t i = 0; i < N && Ok(); ++i) {
            Value(value[i], Index(path, i), &(*out)[i]);
        }
    }

    template <typename T, typename Less>
    void Value(const nlohmann::json& value, const std::string& path,
               std::map<std::string, T, Less>* out) {
        if (!Expect(value.is_object(), value, path, "object")) {
            return;
        }
        out->clear();
        for (const auto& [key, item] : value.items()) {
            if (!Ok()) {
                return;
            }
            Value(item, Join(path, key), &(*out)[key]);
        }
    }

    template <typename S>
    requires std::is_class_v<S>
    void Value(const nlohmann::json& value, const std::string& path, S* out) {
        if (Expect(value.is_object(), value, path, "object")) {
            ReadFields(*this, value, path, out);
        }
    }

    /// Records a problem of the document itself (its schema, its version); kept if first.
    void Fail(ReadFailure failure, std::string problem);

    /// `path.key`, or `key` at the root.
    static std::string Join(std::string_view path, std::string_view key);
    /// `path[i]`.
    static std::string Index(std::string_view path, std::size_t i);

private:
    // Records "'path.key' is missing" (kMissingField).
    void FailMissing(std::string_view path, std::string_view key);
    // Records "wrong type" for `value` at `path` unless `ok`; returns `ok` and Ok() both.
    bool Expect(bool ok, const nlohmann::json& value, const std::string& path,
                std::string_view expected);
    // A number's value, or NaN for null; false (and the problem recorded) for anything else,
    // a duration out of its range included.
    bool Number(const nlohmann::json& value, const std::string& path, double* out);
    // An integer's value into `out` (null keeps it), checked as the class comment says.
    template <typename T>
    void Integer(const nlohmann::json& value, const std::string& path, T* out);

    ReadFailure failure_ = ReadFailure::kNone;
    std::string problem_;
};

/// Reads `document` as a stage file of `schema` at `version` into a T with `ReadFields`
/// (FieldReader::Value): kForeign when it is not an object of that schema or has another
/// version under `version_key`; the problem is prefixed with `file`. Never throws.
template <typename T>
ReadResult<T> ReadStageDocument(const nlohmann::json& document, const std::string& file,
                                std::string_view schema, int version,
                                std::string_view version_key = kVersionKey) {
    ReadResult<T> result;
    const auto found = document.is_object() ? document.find("schema") : document.end();
    if (!document.is_object() || found == document.end() || !found->is_string() ||
        found->template get_ref<const std::string&>() != schema) {
        result.failure = ReadFailure::kForeign;
        result.error = file + ": schema is not '" + std::string(schema) + "'";
        return result;
    }
    const auto v = document.find(version_key);
    if (v == document.end() || !v->is_number_integer() || v->template get<int>() != version) {
        result.failure = ReadFailure::kForeign;
        result.error =
                file + ": " + std::string(version_key) + " must be " + std::to_string(version);
        return result;
    }
    FieldReader reader;
    T value{};
    reader.Value(document, "", &value);
    if (!reader.Ok()) {
        result.failure = reader.Failure();
        result.error = file + ": " + reader.Problem();
        return result;
    }
    result.value = std::move(value);
    return result;
}

/// ReadJsonFile, then ReadStageDocument. Never throws.
template <typename T>
ReadResult<T> ReadStageFile(const std::filesystem::path& path, std::string_view schema,
                            int version) {
    ReadResult<T> result;
    std::optional<nlohmann::json> document = ReadJsonFile(path, &result.error);
    if (!document) {
        result.failure = ReadFailure::kUnreadable;
        return result;
    }
    return ReadStageDocument<T>(*document, path.string(), schema, version);
}

}  // namespace tidepool::stagefiles
