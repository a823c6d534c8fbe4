// The one timing engine's settings as `render`, `bench` and `run` take them, applied to a
// render's options, and what a render records about the machine it ran on. Part of
// tidepool_pipeline_gl.
#pragma once

#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <string>

namespace tidepool::pipeline {

/// How the render times: the stopping rule of its comparisons, the frames of the rest, and on
/// how many threads.
struct TimingSettings {
    double resolution = 1.5;  // half-width of a comparison's 95% interval, percent points
    int min_pairs = 20;
    int max_pairs = 400;
    // Pairs timed with a competing thread on the rendering thread's core per pair timed as the
    // machine runs: each comparison's interval then spans both states of the machine
    // (base::AcrossHostStates).
    double contended_share = 0.5;
    int coarse_frames = 3;
    int warmup = 2;
    // Rendering threads; 0: one per core. One by default: llvmpipe's contexts in one process
    // share one rasteriser lock, so a second thread bought no throughput on 2 cores and moved
    // the frames timed beside it by more than their interval.
    int workers = 1;
    int threads = 0;  // LP_NUM_THREADS: 0 renders on each worker's own thread
};

/// Sets LP_NUM_THREADS from `settings` (llvmpipe reads it when the first context is created)
/// and fills the timing part of `run`: rule, frames, workers and a factory for the workers'
/// contexts on `backend`. Comparisons are every pair of report::ComparedPresetPairs() whose two
/// presets are both among `run->configurations`.
void ApplyTiming(const TimingSettings& settings, runner::BackendKind backend,
                 runner::RunOptions* run);

/// What a render records about the machine and build for `command`, reading `config_path`'s
/// folder for the git revision.
runner::HostInfo DescribeHost(const std::string& command, const std::string& config_path);

}  // namespace tidepool::pipeline
