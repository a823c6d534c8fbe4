// A whole render run: driver verdicts, images at every view, interleaved timing rounds, and the
// versioned results.json that records them (schema: runner/RESULTS.md).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/runner/Statistics.h"

namespace tidepool::runner {

/// The results.json schema this code writes; bump it when a field changes meaning.
inline constexpr const char* kResultsSchema = "tidepool.render-results";
inline constexpr int kResultsSchemaVersion = 1;

/// Facts about the machine and build that the library cannot read itself (the CLI supplies
/// them: it may read /proc/cpuinfo, the environment and git).
struct HostInfo {
    std::string cpu_model;
    std::string lp_num_threads;  // as set in the environment before the context was created
    std::string build_type;
    std::string git_revision = "unknown";
    std::string command;         // "render" or "bench"
};

/// What a run renders and how.
struct RunOptions {
    std::vector<RenderConfiguration> configurations;
    std::vector<CameraView> views;  // an image per configuration per view
    std::string timing_view;        // the view timed; "" means the first of `views`
    RenderSettings settings;
    int warmup_frames = 2;          // per configuration, untimed (llvmpipe compiles on first draw)
    int rounds = 3;                 // each round renders every configuration
    int frames_per_round = 3;       // timed frames per configuration per round
    // Timed frames per round for configurations a preset asked for (the whitepaper's
    // comparisons): their per-round medians decide the report's verdicts, so they get more
    // frames than the rest of the matrix, and are timed as a group of their own at the start
    // of every round, so the pairs a verdict compares are measured close together in time;
    // 0 means frames_per_round and one group.
    int preset_frames_per_round = 0;
    std::filesystem::path out_dir;  // images go to out_dir/images/
    bool write_images = true;
    bool compare_with_glslang = true;  // list variants where glslang and Mesa disagree
    HostInfo host;
    std::string config_path;        // variants.yaml as named by the user
};

/// One view of one configuration.
struct ViewResult {
    std::string view;
    std::string image_path;  // relative to out_dir; "" when no image was written
    FrameReport frame;
};

/// Everything recorded about one configuration.
struct ConfigurationResult {
    RenderConfiguration configuration;
    DriverVerdict verdict;
    std::optional<bool> glslang_valid;  // glslang's verdict on the same variant, when compared
    std::vector<ViewResult> views;
    std::vector<std::vector<double>> samples_ms;  // frame times per round, milliseconds
    SampleStatistics statistics;                  // over every sample of every round
    // The same frames measured as this process's CPU time (every llvmpipe thread included):
    // the work a frame costs, which other processes on a shared machine barely disturb.
    std::vector<std::vector<double>> cpu_samples_ms;
    SampleStatistics cpu_statistics;
    int passes = 0;                               // per frame at the timing view
    int draw_calls = 0;
    std::string gl_error;                         // the first GL error seen, "" when none
    double plan_ms_median = 0;  // CPU planning time per frame (matrices, polygon, culling)

    /// True when the driver accepted every program and no frame raised a GL error.
    bool Ok() const { return verdict.valid && gl_error.empty(); }
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
    std::vector<VerdictDisagreement> disagreements;
    std::vector<Diagnostic> diagnostics;  // every driver diagnostic and run-level problem
    double wall_seconds = 0;
    std::string started_utc;  // ISO 8601

    /// True when every configuration is Ok().
    bool AllOk() const;
};

/// Where a run is, for the CLI's progress line.
struct RunProgress {
    std::string stage;          // "compile", "images", "warmup", "timing"
    std::string configuration;  // id of the configuration being worked on
    long done = 0;              // frames (or compiles) finished
    long total = 0;
    double elapsed_seconds = 0;
    double eta_seconds = 0;     // elapsed / done × remaining; 0 until something is done
};

/// Called after every unit of work; may print, must not throw.
using ProgressCallback = std::function<void(const RunProgress&)>;

/// Compiles every configuration in Mesa, renders an image per view (written as PNG when asked),
/// then times warm-up frames and interleaved rounds (each frame: submission + glFinish on a
/// steady clock; the configuration order rotates every round so drift spreads evenly). Fails
/// through the results: a configuration that does not compile is skipped for images and timing,
/// and any problem is a diagnostic.
RunResults RunRender(GlContext& context, const VariantConfig& config, const RunOptions& options,
                     const ProgressCallback& progress);

/// The results as JSON (schema kResultsSchema, version kResultsSchemaVersion). Never fails.
nlohmann::json ResultsToJson(const RunResults& results);

/// Writes `json` to `path` atomically: a temporary file in the same folder, then a rename, so a
/// reader never sees half a file. Returns "" or what went wrong.
std::string WriteJsonAtomically(const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace tidepool::runner
