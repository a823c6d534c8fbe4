#include "tidepool/pipeline/RunStage.h"

#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/SceneDescription.h"
#include "tidepool/base/SharedClaims.h"
#include "tidepool/base/WorkerProcessPool.h"
#include "tidepool/lab/ScenePlanner.h"
#include "tidepool/pipeline/Host.h"
#include "tidepool/pipeline/MatrixLoading.h"
#include "tidepool/pipeline/OutputFiles.h"
#include "tidepool/pipeline/PlanStage.h"
#include "tidepool/pipeline/RenderStage.h"
#include "tidepool/pipeline/StabilityStage.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <system_error>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace tidepool::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// How a stage run in a process of its own ended: sent back to the parent as "STATUS FAILURES".
struct StageEnd {
    Status status = Status::kOk;  // kEnvironment: it could not run or write its file
    int failures = 0;  // configurations that failed, or stability cases and plans that failed
};

// The render: images at every view, each configuration's coarse time and the comparisons,
// into run.out_dir/results.json.
StageEnd RenderInto(const VariantConfig& config, const runner::RunOptions& run,
                    runner::BackendKind backend, const std::filesystem::path& results_path,
                    ProgressSink& progress) {
    StageEnd end;
    runner::GlContextResult context = runner::CreateGlContext(backend);
    if (!context.context) {
        progress.Tell({Message(Severity::kError, context.error)});
        end.status = Status::kEnvironment;
        return end;
    }
    progress.Begin(fmt::format(
            "render: {} configurations x {} views at {}x{} on {}, LP_NUM_THREADS={}, {} workers, "
            "{} comparisons to +/-{:.1f} points",
            run.configurations.size(), run.views.size(), run.settings.width, run.settings.height,
            context.context->Environment().renderer, run.host.lp_num_threads, run.workers,
            run.comparisons.size(), run.rule.resolution_points));
    const runner::RunResults results =
            runner::RunRender(*context.context, config, run, ProgressCallbackFor(progress));
    progress.Finish();
    progress.Tell(results.diagnostics);
    Outcome written;
    for (const std::string& e : results.write_errors) {
        written.Fail(Status::kEnvironment, e);
    }
    if (!WriteFile(run.out_dir / "results.json",
                   stagefiles::ResultsFileText(runner::ToResultsFile(results)), &written) ||
        written.Stopped()) {
        progress.Tell(written.diagnostics);
        end.status = Status::kEnvironment;
        return end;
    }
    for (const runner::ConfigurationResult& r : results.configurations) {
        end.failures += r.Ok() ? 0 : 1;
    }
    progress.Line(fmt::format(
            "render: {} configurations, {} failed, {:.0f} s; results in {}{}",
            results.configurations.size(), end.failures, results.wall_seconds,
            results_path.string(),
            run.shared.claims != nullptr
                    ? fmt::format(" ({} configurations' images and {} "
                                  "comparisons done by the second process)",
                                  results.shared_configurations, results.SharedComparisons())
                    : ""));
    return end;
}

// The stability catalogue into render_dir/stability.json.
StageEnd StabilityInto(runner::GlContext& context, const VariantConfig& config,
                       const std::vector<Variant>& variants, const RunRequest& request,
                       const std::string& threads, const std::filesystem::path& render_dir,
                       const std::function<void(double share_done)>& on_progress,
                       ProgressSink& progress) {
    StageEnd end;
    const Clock::time_point start = Clock::now();
    StabilityRun run;
    run.width = request.stability_width;
    run.height = request.stability_height;
    run.size = fmt::format("{}x{}", run.width, run.height);
    run.lp_num_threads = threads;
    run.config_path = request.config;
    run.on_progress = on_progress;
    std::string error;
    const lab::StabilityReport report =
            RunStabilityCatalogue(context, config, variants, run, &error);
    Outcome written;
    if (!error.empty()) {
        written.Fail(Status::kEnvironment, "stability: " + error);
    } else {
        WriteFile(render_dir / stagefiles::kStabilityFileName,
                  stagefiles::StabilityFileText(report), &written);
    }
    if (written.Stopped()) {
        progress.Tell(written.diagnostics);
        end.status = Status::kEnvironment;
        return end;
    }
    for (const lab::StabilityCaseResult& r : report.cases) {
        if (!r.passed) {
            ++end.failures;
            progress.Line(fmt::format("stability: FAIL {} (max_error {:.3g}, bound {:.3g})", r.name,
                                      r.max_error, r.bound));
        }
    }
    // render_dir is the staging folder until the render folder is published: name the file only.
    progress.Line(
            fmt::format("stability: {} cases at {}x{}, {} failed, {:.0f} s; {} in the render "
                        "folder",
                        report.cases.size(), run.width, run.height, end.failures,
                        SecondsSince(start), stagefiles::kStabilityFileName));
    return end;
}

// Whether the configuration has scenes (scenes/*.yaml beside it) and every one of them loads;
// otherwise tells why and how to go on without them.
bool ScenesLoad(const VariantConfig& config, ProgressSink& progress) {
    const std::filesystem::path folder = config.base_dir / "scenes";
    const std::vector<std::filesystem::path> scenes = SceneFilesIn(folder);
    if (scenes.empty()) {
        progress.Tell({Message(Severity::kError,
                               fmt::format("plans: no scenes/*.yaml in {}; add one, or run with "
                                           "--no-plans",
                                           folder.string()))});
        return false;
    }
    bool all = true;
    for (const std::filesystem::path& path : scenes) {
        SceneResult scene = LoadSceneDescription(path);
        progress.Tell(scene.diagnostics);
        all = all && scene.scene.has_value();
    }
    return all;
}

// Every scenes/*.yaml planned into render_dir/plans.json, the candidates' images under
// render_dir/images/.
StageEnd PlansInto(runner::GlContext& context, const VariantConfig& config,
                   const RunRequest& request, const runner::RunOptions& run,
                   const std::function<void(double share_done)>& on_progress,
                   ProgressSink& progress) {
    const std::filesystem::path& render_dir = run.out_dir;
    StageEnd end;
    const Clock::time_point start = Clock::now();
    const std::vector<std::filesystem::path> scenes = SceneFilesIn(config.base_dir / "scenes");
    if (scenes.empty()) {
        progress.Tell(
                {Message(Severity::kError, fmt::format("plans: no scenes/*.yaml in {}",
                                                       (config.base_dir / "scenes").string()))});
        end.status = Status::kEnvironment;
        return end;
    }
    lab::PlanOptions options;
    options.settings.width = request.plan_width;
    options.settings.height = request.plan_height;
    options.rule = run.rule;
    options.rule.resolution_points = request.plan_resolution;
    const runner::GlEnvironment& gl = context.Environment();
    options.clock =
            runner::ChooseFrameClock(gl.renderer, run.host.lp_num_threads, gl.timer_query).clock;
    options.out_dir = render_dir;
    options.validated = run.validated;  // the candidates' verdicts, from the run's validation
    std::vector<lab::ScenePlan> plans;
    for (const std::filesystem::path& path : scenes) {
        SceneResult scene = LoadSceneDescription(path);
        progress.Tell(scene.diagnostics);
        if (!scene.scene) {
            ++end.failures;  // a bad scene file cannot meet its target
            continue;
        }
        lab::ScenePlan plan = lab::PlanScene(context, config, *scene.scene, options);
        progress.Tell(plan.diagnostics);
        if (plan.chosen < 0 || !plan.met) {
            ++end.failures;
            progress.Line(
                    fmt::format("plans: scene {} {}", plan.scene.name,
                                plan.chosen < 0 ? "could not be planned" : "misses its target"));
        }
        plans.push_back(std::move(plan));
        if (on_progress) {
            on_progress(static_cast<double>(plans.size()) / static_cast<double>(scenes.size()));
        }
    }
    if (const std::string error = stagefiles::WritePlansFile(
                lab::PlansFileFor(plans, options), render_dir / stagefiles::kPlansFileName);
        !error.empty()) {
        Outcome written;
        written.Fail(Status::kEnvironment, error);
        progress.Tell(written.diagnostics);
        end.status = Status::kEnvironment;
        return end;
    }
    progress.Line(
            fmt::format("plans: {} scenes at {}x{}, candidates timed to +/-{:.1f} points, {} "
                        "not met, done after {:.0f} s; {} in the render folder",
                        plans.size(), options.settings.width, options.settings.height,
                        options.rule.resolution_points, end.failures, SecondsSince(start),
                        stagefiles::kPlansFileName));
    return end;
}

// The stability catalogue, the scene plans, then units off the end of the render's work list, on
// one context of their own.
StageEnd BesideTheRender(const VariantConfig& config, const std::vector<Variant>& variants,
                         const RunRequest& request, const runner::RunOptions& run,
                         ProgressSink& progress) {
    const Clock::time_point start = Clock::now();
    StageEnd end;
    runner::GlContextResult context = runner::CreateGlContext(request.backend);
    if (!context.context) {
        progress.Tell({Message(Severity::kError, "stability and plans: " + context.error)});
        end.status = Status::kEnvironment;
        return end;
    }
    const std::string& threads = run.host.lp_num_threads;
    JoinForecast forecast(run.shared.claims, request.stability, request.plans);
    if (request.stability) {
        const StageEnd stable = StabilityInto(
                *context.context, config, variants, request, threads, run.out_dir,
                [&](double share) { forecast.Stability(share); }, progress);
        end.status = stable.status == Status::kEnvironment ? stable.status : end.status;
        end.failures += stable.failures;
    }
    if (request.plans) {
        const StageEnd planned = PlansInto(
                *context.context, config, request, run,
                [&](double share) { forecast.Plans(share); }, progress);
        end.status = planned.status == Status::kEnvironment ? planned.status : end.status;
        end.failures += planned.failures;
    }
    progress.Line(
            fmt::format("stability and plans: {:.0f} s in a second process, beside the "
                        "render",
                        SecondsSince(start)));
    if (run.shared.claims != nullptr) {
        // Then units off the end of the render's work list: the stability catalogue and the plans
        // are long and can only run here, configurations and comparisons are units either
        // process can take, so taking them last lets both processes end together.
        const Clock::time_point units_start = Clock::now();
        const runner::SharedUnitsDone units =
                runner::RenderSharedUnits(*context.context, config, run);
        if (!units.error.empty()) {
            progress.Tell(
                    {Message(Severity::kWarning, "units beside the render: " + units.error +
                                                         "; the render process does every unit")});
        }
        for (const std::string& e : units.write_errors) {
            progress.Tell({Message(Severity::kError, e)});
            end.status = Status::kEnvironment;
        }
        progress.Line(fmt::format(
                "units beside the render: {} configurations' images and {} comparisons, {:.0f} s",
                units.configurations, units.comparisons, SecondsSince(units_start)));
    }
    return end;
}

// The render and, when asked for, the stability and plan stages at the same time, each in a
// process of its own. Processes rather than threads: llvmpipe's contexts in one process share
// one rasteriser lock, so a second rendering thread bought no throughput (one thread rendered
// the default matrix in 83 s, two in 122 s) and frames timed beside it moved by more than their
// interval (the low-resolution water row read -4% quiet and 0% loaded). A second process has a
// rasteriser of its own. The first end is the render's, the second the other stages'.
std::pair<StageEnd, StageEnd> RenderBesideTheOtherStages(const VariantConfig& config,
                                                         const std::vector<Variant>& variants,
                                                         const RunRequest& request,
                                                         const runner::RunOptions& run,
                                                         const std::filesystem::path& results_path,
                                                         ProgressSink& progress) {
    // The second process takes units off the render's work list once its own stages are done,
    // so that neither core idles while the other renders.
    runner::RunOptions shared_run = run;
    std::unique_ptr<base::SharedClaims> claims;
    if (request.stability || request.plans) {
        // A unit per configuration, then one per comparison; none: no sharing.
        claims = base::SharedClaims::Create(run.configurations.size() + run.comparisons.size());
        if (claims) {
            shared_run.shared = {claims.get(), run.out_dir / ".second-process"};
        }
    }
    std::vector<std::function<StageEnd()>> stages;
    stages.emplace_back([&] {
        return RenderInto(config, shared_run, request.backend, results_path, progress);
    });
    if (request.stability || request.plans) {
        stages.emplace_back(
                [&] { return BesideTheRender(config, variants, request, shared_run, progress); });
    }
    const std::vector<base::WorkerItemResult> ended = base::RunInWorkerProcesses(
            stages.size(), static_cast<int>(stages.size()), base::WorkerLimits{},
            [&](std::size_t i, const base::ProgressNote&) {
                const StageEnd end = stages[i]();
                std::fflush(nullptr);  // the worker process ends with _exit
                return fmt::format("{} {}", static_cast<int>(end.status), end.failures);
            });
    if (claims) {
        // Each unit's results are in results.json now; the folder must not be published.
        std::error_code ignored;
        std::filesystem::remove_all(shared_run.shared.folder, ignored);
    }
    std::pair<StageEnd, StageEnd> ends;
    for (std::size_t i = 0; i < ended.size(); ++i) {
        StageEnd& end = i == 0 ? ends.first : ends.second;
        int status = static_cast<int>(Status::kEnvironment);
        if (ended[i].failure != base::WorkerFailure::kNone ||
            std::sscanf(ended[i].payload.c_str(), "%d %d", &status, &end.failures) != 2) {
            progress.Tell({Message(
                    Severity::kError,
                    fmt::format("the {} process ended without a result: {}",
                                i == 0 ? "render" : "stability and plans", ended[i].detail))});
        }
        end.status = static_cast<Status>(status);
    }
    return ends;
}

}  // namespace

JoinForecast::JoinForecast(base::SharedClaims* claims, bool stability, bool plans,
                           Clock::time_point start)
    : claims_(claims),
      stability_share_(!plans      ? 1.0
                       : stability ? kStabilityShareOfStages
                                   : 0.0),
      start_(start) {}

void JoinForecast::Stability(double share, Clock::time_point now) const {
    Say(stability_share_ * share, now);
}

void JoinForecast::Plans(double share, Clock::time_point now) const {
    Say(stability_share_ + (1.0 - stability_share_) * share, now);
}

void JoinForecast::Say(double share, Clock::time_point now) const {
    if (claims_ == nullptr || share <= 0) {
        return;
    }
    claims_->Beat();  // alive: the render counts on a forecast only while it is renewed
    claims_->ExpectHelperAt(start_ + std::chrono::duration_cast<Clock::duration>(
                                             (now - start_) / std::min(share, 1.0)));
}

RunResult Run(const RunRequest& request, ProgressSink& progress) {
    RunResult result;
    Outcome& outcome = result.outcome;
    result.manifest_path = request.out / "manifest" / "manifest.json";
    const std::filesystem::path render_dir = request.out / "render";
    result.results_path = render_dir / "results.json";

    // 1. Validate: the manifest.
    LoadedMatrix loaded = LoadMatrix(request.config);
    progress.Tell(loaded.outcome.diagnostics);
    if (!loaded.config) {
        outcome.status = loaded.outcome.status;
        return result;
    }
    const VariantConfig& config = *loaded.config;
    const ExpansionResult& expansion = loaded.expansion;
    // Both outputs are checked before any work: neither a user's manifest.json nor a render
    // folder tidepool did not write is ever replaced.
    if (Outcome check = WriteManifest(result.manifest_path.parent_path(), "", true);
        check.Stopped()) {
        progress.Tell(check.diagnostics);
        outcome.status = check.status;
        return result;
    }
    // Every scene is read before any work, as `plan` reads its own: a bad one found beside the
    // render, minutes in, was counted as a plan that missed its target.
    if (request.plans && !ScenesLoad(config, progress)) {
        outcome.status = Status::kUsage;
        return result;
    }
    // The render folder (images, results.json, stability.json, plans.json) is staged whole and
    // published before the report reads it, so a killed run leaves the previous one intact.
    Outcome publishing;
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(render_dir, "tidepool run", &publishing);
    progress.Tell(publishing.diagnostics);
    if (!publisher) {
        outcome.status = publishing.status;
        return result;
    }
    ValidationOptions validation_options;
    validation_options.jobs = DefaultJobs();
    validation_options.targets = config.targets;
    const std::unique_ptr<base::ContentCache> cache = OpenValidationCache(request.cache);
    validation_options.cache = cache.get();
    const ValidationReport validation =
            ValidateVariants(config, expansion.variants, validation_options);
    if (const std::optional<Diagnostic> warning = CacheWarning(cache.get())) {
        progress.Tell({*warning});
    }
    progress.Tell(validation.diagnostics);
    for (const VariantVerdict& verdict : validation.verdicts) {
        progress.Tell(verdict.diagnostics);
    }
    const nlohmann::json manifest = BuildManifest(config, expansion, &validation);
    if (Outcome written =
                WriteManifest(result.manifest_path.parent_path(), JsonText(manifest, 2) + "\n");
        written.Stopped()) {
        progress.Tell(written.diagnostics);
        outcome.status = written.status;
        return result;
    }
    progress.Line(fmt::format("validate: {} variants, {} pruned, {} invalid; manifest in {}",
                              expansion.variants.size(), expansion.pruned_total,
                              validation.InvalidCount(), result.manifest_path.string()));

    // 2. The render, and beside it 3. the stability catalogue and 4. the scene plans, each in a
    // process of its own with its own GL context, all writing into the staging folder.
    const runner::ConfigurationSet configurations =
            runner::BuildDefaultConfigurations(config, expansion.variants);
    progress.Tell(configurations.diagnostics);
    if (HasErrors(configurations.diagnostics) || configurations.configurations.empty()) {
        outcome.status = Status::kUsage;
        return result;
    }
    runner::RunOptions run;
    run.configurations = configurations.configurations;
    run.views = runner::DefaultViews();
    run.settings.width = request.width;
    run.settings.height = request.height;
    run.settings.fourier = request.fourier;
    run.out_dir = publisher->Staging();
    run.config_path = request.config;
    // The render's glslang/Mesa comparison and the planner take glslang's verdicts from the
    // validation above, which wrote the manifest, instead of validating again.
    run.validated = &validation;
    if (request.prepare_timing) {
        request.prepare_timing(&run);
    }
    const auto [render, beside] = RenderBesideTheOtherStages(config, expansion.variants, request,
                                                             run, result.results_path, progress);
    if (render.status == Status::kEnvironment) {
        outcome.status = Status::kEnvironment;
        return result;
    }
    Outcome published;
    if (!Publish(*publisher, &published)) {
        progress.Tell(published.diagnostics);
        outcome.status = published.status;
        return result;
    }
    result.rendered = true;
    if (beside.status == Status::kEnvironment) {
        outcome.status = Status::kEnvironment;
    } else if (render.failures > 0 || validation.InvalidCount() > 0 || beside.failures > 0) {
        outcome.status = Status::kInvalid;
    }
    return result;
}

}  // namespace tidepool::pipeline
