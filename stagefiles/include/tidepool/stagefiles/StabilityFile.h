// stability.json (schema "tidepool.stability", version 1, docs/HARD_CASES.md): the hard-case
// catalogue, the emulated-fp16 precision study and the shader-guard comparison. Written by
// `tidepool stability` and `tidepool run` (the lab's catalogue fills it: lab/StabilityReport.h),
// read by the report's Numerical stability section.
#pragma once

#include "tidepool/stagefiles/StageFile.h"

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

inline constexpr std::string_view kStabilitySchemaName = "tidepool.stability";
inline constexpr int kStabilityVersion = 1;
/// The file name of the stability catalogue, beside results.json in a run's render folder.
inline constexpr std::string_view kStabilityFileName = "stability.json";

/// The outcome of one hard case (lab/HardCases.h).
struct StabilityCase {
    std::string name;
    std::string description;
    std::string kind;          // HardCaseKindName: "cpu" or "gl"
    int variants_checked = 0;  // GL: configurations rendered; CPU: 0
    long nan_count = 0;        // GL: pixel channels; CPU: evaluated values
    long inf_count = 0;
    double max_error = 0;  // GL: largest distance of a channel outside [0, 1]; CPU: see bound
    double bound = 0;      // the largest max_error that passes, and why (in `note`)
    bool passed = false;
    std::string fix;
    std::string note;  // what max_error measures and failures, if any

    bool operator==(const StabilityCase&) const = default;
};

/// The accuracy of one shader expression over its sweep (the emulated-fp16 precision study).
struct PrecisionEntry {
    std::string expression;          // the expression as the shader writes it
    double max_abs_error_float = 0;  // against double, over the sweep
    double max_abs_error_fp16 = 0;
    double max_rel_error_fp16 = 0;  // abs error / max(|reference|, the expression's floor)
    double bound_fp16 = 0;          // the relative error above which it "loses precision"
    int non_finite_fp16 = 0;        // sweep points where fp16 gave NaN or Inf
    bool loses_precision = false;   // max_rel_error_fp16 > bound_fp16, or non-finite in fp16
    std::string note;               // where it breaks, and what the shaders do about it

    bool operator==(const PrecisionEntry&) const = default;
};

/// What removing one shader guard changes on the default views.
struct GuardEntry {
    std::string guard;  // the guard, and the test-only define that removes it
    double max_channel_diff_normal_views = 0;
    double tolerance = 0;
    bool passed = false;

    bool operator==(const GuardEntry&) const = default;
};

/// Everything stability.json holds.
struct StabilityFile {
    std::map<std::string, std::string> environment;  // backend, renderer, size, ...
    std::vector<StabilityCase> cases;
    std::vector<PrecisionEntry> precision;
    std::vector<GuardEntry> guards;

    bool operator==(const StabilityFile&) const = default;
};

/// `file` as JSON. Never fails.
nlohmann::json ToJson(const StabilityFile& file);
/// `file` as the text of stability.json: two-space indented with a final newline. Never fails.
std::string StabilityFileText(const StabilityFile& file);

/// Reads `document` as stability.json, naming `file_name` in the error. Fails as
/// ReadStabilityFile.
ReadResult<StabilityFile> StabilityFileFromJson(const nlohmann::json& document,
                                                const std::string& file_name);
/// Reads stability.json at `path`: kUnreadable, kForeign (another schema or version) or
/// kWrongType, with an error naming the file and the field.
ReadResult<StabilityFile> ReadStabilityFile(const std::filesystem::path& path);

}  // namespace tidepool::stagefiles
