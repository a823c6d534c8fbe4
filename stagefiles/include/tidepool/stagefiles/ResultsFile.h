// results.json (schema "tidepool.render-results", version 1, runner/RESULTS.md): what a render
// run measured of every configuration, the comparisons it timed pair by pair, and every setting
// that moves a figure. Written by `tidepool render`, `bench` and `run` (runner/Results.h builds
// it), read by the report. Files written before every stage file carried its version under
// `version` say `schema_version`; they still read.
#pragma once

#include "tidepool/stagefiles/ManifestFile.h"
#include "tidepool/stagefiles/StageFile.h"

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

inline constexpr std::string_view kResultsSchemaName = "tidepool.render-results";
inline constexpr int kResultsVersion = 1;
/// The version key of results.json before every stage file said `version`; still read.
inline constexpr const char* kOldResultsVersionKey = "schema_version";

/// The GL context and the machine a run rendered on.
struct ResultsEnvironment {
    std::string backend;
    std::string context_api;
    std::string gl_renderer;
    std::string gl_version;
    std::string glsl_version;
    std::string mesa_version;
    bool float_render_target = false;
    bool timer_query = false;
    std::string cpu_model;
    std::string lp_num_threads;
    std::string build_type;
    std::string git_revision;
    std::string command;

    bool operator==(const ResultsEnvironment&) const = default;
};

/// A camera view.
struct ResultsView {
    std::string name;
    std::array<double, 3> eye{};
    std::array<double, 3> target{};
    double fov_y_radians = 0;
    double near = 0;
    double far = 0;

    bool operator==(const ResultsView&) const = default;
};

/// The water's extinction model (ENABLE_EXTINCTION).
struct ResultsExtinction {
    std::array<double, 3> extinction{};
    double visibility = 0;
    std::array<double, 3> surface_colour{};
    std::array<double, 3> depth_colour{};

    bool operator==(const ResultsExtinction&) const = default;
};

/// The Fourier reflection's settings (REFLECTION_FOURIER).
struct ResultsFourier {
    int coefficients = 0;
    int directions = 0;
    double march_distance = 0;
    int integration_samples = 0;
    double grid_spacing = 0;
    double grid_margin = 0;

    bool operator==(const ResultsFourier&) const = default;
};

/// Every render and timing setting of the run.
struct ResultsSettings {
    std::string config;
    int width = 640;
    int height = 480;
    std::vector<ResultsView> views;
    std::string timing_view;
    int warmup_frames = 0;
    int coarse_frames = 0;
    int pass_frames = 0;
    int workers = 0;
    std::string timing_method;
    double animation_time_s = 0;
    double clip_plane_offset = 0;
    double wave_distortion = 0;
    std::array<std::array<double, 2>, 2> bump_scale{};
    std::array<std::array<double, 2>, 2> bump_velocity{};
    std::array<double, 3> fog_colour{};
    double rcp_max_fog_distance = 0;
    std::array<double, 3> underwater_colour{};
    double rcp_max_fog_depth = 0;
    std::array<double, 4> water_colour{};
    int low_res_water_size = 0;
    int sky_size = 0;
    int normal_map_size = 0;
    int normalisation_cube_size = 0;
    double max_water_depth = 0;
    ResultsExtinction extinction;
    std::array<double, 2> foam_depth{};
    double shore_hardness = 0;
    double shininess = 0;
    ResultsFourier fourier;

    bool operator==(const ResultsSettings&) const = default;
};

/// The driver's verdict on a configuration's program.
struct ResultsDriver {
    bool valid = false;
    bool vertex_compiled = false;
    bool fragment_compiled = false;
    bool linked = false;
    std::string vertex_log;
    std::string fragment_log;
    std::string link_log;
    std::vector<DiagnosticEntry> diagnostics;

    bool operator==(const ResultsDriver&) const = default;
};

/// An image against the reference's at the same view; NaN where the file has null (an
/// identical image's PSNR is infinite, which JSON writes as null).
struct ResultsAccuracy {
    double psnr_db = 0;
    double ssim = 0;
    double share_visible = 0;

    bool operator==(const ResultsAccuracy&) const = default;
};

/// One view of a configuration.
struct ResultsViewResult {
    std::string view;
    std::string image;  // relative to results.json's folder; "" when none was written
    int passes = 0;
    std::vector<std::string> pass_names;  // absent in older files
    std::optional<int> draw_calls;        // absent in older files
    bool oblique_fallback = false;
    std::string gl_error;
    std::optional<ResultsAccuracy> accuracy;  // absent when there was no reference image

    bool operator==(const ResultsViewResult&) const = default;
};

/// The summary of a configuration's frame times (base/SampleStatistics.h), NaN where null.
struct ResultsStatistics {
    int count = 0;
    double min_ms = 0;
    double max_ms = 0;
    double mean_ms = 0;
    double median_ms = 0;
    double q1_ms = 0;
    double q3_ms = 0;
    double iqr_ms = 0;
    double ci_low_ms = 0;
    double ci_high_ms = 0;
    double ci_coverage = 0;
    std::string ci_method;

    bool operator==(const ResultsStatistics&) const = default;
};

/// Everything recorded about one configuration.
struct ResultsConfiguration {
    std::string id;                      // required
    std::optional<std::string> variant;  // absent in older files: the id
    std::string program;
    std::vector<std::string> defines;
    std::vector<std::string> effects;
    bool uniform_bools = false;
    std::vector<std::string> presets;
    PassOptionsEntry passes;
    ResultsDriver driver;
    std::optional<bool> glslang_valid;  // null when not compared
    std::vector<ResultsViewResult> views;
    int frame_passes = 0;
    int frame_draw_calls = 0;
    std::vector<std::vector<double>> samples_ms;      // wall clock, per round
    std::optional<ResultsStatistics> statistics;      // absent in older files
    std::vector<std::vector<double>> cpu_samples_ms;  // absent in older files
    std::optional<ResultsStatistics> cpu_statistics;  // absent in older files
    double plan_ms_median = 0;
    std::map<std::string, double, std::less<>> pass_ms;
    double instrumented_frame_ms = 0;
    std::string gl_error;
    bool ok = false;  // required

    bool operator==(const ResultsConfiguration&) const = default;
};

/// How the run timed: its clock and stopping rule.
struct ResultsTiming {
    std::string clock;
    std::string clock_reason;
    std::optional<double> resolution_points;  // absent in older files
    int min_pairs = 0;
    int max_pairs = 0;
    int batch_pairs = 0;
    // Pairs timed with the core shared per pair timed as the machine ran (0 in older files).
    double contended_share = 0;
    double confidence = 0;
    std::string estimator;
    // The stopping rule's boundary clauses (base::StoppingRule): the pairs after which a
    // comparison stops at the resolution unless an end lies near a boundary it does not hold,
    // and how many standard errors an end must clear the direction margin by. Absent in older
    // files.
    std::optional<int> boundary_pairs;
    std::optional<double> boundary_standard_errors;

    bool operator==(const ResultsTiming&) const = default;
};

/// A comparison timed pair by pair; the estimate is NaN where the file has null.
struct ResultsComparison {
    std::string label;      // required
    std::string baseline;   // required; a configuration id
    std::string candidate;  // required
    std::string error;
    int pairs = 0;
    std::string decision;
    double ratio = 0;
    double ratio_low = 0;
    double ratio_high = 0;
    double change_percent = 0;
    double change_low = 0;
    double change_high = 0;
    std::vector<double> baseline_ms;   // required: on the run's clock
    std::vector<double> candidate_ms;  // required
    std::vector<double> baseline_wall_ms;
    std::vector<double> candidate_wall_ms;
    // Pairs timed with the core shared (base::AcrossHostStates; empty when none, and in older
    // files), on the run's clock, and the interval stated across both sets of pairs (the
    // as-run interval when there are none).
    std::vector<double> contended_baseline_ms;
    std::vector<double> contended_candidate_ms;
    double stated_change_low = 0;
    double stated_change_high = 0;
    // Each side's per-pass medians over the comparison's instrumented frames, taken in pairs,
    // and those frames' median as a whole (empty / 0 in files written before they were kept).
    std::map<std::string, double, std::less<>> baseline_pass_ms;
    std::map<std::string, double, std::less<>> candidate_pass_ms;
    double baseline_instrumented_frame_ms = 0;
    double candidate_instrumented_frame_ms = 0;
    // Which process timed it: "render" (the process writing the file) or "second_process"
    // (`run`'s process beside the render, which times at other moments of the machine's load);
    // "" in files written before it was kept.
    std::string timed_by;

    bool operator==(const ResultsComparison&) const = default;
};

/// A variant on which glslang and Mesa reach different verdicts.
struct ResultsDisagreement {
    std::string variant;
    bool glslang_valid = false;
    bool mesa_valid = false;

    bool operator==(const ResultsDisagreement&) const = default;
};

/// Everything results.json holds.
struct ResultsFile {
    std::string started_utc;
    double wall_seconds = 0;
    ResultsEnvironment environment;
    ResultsSettings settings;
    std::vector<ResultsConfiguration> configurations;  // required
    ResultsTiming timing;
    std::vector<ResultsComparison> comparisons;
    std::vector<ResultsDisagreement> disagreements;
    std::vector<DiagnosticEntry> diagnostics;
    bool ok = false;

    bool operator==(const ResultsFile&) const = default;
};

/// The JSON of each part, as results.json holds it. Never fail.
nlohmann::json ToJson(const ResultsEnvironment& environment);
nlohmann::json ToJson(const ResultsSettings& settings);
nlohmann::json ToJson(const ResultsFile& file);

/// Reads `document` as results.json, naming `file_name` in the error. Fails as ReadResultsFile.
ReadResult<ResultsFile> ResultsFileFromJson(const nlohmann::json& document,
                                            const std::string& file_name);
/// Reads results.json at `path` (its version under `version`, or `schema_version` when it has
/// only that): kUnreadable, kForeign (another schema or version), kMissingField
/// ('configurations', a configuration's 'id' or 'ok', a comparison's 'label', 'baseline',
/// 'candidate', 'baseline_ms' or 'candidate_ms') or kWrongType, with an error naming the file and
/// the field.
ReadResult<ResultsFile> ReadResultsFile(const std::filesystem::path& path);
/// `file` as the text of results.json: two-space indented with a final newline. Never fails.
std::string ResultsFileText(const ResultsFile& file);

}  // namespace tidepool::stagefiles
