// `tidepool run` up to the report: validate (the manifest), then the render with the stability
// catalogue and the scene plans beside it in a second process, into one render folder published
// whole. The report is the last step, pipeline::BuildReport over the two files this returns.
// Part of tidepool_pipeline_gl.
#pragma once

#include "tidepool/base/SharedClaims.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/pipeline/ProgressSink.h"
#include "tidepool/pipeline/ValidationCache.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

namespace tidepool::pipeline {

/// What `run` is asked to do (sizes already parsed and checked by the caller).
struct RunRequest {
    std::string config = "variants.yaml";
    std::filesystem::path out = "reports/out";  // receives manifest/ and render/
    int width = 640;
    int height = 480;
    runner::BackendKind backend = runner::BackendKind::kAuto;
    runner::FourierSettings fourier;
    CacheChoice cache;
    // Stability and plans run beside the render. Their sizes keep them well inside the render's
    // time: the stability cases look for NaN, Inf and bounds, which do not depend on resolution
    // (64x48 is `tidepool stability`'s own default); the plans compare images against the
    // scene's full-effect image at 160x120 (above the 11x11 SSIM window many times over), each
    // candidate timed against the full effect pair by pair to +/-plan_resolution points.
    bool stability = true;
    bool plans = true;
    int stability_width = 64;
    int stability_height = 48;
    int plan_width = 160;
    int plan_height = 120;
    double plan_resolution = 3.0;
    /// Fills the render's timing settings (stopping rule, frames, workers, context factory,
    /// comparisons) and host description once its configurations are chosen.
    std::function<void(runner::RunOptions*)> prepare_timing;
};

/// What `run` did up to the report.
struct RunResult {
    Outcome outcome;        // kInvalid when a variant, configuration, stability case or plan failed
    bool rendered = false;  // the render folder was published: the report can be built
    std::filesystem::path manifest_path;
    std::filesystem::path results_path;
};

/// Validates the matrix into `out`/manifest/manifest.json, then renders it into `out`/render/
/// (images, results.json) while a second process runs the stability catalogue and plans every
/// scenes/*.yaml (stability.json, plans.json) into the same folder, and publishes the folder.
/// Neither a user's manifest.json nor a render folder tidepool did not write is ever replaced
/// (kUsage, before any work). Tells `progress` each stage's summary line and the render's
/// progress; the messages of the stages run in their own processes are told as they come.
/// Must be called while the process has one thread (it forks).
RunResult Run(const RunRequest& request, ProgressSink& progress);

/// The share of the second process's own stages that the stability catalogue takes when the scene
/// plans follow it: the median of seven main jobs on the default matrix of 2026-12-07, where the
/// catalogue took 17 to 19 of 40 to 56 s quiet and 39 to 40 of 82 to 87 s beside two `yes`
/// (0.34 to 0.48). At 0.25 (2026-11-28: 12 of 48 s quiet, 28 of 103 s loaded, before the plans
/// got faster), the forecast put the join up to 1.7 times too late while the catalogue ran, and
/// the render's ETA leaned on it. (Before that, the plans took 67 to 216 s and the catalogue 10 to
/// 19% of the two; and before that a third, from a catalogue that took 25 of 73 s, put the join
/// after the catalogue at 39 s in runs that joined after 79 to 132 s.)
inline constexpr double kStabilityShareOfStages = 0.43;

/// The second process's forecast of when it will start taking the render's units
/// (base::SharedClaims::ExpectHelperAt), from the share of its own stages done so far: the time
/// they have taken over that share. The stability catalogue counts for kStabilityShareOfStages
/// of the two stages and the scene plans for the rest. Each forecast also beats the claim
/// table's heartbeat: the render counts on a forecast only while it is renewed (runner's
/// ProgressMeter::kForecastSilence).
class JoinForecast {
public:
    using Clock = std::chrono::steady_clock;

    /// Says nothing when `claims` is null. `stability` and `plans`: the stages it runs.
    JoinForecast(base::SharedClaims* claims, bool stability, bool plans,
                 Clock::time_point start = Clock::now());

    /// `share` of the stability catalogue is done at `now`.
    void Stability(double share, Clock::time_point now = Clock::now()) const;
    /// `share` of the scene plans is done at `now`.
    void Plans(double share, Clock::time_point now = Clock::now()) const;

private:
    void Say(double share, Clock::time_point now) const;

    base::SharedClaims* claims_;
    double stability_share_;
    Clock::time_point start_;
};

}  // namespace tidepool::pipeline
