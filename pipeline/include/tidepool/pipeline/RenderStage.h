// The render stage (`render`, `bench`): every selected configuration rendered headless at every
// view and timed through the runner's one timing engine, into a folder published whole.
// Part of tidepool_pipeline_gl: only `tidepool-gl` links it.
#pragma once

#include "tidepool/base/FolderPublisher.h"
#include "tidepool/pipeline/MatrixLoading.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/pipeline/ProgressSink.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::pipeline {

/// Which configurations to render, at which views and size.
struct RenderSelection {
    std::string config = "variants.yaml";
    std::vector<std::string> filters;  // globs over configuration ids; none: all
    std::vector<std::string> presets;  // presets to keep; none: all
    std::vector<std::string> views;    // view names; none: every default view
    int width = 640;
    int height = 480;
    runner::FourierSettings fourier;
    bool write_images = true;
};

/// A matrix loaded and its configurations and views chosen: the run's options, ready for the
/// timing settings (workers, stopping rule, comparisons) and the host description.
struct PreparedRender {
    Outcome outcome;  // why nothing can be rendered, or the loader's warnings
    std::optional<VariantConfig> config;
    runner::RunOptions run;
};

/// Loads the matrix and chooses the configurations and views. Stops with kUsage when the matrix
/// does not load, the filters or presets have errors or match nothing, or a view is unknown.
PreparedRender PrepareRender(const RenderSelection& selection);

/// What the render did.
struct RenderResult {
    Outcome outcome;  // kInvalid when a configuration failed; kEnvironment when a file was not
                      // written (nothing published then: the previous output stays)
    bool rendered = false;  // false when it stopped before rendering (no folder, no GL)
    runner::RunResults results;
    nlohmann::json json;                 // results.json
    std::filesystem::path results_path;  // where results.json is once published
};

/// The runner's progress callback that tells `sink` (render and run alike).
runner::ProgressCallback ProgressCallbackFor(ProgressSink& sink);

/// Renders `prepared` (whose `run` has its timing settings) with a GL context on `backend` into
/// `out`, staged and published whole by `writer` ("tidepool render"): images, then results.json.
/// Tells `progress` what it is about to do (configurations, views, renderer, workers) and how far
/// it is. Stops when `out` is someone else's (kUsage) or there is no GL context (kEnvironment).
RenderResult Render(PreparedRender& prepared, runner::BackendKind backend,
                    const std::filesystem::path& out, const std::string& writer,
                    ProgressSink& progress);

}  // namespace tidepool::pipeline
