// A whole render run: driver verdicts, images at every view, interleaved timing rounds, and the
// versioned results.json that records them (schema: runner/RESULTS.md).
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/stagefiles/ResultsFile.h"

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::base {
class SharedClaims;
}

namespace tidepool::runner {

/// Facts about the machine and build that the library cannot read itself (the CLI supplies
/// them: it may read /proc/cpuinfo, the environment and git).
struct HostInfo {
    std::string cpu_model;
    std::string lp_num_threads;  // as set in the environment before the context was created
    std::string build_type;
    std::string git_revision = "unknown";
    std::string command;  // "render" or "bench"
};

/// Two configurations whose frame times a report compares: they are timed pair by pair until
/// the interval is as narrow as the stopping rule asks.
struct TimedComparison {
    std::string label;         // e.g. "row 4" or "full -> full_cubemap_reflection"
    std::size_t baseline = 0;  // indices into RunOptions::configurations
    std::size_t candidate = 0;
    // Where the report's verdict on it changes besides the direction margins (a whitepaper row's
    // magnitude band): RunOptions::rule's boundaries_points for this comparison.
    std::vector<double> boundaries_points = {};
};

/// Units shared with a second process beside the render (`run`'s stability and plan process,
/// which has a core of its own): once its own stages are done it takes units, configurations'
/// and comparisons' alike, from the end of the render's work order while the render takes them
/// from the start (RenderSharedUnits), and the render reads their results back before writing
/// results.json. Both sides of a comparison are always timed in one process, pair by pair.
struct SharedUnits {
    // One unit per configuration, then one per comparison (SharedComparisonUnit); null: no
    // second process.
    base::SharedClaims* claims = nullptr;
    std::filesystem::path folder;  // where the second process leaves each unit's results
};

/// What a run renders and how.
struct RunOptions {
    std::vector<RenderConfiguration> configurations;
    std::vector<CameraView> views;  // an image per configuration per view
    std::string timing_view;        // the view timed; "" means the first of `views`
    RenderSettings settings;
    int warmup_frames = 2;  // untimed, per compared configuration and thread (llvmpipe
                            // compiles on first draw); images warm the others

    // Timed frames of every configuration on its own: enough for the accuracy-versus-time chart
    // (a coarse time), not for a comparison, which `comparisons` time in pairs.
    int coarse_frames = 3;
    std::vector<TimedComparison> comparisons;
    base::StoppingRule rule;  // when a comparison has enough pairs
    // Pairs of frames with a glFinish after each pass, per comparison (one frame of each side
    // per pair): the per-pass times behind the report's "why" column (medians over these frames).
    int pass_frames = 5;
    // Rendering threads, each with a GL context of its own (`make_context` makes all but the
    // first, which is the context RunRender is given, used on the calling thread). Both sides
    // of a comparison are always timed on one thread.
    int workers = 1;
    GlContextFactory make_context;
    std::filesystem::path out_dir;  // images go to out_dir/images/
    bool write_images = true;
    // The configuration whose images every other is compared with (the one with this preset):
    // rendered first, its images kept, and every configuration's images compared with them
    // while still in memory (ViewResult::accuracy), so the report need not read them back.
    std::string reference_preset = "reference";
    bool compare_with_glslang = true;  // list variants where glslang and Mesa disagree
    // glslang's verdicts already found, by the validation that wrote the run's manifest: the
    // comparison takes them from here and validates only variants missing from it. Not owned;
    // none: every variant is validated.
    const ValidationReport* validated = nullptr;
    HostInfo host;
    std::string config_path;  // variants.yaml as named by the user
    SharedUnits shared;       // none unless a second process helps with the units
};

/// One view of one configuration.
struct ViewResult {
    std::string view;
    std::string image_path;  // relative to out_dir; "" when no image was written
    FrameReport frame;
    // The image against the reference configuration's at the same view (base/ImageMetrics.h);
    // absent when the reference has no image there (not rendered yet on another thread, failed,
    // or no configuration has RunOptions::reference_preset).
    std::optional<base::ImageAccuracy> accuracy;
};

/// Everything recorded about one configuration.
struct ConfigurationResult {
    RenderConfiguration configuration;
    DriverVerdict verdict;
    std::optional<bool> glslang_valid;  // glslang's verdict on the same variant, when compared
    std::vector<ViewResult> views;
    // The coarse frames' wall-clock times, one "round" of one frame each (the v1 layout, which
    // readers pair by round when a results file has no comparisons).
    std::vector<std::vector<double>> samples_ms;
    base::SampleStatistics statistics;
    // The same frames on the run's clock (RunResults::clock): CPU time on a software renderer.
    std::vector<std::vector<double>> cpu_samples_ms;
    base::SampleStatistics cpu_statistics;
    // Per-pass medians on the run's clock over RunOptions::pass_frames instrumented frames
    // (compared configurations only: those of the first comparison that timed it, see
    // ComparisonTiming), and the median of those frames as a whole.
    std::map<std::string, double> pass_ms;
    double instrumented_frame_ms = 0;
    int passes = 0;  // per frame at the timing view
    int draw_calls = 0;
    std::string gl_error;       // the first GL error seen, "" when none
    double plan_ms_median = 0;  // CPU planning time per frame (matrices, polygon, culling)

    /// True when the driver accepted every program and no frame raised a GL error.
    bool Ok() const { return verdict.valid && gl_error.empty(); }
};

/// A comparison as timed.
struct ComparisonResult {
    TimedComparison comparison;
    ComparisonTiming timing;
    std::string error;  // "" when both sides rendered; otherwise why there is no estimate
    bool timed_by_second_process = false;  // RunOptions::shared: the process beside timed it
};

/// A variant on which glslang and Mesa reach different verdicts.
struct VerdictDisagreement {
    std::string variant;
    bool glslang_valid = false;
    bool mesa_valid = false;
};

/// The whole run.
struct RunResults {
    GlEnvironment gl;
    HostInfo host;
    RunOptions options;  // settings as used (configurations are repeated in `configurations`)
    std::vector<ConfigurationResult> configurations;
    std::vector<ComparisonResult> comparisons;
    FrameClockChoice clock;         // the clock every time is on
    int workers = 1;                // rendering threads that actually ran
    int shared_configurations = 0;  // configurations a second process rendered (RunOptions::shared)
    std::vector<VerdictDisagreement> disagreements;
    std::vector<Diagnostic> diagnostics;  // every driver diagnostic and run-level problem
    // Files that could not be written (a PNG, for instance): an environment failure, exit 3.
    std::vector<std::string> write_errors;
    double wall_seconds = 0;
    std::string started_utc;  // ISO 8601

    /// True when every configuration is Ok().
    bool AllOk() const;
    /// Comparisons a second process timed (ComparisonResult::timed_by_second_process).
    int SharedComparisons() const;
};

/// Where a run is, for the CLI's progress line.
struct RunProgress {
    std::string stage;          // "images", "comparisons", "waiting for" (the second process)
    std::string configuration;  // id of the configuration (or label of the comparison, or
                                // "the second process's units")
    long done = 0;              // frames finished
    long total = 0;             // frames expected: comparisons' pairs are re-estimated at
                                // every look from the interval's width
    double elapsed_seconds = 0;
    // The remaining frames of each kind (comparisons, images) times that kind's measured
    // thread-seconds per frame, over the rendering threads, shared with a second process as it
    // takes units; at least what the units that process is working on have left (the run
    // collects their results at its end); 0 until something is done.
    double eta_seconds = 0;
    double percent = 0;  // this process's share of its work done, by the seconds it takes
    // The figures the ETA was worked out from, by name, for a progress log (`--progress-log`,
    // README "Progress"): each kind's frames done and left with its price, the comparisons'
    // seconds left, the threads and the second process's forecast. A figure with no value yet
    // is left out.
    std::vector<std::pair<std::string, double>> parts;
};

/// Called after every unit of work, and every half second while the render waits for a second
/// process's last units; may print, must not throw.
using ProgressCallback = std::function<void(const RunProgress&)>;

/// Compiles every configuration in Mesa, renders an image per view (written as PNG when asked)
/// and times `coarse_frames` frames of it; times every comparison pair by pair until the
/// stopping rule ends it, with per-pass times of each compared configuration; all on the clock
/// ChooseFrameClock picks for the context, spread over `workers` threads. Fails through the
/// results: a configuration that does not compile is skipped for images and timing, a
/// comparison with a failed side has an error, and any problem is a diagnostic.
RunResults RunRender(GlContext& context, const VariantConfig& config, const RunOptions& options,
                     const ProgressCallback& progress);

/// The claim-table unit of comparison `k` (RunOptions::comparisons): after every configuration's.
std::size_t SharedComparisonUnit(const RunOptions& options, std::size_t k);

/// What a second process's share of the units came to.
struct SharedUnitsDone {
    int configurations = 0;                 // configurations' units it finished and handed over
    int comparisons = 0;                    // comparisons it timed and handed over
    std::vector<std::string> write_errors;  // PNGs it could not write
    std::string error;                      // "" unless it could not set up a renderer
};

/// The second process's side of RunOptions::shared: renders the reference configuration's views
/// (kept in memory only, to compare with), then takes units from the end of the render's work
/// order until none is left, leaving each unit's results in the shared folder. Does nothing when
/// RunOptions::shared has no claims. Fails through the result; a unit whose results it cannot
/// write is done again by the render process.
SharedUnitsDone RenderSharedUnits(GlContext& context, const VariantConfig& config,
                                  const RunOptions& options);

/// The results as results.json holds them (stagefiles/ResultsFile.h). Never fails.
stagefiles::ResultsFile ToResultsFile(const RunResults& results);
/// ToJson(ToResultsFile(results)): the one writer's JSON. Never fails.
nlohmann::json ResultsToJson(const RunResults& results);

}  // namespace tidepool::runner
