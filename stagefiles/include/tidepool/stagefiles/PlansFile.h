// plans.json (schema "tidepool.plans", version 1, docs/SCENES.md): per scene, the configuration
// the planner chose, the full-effect one it was measured against, and every candidate it tried.
// Written by `tidepool plan` and `tidepool run` (lab/src/ScenePlanner.cpp builds it), read by the
// report's Scenes section.
#pragma once

#include "tidepool/stagefiles/StageFile.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

inline constexpr std::string_view kPlansSchemaName = "tidepool.plans";
inline constexpr int kPlansVersion = 1;
/// The file name of the scene plans, beside results.json in a run's render folder.
inline constexpr std::string_view kPlansFileName = "plans.json";

/// The pass options that tell a plan's configurations apart.
struct PlanPassOptions {
    int reflection_size = 0;
    bool low_res_water = false;

    bool operator==(const PlanPassOptions&) const = default;
};

/// One configuration as the planner rendered it: its passes, draws and pixels of one frame.
struct PlanConfiguration {
    std::string id;       // configuration id (variant plus pass suffix)
    std::string variant;  // variant id
    std::vector<std::string> passes;
    std::vector<int> pass_draw_calls;  // in `passes`' order
    PlanPassOptions pass_options;
    int draw_calls = 0;
    std::string image;  // relative to plans.json's folder; "" when not written
    long long pixels_shaded_estimate = 0;

    bool operator==(const PlanConfiguration&) const = default;
};

/// A candidate's image against the full configuration's. NaN when not measured.
struct PlanImageError {
    double psnr_db = 0;  // 99 stands for identical (JSON has no infinity)
    double ssim = 0;
    double share_visible = 0;

    bool operator==(const PlanImageError&) const = default;
};

/// What the planner measured of a valid candidate.
struct PlanMeasurement {
    PlanImageError error;
    double time_ms = 0;
    double time_change_percent = 0;                // vs full, + = slower
    std::array<double, 2> time_change_interval{};  // its 95% interval
    int pairs = 0;
    bool meets_quality = false;

    bool operator==(const PlanMeasurement&) const = default;
};

/// One configuration the planner tried.
struct PlanCandidate {
    PlanConfiguration configuration;
    std::string proposed_because;
    std::optional<double> water_colour_alpha;  // absent: the renderer's default
    bool valid = false;
    PlanMeasurement measurement;           // written only when valid
    std::vector<std::string> diagnostics;  // written only when not valid

    bool operator==(const PlanCandidate&) const = default;
};

/// An effect of the full configuration the plan dropped, or that the measurement kept.
struct PlanEffect {
    std::string effect;
    std::string reason;
    double psnr_change_db = 0;  // of dropping it alone
    double time_change_percent = 0;

    bool operator==(const PlanEffect&) const = default;
};

/// The quality and time bounds of a scene; absent ones were not asked for.
struct PlanTarget {
    std::optional<double> frame_budget_ms;
    std::optional<double> max_share_visible;
    std::optional<double> min_psnr_db;

    bool operator==(const PlanTarget&) const = default;
};

/// What a plan chose and why; a plan that failed has none.
struct PlanChoice {
    PlanConfiguration chosen;
    PlanConfiguration full;
    double time_ms_chosen = 0;
    double time_ms_full = 0;
    double time_change_percent = 0;
    std::array<double, 2> time_change_interval{};
    std::string choice_reason;
    PlanImageError error;  // the chosen image against the full one
    std::vector<PlanEffect> dropped;
    std::vector<PlanEffect> kept;
    int passes_saved = 0;
    int draws_saved = 0;
    long long pixels_saved = 0;
    std::vector<PlanCandidate> candidates;

    bool operator==(const PlanChoice&) const = default;
};

/// One scene's plan.
struct PlannedScene {
    std::string scene;  // required
    std::string description;
    PlanTarget target;
    std::vector<std::string> needed;
    std::vector<std::string> errors;  // GCC-form diagnostics that ended the plan
    bool met = false;
    std::optional<PlanChoice> choice;  // read when the file has "chosen"

    bool operator==(const PlannedScene&) const = default;
};

/// How every candidate was timed against the full configuration.
struct PlansTiming {
    double resolution_points = 0;
    int min_pairs = 0;
    int max_pairs = 0;
    // The pairs a candidate whose image misses the scene's target is stopped at
    // (lab::CandidateRule); 0: timed like the others (a file from before 2026-11-28).
    int missed_target_pairs = 0;
    // Pairs timed with a competing thread on the rendering thread's core per pair timed as the
    // machine runs (base::StoppingRule::contended_share); each interval spans both states. 0:
    // as the machine runs only (and in files before 2026-11-28, whatever `run` did).
    double contended_share = 0;

    bool operator==(const PlansTiming&) const = default;
};

/// Everything plans.json holds.
struct PlansFile {
    std::array<int, 2> size{};  // render width and height
    PlansTiming timing;
    std::vector<PlannedScene> plans;  // required

    bool operator==(const PlansFile&) const = default;
};

/// One scene's plan as the JSON object plans.json holds for it. Never fails.
nlohmann::json ToJson(const PlannedScene& plan);
/// `file` as JSON. Never fails.
nlohmann::json ToJson(const PlansFile& file);

/// Reads `document` as plans.json, naming `file_name` in the error. Fails as ReadPlansFile.
ReadResult<PlansFile> PlansFileFromJson(const nlohmann::json& document,
                                        const std::string& file_name);
/// Reads plans.json at `path`: kUnreadable, kForeign (another schema or version), kMissingField
/// ('plans' or a plan's 'scene') or kWrongType, with an error naming the file and the field.
ReadResult<PlansFile> ReadPlansFile(const std::filesystem::path& path);
/// Writes `file` to `path` atomically (base::WriteFileAtomically), two-space indented with a
/// final newline. Returns "" or a message naming the path and the system error.
std::string WritePlansFile(const PlansFile& file, const std::filesystem::path& path);

}  // namespace tidepool::stagefiles
