// The saved files a report is built from: the compiler's manifest (tidepool.manifest v1), the
// runner's results (tidepool.render-results v1) and, when present, the numerical-stability
// catalogue (tidepool.stability) next to the results, each through its reader in stagefiles/.
// Loading checks schemas and the type of every field, so a corrupt or foreign file is an error
// naming that file and field, never a crash.
#pragma once

#include "tidepool/base/ImageMetrics.h"
#include "tidepool/stagefiles/ManifestFile.h"
#include "tidepool/stagefiles/PlansFile.h"
#include "tidepool/stagefiles/ResultsFile.h"
#include "tidepool/stagefiles/StabilityFile.h"

#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::report {

/// The clock whose samples the report compares configurations on.
enum class TimingClock {
    kWall,  // samples_ms: steady-clock time per frame (what a user waits)
    kCpu,   // cpu_samples_ms: CLOCK_PROCESS_CPUTIME_ID, every llvmpipe thread of the process
};

/// "cpu" or "wall"; never fails.
std::string_view TimingClockName(TimingClock clock);

/// One camera view of a configuration, the image rendered at it and the passes that drew it.
struct ViewImage {
    std::string view;
    std::filesystem::path image;  // absolute (resolved against the results folder); empty if none
    // The frame's passes in order ("reflection", "refraction", "main"); empty when the results
    // predate `pass_names` (the field is optional in tidepool.render-results v1).
    std::vector<std::string> pass_names;
    std::optional<int> draw_calls;  // draw calls of one frame; absent in older results
    // The image against the reference's at this view, as the render measured it while the
    // image was in memory (results' `accuracy`); absent in older results, and then the report
    // reads both images and measures it itself.
    std::optional<base::ImageAccuracy> accuracy;  // PSNR +infinity when null in the file
};

/// One render configuration (variant + pass options) as the runner recorded it.
struct MeasuredConfiguration {
    std::string id;       // variant id plus pass suffix
    std::string variant;  // the variant compiled
    std::string program;
    std::vector<std::string> defines;
    std::vector<std::string> effects;
    std::vector<std::string> presets;  // presets that asked for this configuration
    bool uniform_bools = false;
    int reflection_size = 256;
    int refraction_size = 256;
    bool low_res_water = false;
    std::string clip = "oblique";
    bool culling = true;
    bool depth_fog = true;      // the refraction pass's underwater depth fog (with ENABLE_FOG)
    bool ok = false;            // compiled, linked, rendered without a GL error
    bool driver_valid = false;  // Mesa's verdict
    std::optional<bool> glslang_valid;  // glslang's verdict, when the runner compared
    std::string gl_error;
    std::vector<std::string> driver_messages;  // GCC-style driver diagnostics
    std::vector<ViewImage> views;
    std::vector<std::vector<double>> samples_ms;                  // wall clock, per round
    double median_ms = std::numeric_limits<double>::quiet_NaN();  // wall clock
    double ci_low_ms = std::numeric_limits<double>::quiet_NaN();
    double ci_high_ms = std::numeric_limits<double>::quiet_NaN();
    std::vector<std::vector<double>> cpu_samples_ms;  // process CPU time, per round (may be empty)
    double cpu_median_ms = std::numeric_limits<double>::quiet_NaN();
    double cpu_ci_low_ms = std::numeric_limits<double>::quiet_NaN();
    double cpu_ci_high_ms = std::numeric_limits<double>::quiet_NaN();
    int frame_passes = 0;
    int frame_draw_calls = 0;
    // Per-pass medians of instrumented frames (a glFinish after every pass) on the run's clock,
    // and those frames' median as a whole; empty / NaN when the results do not have them.
    std::map<std::string, double> pass_ms;
    double instrumented_frame_ms = std::numeric_limits<double>::quiet_NaN();

    /// True when `preset` asked for this configuration.
    bool HasPreset(std::string_view preset) const;
    /// The pass options as a short human label ("256, oblique" plus "low-res water" etc.).
    std::string PassLabel() const;
    /// The image at `view`, or an empty path when there is none.
    std::filesystem::path ImageAt(std::string_view view) const;
    /// The view called `view`, or null when the configuration has none of that name.
    const ViewImage* ViewAt(std::string_view view) const;
    /// The per-round samples on `clock`.
    const std::vector<std::vector<double>>& SamplesOn(TimingClock clock) const;
    /// The median frame time on `clock` (NaN when not timed on it).
    double MedianOn(TimingClock clock) const;
};

/// Two configurations the runner timed pair by pair (results.json `comparisons`).
struct MeasuredComparison {
    std::string label;
    std::string baseline;  // configuration ids
    std::string candidate;
    std::vector<double> baseline_ms;       // on the run's clock, pair i = (baseline_ms[i],
    std::vector<double> candidate_ms;      // candidate_ms[i])
    std::vector<double> baseline_wall_ms;  // the same frames on the wall clock (may be empty)
    std::vector<double> candidate_wall_ms;
    // Pairs timed with the core shared (empty when none), on the run's clock.
    std::vector<double> contended_baseline_ms;
    std::vector<double> contended_candidate_ms;
    std::string decision;  // "resolved" or "capped"
    std::string error;     // why the runner has no pairs ("" when it has)
    // Each side's per-pass medians over the comparison's own instrumented frames, taken in pairs
    // (empty in results written before they were kept).
    std::map<std::string, double> baseline_pass_ms;
    std::map<std::string, double> candidate_pass_ms;
    // "render", "second_process" (`run`'s process beside the render timed it) or "" (older).
    std::string timed_by;
};

/// Everything a report is built from.
struct ReportInputs {
    std::filesystem::path manifest_path;
    std::filesystem::path results_path;
    stagefiles::ManifestFile manifest;                  // as read (every field's type checked)
    stagefiles::ResultsFile results;                    // as read (every field's type checked)
    std::vector<MeasuredConfiguration> configurations;  // in run order, failed ones included
    std::string timing_view;  // the view that was timed (the report's default view)
    int width = 640;          // the render size of the run
    int height = 480;
    std::vector<std::string> view_names;
    std::filesystem::path stability_path;                // where stability.json was looked for
    std::optional<stagefiles::StabilityFile> stability;  // its content when present and valid
    std::string stability_error;                 // why a present stability.json was not used
    std::filesystem::path plans_path;            // where plans.json was looked for
    std::optional<stagefiles::PlansFile> plans;  // its content when present and valid
    std::string plans_error;                     // why a present plans.json was not used
    // The clock every comparison uses: CPU time when every timed configuration has CPU samples
    // (wall time on a shared machine is disturbed by other processes), else wall time.
    TimingClock clock = TimingClock::kWall;
    std::string clock_name;    // as results.json names it ("thread_cpu", ...)
    std::string clock_reason;  // one sentence: why this clock
    std::vector<MeasuredComparison> comparisons;
    double resolution_points = std::numeric_limits<double>::quiet_NaN();  // asked of each pair

    /// The pairs the runner recorded for (baseline, candidate) ids, or null.
    const MeasuredComparison* FindComparison(std::string_view baseline,
                                             std::string_view candidate) const;

    /// The configuration `preset` asked for, or null when no configuration carries it.
    const MeasuredConfiguration* FindByPreset(std::string_view preset) const;
    /// The configuration with this id, or null.
    const MeasuredConfiguration* FindById(std::string_view id) const;
};

/// What LoadReportInputs found: the inputs, or an error naming the offending file.
struct ReportInputsResult {
    std::optional<ReportInputs> inputs;
    std::string error;  // "" on success; starts with the path of the file at fault
};

/// Reads and checks the manifest and the results (and stability.json and plans.json beside the
/// results, if any). Fails (no inputs, `error` naming the file) when a file is missing,
/// unreadable, not JSON, of another schema or version, or lacks a field the report needs. Images
/// are checked later, when they are read. A corrupt stability.json or plans.json does not fail
/// the load: the report shows why (the error names the file). Chooses the comparison clock.
ReportInputsResult LoadReportInputs(const std::filesystem::path& manifest_path,
                                    const std::filesystem::path& results_path);

}  // namespace tidepool::report
