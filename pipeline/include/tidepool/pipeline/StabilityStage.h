// The stability stage (`stability`): the hard-case catalogue (CPU sweeps and every water variant
// rendered into a float target), the emulated-fp16 precision study and the shader-guard
// comparison, written to stability.json. Part of tidepool_pipeline_gl.
#pragma once

#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/runner/GlBackend.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tidepool::pipeline {

/// How the catalogue's GL cases run, and what stability.json records about it.
struct StabilityRun {
    int width = 64;
    int height = 48;
    std::string size;            // the size as the user gave it ("64x48"), recorded as is
    std::string lp_num_threads;  // LP_NUM_THREADS the context was created with, recorded
    std::string config_path;     // variants.yaml as the user named it, recorded
    // Called as the GL cases, nearly all of the catalogue's time, go by (their share done); may
    // be empty.
    std::function<void(double share_done)> on_progress;
};

/// Runs the whole catalogue with `context` on the water variants among `variants`. Fails (the
/// report incomplete, `error` set) when the context cannot render to float.
lab::StabilityReport RunStabilityCatalogue(runner::GlContext& context, const VariantConfig& config,
                                           const std::vector<Variant>& variants,
                                           const StabilityRun& run, std::string* error);

/// What `stability` is asked to do.
struct StabilityOptions {
    std::string config = "variants.yaml";
    std::filesystem::path out;  // folder for stability.json
    runner::BackendKind backend = runner::BackendKind::kAuto;
    int threads = 2;  // LP_NUM_THREADS for llvmpipe
    StabilityRun run;
};

/// What `stability` did.
struct StabilityResult {
    Outcome outcome;  // kInvalid when a case failed
    lab::StabilityReport report;
    std::string json;            // stability.json as written
    std::filesystem::path path;  // where it was written
    int failed = 0;              // cases that failed
};

/// Loads the matrix, runs the catalogue and writes `out`/stability.json atomically. Stops when a
/// stability.json there is not tidepool's (kUsage, checked before anything runs), the matrix does
/// not load (kUsage), or there is no GL context, no float target or the write fails
/// (kEnvironment). Sets LP_NUM_THREADS before creating the context.
StabilityResult RunStability(const StabilityOptions& options);

}  // namespace tidepool::pipeline
