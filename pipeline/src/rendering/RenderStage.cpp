#include "tidepool/pipeline/RenderStage.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/pipeline/OutputFiles.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"

#include <algorithm>
#include <memory>
#include <utility>

#include <fmt/format.h>

namespace tidepool::pipeline {
namespace {

// The views named in `names` (all default views for none); stops `outcome` on an unknown name.
std::vector<runner::CameraView> ChooseViews(const std::vector<std::string>& names,
                                            Outcome* outcome) {
    const std::vector<runner::CameraView> default_views = runner::DefaultViews();
    std::vector<runner::CameraView> views;
    for (const std::string& name : names) {
        const runner::CameraView* view = runner::FindView(default_views, name);
        if (view == nullptr) {
            std::string known;
            for (const runner::CameraView& v : default_views) {
                known += (known.empty() ? "" : ", ") + v.name;
            }
            outcome->Fail(Status::kUsage,
                          fmt::format("unknown view '{}'; the views are {}", name, known));
            return {};
        }
        if (std::count(names.begin(), names.end(), name) > 1) {
            outcome->Fail(Status::kUsage,
                          fmt::format("--view '{}' is given twice; give it once", name));
            return {};
        }
        views.push_back(*view);
    }
    return views.empty() ? default_views : views;
}

}  // namespace

runner::ProgressCallback ProgressCallbackFor(ProgressSink& sink) {
    return [&sink](const runner::RunProgress& p) {
        sink.Progress({p.stage, p.configuration, p.done, p.total, p.elapsed_seconds, p.eta_seconds,
                       p.percent, p.parts});
    };
}

PreparedRender PrepareRender(const RenderSelection& selection) {
    PreparedRender prepared;
    LoadedMatrix loaded = LoadMatrix(selection.config);
    prepared.outcome = std::move(loaded.outcome);
    if (!loaded.config) {
        return prepared;
    }
    const runner::ConfigurationSet all =
            runner::BuildDefaultConfigurations(*loaded.config, loaded.expansion.variants);
    const runner::ConfigurationSet selected = runner::FilterConfigurations(
            all, runner::ConfigurationFilter{selection.filters, selection.presets});
    prepared.outcome.Add(selected.diagnostics);
    if (HasErrors(selected.diagnostics)) {
        prepared.outcome.status = Status::kUsage;
        return prepared;
    }
    if (selected.configurations.empty()) {
        prepared.outcome.Fail(Status::kUsage,
                              "no configuration matches the --filter/--preset given");
        return prepared;
    }
    runner::RunOptions& run = prepared.run;
    run.views = ChooseViews(selection.views, &prepared.outcome);
    if (prepared.outcome.Stopped()) {
        return prepared;
    }
    run.configurations = selected.configurations;
    run.settings.width = selection.width;
    run.settings.height = selection.height;
    run.settings.fourier = selection.fourier;
    run.write_images = selection.write_images;
    run.config_path = selection.config;
    prepared.config = std::move(loaded.config);
    return prepared;
}

RenderResult Render(PreparedRender& prepared, runner::BackendKind backend,
                    const std::filesystem::path& out, const std::string& writer,
                    ProgressSink& progress) {
    RenderResult result;
    runner::RunOptions& run = prepared.run;
    // The whole folder (images, then results.json) is staged and published with one rename, so
    // a killed or failed render leaves the previous good output as it was.
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(out, writer, &result.outcome);
    if (!publisher) {
        return result;
    }
    run.out_dir = publisher->Staging();
    runner::GlContextResult context = runner::CreateGlContext(backend);
    if (!context.context) {
        result.outcome.Fail(Status::kEnvironment, context.error);
        return result;
    }
    const runner::GlEnvironment& gl = context.context->Environment();
    progress.Begin(fmt::format(
            "{}: {} configurations x {} views at {}x{} on {} ({}, {}), LP_NUM_THREADS={}, {} "
            "workers, {} comparisons to +/-{:.1f} points",
            run.host.command, run.configurations.size(), run.views.size(), run.settings.width,
            run.settings.height, gl.renderer, gl.backend, gl.version, run.host.lp_num_threads,
            run.workers, run.comparisons.size(), run.rule.resolution_points));
    result.results = runner::RunRender(*context.context, *prepared.config, run,
                                       ProgressCallbackFor(progress));
    progress.Finish();
    result.rendered = true;
    result.outcome.Add(result.results.diagnostics);

    result.json = runner::ResultsToJson(result.results);
    result.results_path = publisher->Target() / "results.json";
    const std::string write_error = base::WriteFileAtomically(publisher->Staging() / "results.json",
                                                              JsonText(result.json, 2) + "\n");
    if (!write_error.empty()) {
        result.outcome.Fail(Status::kEnvironment, write_error);
    } else if (result.results.write_errors.empty() && !Publish(*publisher, &result.outcome)) {
        return result;
    }
    for (const std::string& e : result.results.write_errors) {
        result.outcome.Fail(Status::kEnvironment, e);  // nothing published: the previous stays
    }
    if (result.outcome.Stopped()) {
        return result;
    }
    for (const runner::ConfigurationResult& r : result.results.configurations) {
        if (!r.Ok()) {
            result.outcome.status = Status::kInvalid;
        }
    }
    return result;
}

}  // namespace tidepool::pipeline
