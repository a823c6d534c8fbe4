// `tidepool run` (validate, render, stability catalogue, scene plans and report in one go):
// flags → options → library calls → print → exit code. Built into `tidepool-gl`.
#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/WorkerProcessPool.h"
#include "tidepool/lab/ScenePlanner.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Results.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

// `run` times through the one timing engine (TimingFlags): each configuration coarsely on its
// own, each compared pair of presets pair by pair until its interval is +/-1.5 points.
struct RunCommandOptions {
    std::string config = "variants.yaml";
    std::string name = "default";
    std::string out = "reports/out";
    std::string size = "640x480";
    TimingFlags timing;
    std::string backend = "auto";
    // Stability and plans run after the render so the report has every section. Their sizes
    // keep them to under a minute of the default run: the stability cases look for NaN,
    // Inf and bounds, which do not depend on resolution (64x48 is `tidepool stability`'s own
    // default); the plans compare images against the scene's full-effect image at 160x120
    // (above the 11x11 SSIM window many times over), each candidate timed against the full
    // effect pair by pair to +/-plan_resolution points (docs/SCENES.md).
    bool no_stability = false;
    bool no_plans = false;
    std::string stability_size = "64x48";
    std::string plan_size = "160x120";
    double plan_resolution = 3.0;
    tidepool::runner::FourierSettings fourier;
    CacheFlags cache;
};

// What a follow-up stage of `run` ended with.
struct StageOutcome {
    bool environment_error = false;  // could not run or write its file (message printed)
    int failures = 0;                // failed stability cases, or plans that missed the target
};

// The stability catalogue (the library calls `tidepool stability` makes) into
// render_dir/stability.json.
StageOutcome RunStabilityStage(runner::GlContext& context, const VariantConfig& config,
                               const std::vector<Variant>& variants, int width, int height,
                               const std::string& threads, const std::string& config_path,
                               const std::filesystem::path& render_dir) {
    using namespace tidepool::runner;
    StageOutcome outcome;
    const auto start = std::chrono::steady_clock::now();
    StabilityReport report;
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    for (const HardCase& hard_case : catalogue) {
        if (hard_case.kind == HardCaseKind::kCpu) {
            report.cases.push_back(RunCpuHardCase(hard_case));
        }
    }
    report.precision = RunPrecisionStudy();
    const GlEnvironment& env = context.Environment();
    report.environment = {
            {"backend", env.backend},    {"renderer", env.renderer},
            {"version", env.version},    {"mesa_version", env.mesa_version},
            {"lp_num_threads", threads}, {"size", fmt::format("{}x{}", width, height)},
            {"config", config_path}};
    GlStabilityOptions gl_options;
    gl_options.width = width;
    gl_options.height = height;
    std::string error;
    std::vector<StabilityCaseResult> gl_cases = RunGlHardCases(
            context, config, WaterVariantConfigurations(variants), catalogue, gl_options, &error);
    if (error.empty()) {
        for (StabilityCaseResult& r : gl_cases) {
            report.cases.push_back(std::move(r));
        }
        report.guards = MeasureGuards(context, config, gl_options, &error);
    }
    if (!error.empty()) {
        std::fprintf(stderr, "error: stability: %s\n", error.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    const std::filesystem::path path = render_dir / report::kStabilityFileName;
    if (std::string e = base::WriteFileAtomically(path, StabilityReportJson(report)); !e.empty()) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    for (const StabilityCaseResult& r : report.cases) {
        if (!r.passed) {
            ++outcome.failures;
            std::fprintf(stderr, "stability: FAIL %s (max_error %.3g, bound %.3g)\n",
                         r.name.c_str(), r.max_error, r.bound);
        }
    }
    // `render_dir` is the staging folder until the render folder is published: name the file only.
    std::fprintf(stderr,
                 "stability: %zu cases at %dx%d, %d failed, %.0f s; %s in the render folder\n",
                 report.cases.size(), width, height, outcome.failures,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 std::string(report::kStabilityFileName).c_str());
    return outcome;
}

// Every scenes/*.yaml planned (the library calls `tidepool plan --all` makes) into
// render_dir/plans.json, candidate images under render_dir/images/: Plan(i) plans scene i on
// whatever rendering thread runs it, Finish() writes the file once every scene is planned.
class PlanStage {
public:
    PlanStage(const VariantConfig& config, const runner::GlEnvironment& gl, int width, int height,
              const base::StoppingRule& rule, const std::filesystem::path& render_dir)
        : config_(config), start_(std::chrono::steady_clock::now()) {
        const std::filesystem::path scene_dir = config.base_dir / "scenes";
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(scene_dir, ec)) {
            if (entry.path().extension() == ".yaml") {
                scenes_.push_back(entry.path());
            }
        }
        std::sort(scenes_.begin(), scenes_.end());
        if (scenes_.empty()) {
            std::fprintf(stderr, "error: plans: no scenes/*.yaml in %s\n", scene_dir.c_str());
            outcome_.environment_error = true;
        }
        plans_.resize(scenes_.size());
        options_.settings.width = width;
        options_.settings.height = height;
        options_.rule = rule;
        const char* threads = std::getenv("LP_NUM_THREADS");
        options_.clock = runner::ChooseFrameClock(gl.renderer, threads != nullptr ? threads : "",
                                                  gl.timer_query)
                                 .clock;
        options_.out_dir = render_dir;
    }

    std::size_t SceneCount() const { return scenes_.size(); }

    // Plans scene `i` with `context` (current on the calling thread).
    void Plan(runner::GlContext& context, std::size_t i) {
        SceneResult scene = LoadSceneDescription(scenes_[i]);
        PrintDiagnostics(scene.diagnostics);
        if (!scene.scene) {
            return;  // a bad scene file cannot meet its target: Finish counts it
        }
        plans_[i] = runner::PlanScene(context, config_, *scene.scene, options_);
        PrintDiagnostics(plans_[i]->diagnostics);
    }

    // Writes plans.json beside results.json; the outcome counts scenes not planned or not met.
    StageOutcome Finish() {
        if (outcome_.environment_error) {
            return outcome_;
        }
        std::vector<runner::ScenePlan> plans;
        for (std::optional<runner::ScenePlan>& plan : plans_) {
            if (!plan) {
                ++outcome_.failures;
                continue;
            }
            if (plan->chosen < 0 || !plan->met) {
                ++outcome_.failures;
                std::fprintf(stderr, "plans: scene %s %s\n", plan->scene.name.c_str(),
                             plan->chosen < 0 ? "could not be planned" : "misses its target");
            }
            plans.push_back(std::move(*plan));
        }
        const std::filesystem::path path = options_.out_dir / report::kPlansFileName;
        if (std::string e = base::WriteFileAtomically(
                    path, JsonText(runner::PlansToJson(plans, options_), 2) + "\n");
            !e.empty()) {
            std::fprintf(stderr, "error: %s\n", e.c_str());
            outcome_.environment_error = true;
            return outcome_;
        }
        std::fprintf(
                stderr,
                "plans: %zu scenes at %dx%d, candidates timed to +/-%.1f points, %d "
                "not met, done after %.0f s; %s in the render folder\n",
                plans.size(), options_.settings.width, options_.settings.height,
                options_.rule.resolution_points, outcome_.failures,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(),
                std::string(report::kPlansFileName).c_str());
        return outcome_;
    }

private:
    const VariantConfig& config_;
    std::chrono::steady_clock::time_point start_;
    std::vector<std::filesystem::path> scenes_;
    std::vector<std::optional<runner::ScenePlan>> plans_;  // by scene; empty when not planned
    runner::PlanOptions options_;
    StageOutcome outcome_;
};

// What the stages beside the render do: sizes and the plans' stopping rule.
struct SideStages {
    bool stability = true;
    bool plans = true;
    int stability_width = 0;
    int stability_height = 0;
    int plan_width = 0;
    int plan_height = 0;
    base::StoppingRule plan_rule;
};

// How the render (failures: configurations that failed) and the stages beside it ended.
struct StageEnds {
    StageOutcome render;
    StageOutcome side;
};

// 2. The render: images at every view, each configuration's coarse time and the comparisons,
// into run.out_dir/results.json.
StageOutcome RenderStage(const VariantConfig& config, const runner::RunOptions& run,
                         runner::BackendKind backend, const std::filesystem::path& results_path) {
    using namespace tidepool::runner;
    StageOutcome outcome;
    GlContextResult context = CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: %s\n", context.error.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    std::fprintf(stderr,
                 "render: %zu configurations x %zu views at %dx%d on %s, "
                 "LP_NUM_THREADS=%s, %d workers, %zu comparisons to +/-%.1f points\n",
                 run.configurations.size(), run.views.size(), run.settings.width,
                 run.settings.height, context.context->Environment().renderer.c_str(),
                 run.host.lp_num_threads.c_str(), run.workers, run.comparisons.size(),
                 run.rule.resolution_points);
    const RunResults results = RunRender(*context.context, config, run, MakeProgressPrinter());
    FinishProgress();
    PrintDiagnostics(results.diagnostics);
    for (const std::string& e : results.write_errors) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
    }
    if (std::string error = base::WriteFileAtomically(run.out_dir / "results.json",
                                                      JsonText(ResultsToJson(results), 2) + "\n");
        !error.empty() || !results.write_errors.empty()) {
        if (!error.empty()) {
            std::fprintf(stderr, "error: %s\n", error.c_str());
        }
        outcome.environment_error = true;
        return outcome;
    }
    for (const ConfigurationResult& r : results.configurations) {
        outcome.failures += r.Ok() ? 0 : 1;
    }
    std::fprintf(stderr, "render: %zu configurations, %d failed, %.0f s; results in %s\n",
                 results.configurations.size(), outcome.failures, results.wall_seconds,
                 results_path.c_str());
    return outcome;
}

// 3. The stability catalogue and 4. the scene plans, one after the other on one context.
StageOutcome SideStage(const VariantConfig& config, const std::vector<Variant>& variants,
                       const SideStages& side, runner::BackendKind backend,
                       const std::string& threads, const std::string& config_path,
                       const std::filesystem::path& render_dir) {
    const auto start = std::chrono::steady_clock::now();
    StageOutcome outcome;
    runner::GlContextResult context = runner::CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: stability and plans: %s\n", context.error.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    if (side.stability) {
        outcome = RunStabilityStage(*context.context, config, variants, side.stability_width,
                                    side.stability_height, threads, config_path, render_dir);
    }
    if (side.plans) {
        PlanStage plans(config, context.context->Environment(), side.plan_width, side.plan_height,
                        side.plan_rule, render_dir);
        for (std::size_t i = 0; i < plans.SceneCount(); ++i) {
            plans.Plan(*context.context, i);
        }
        const StageOutcome planned = plans.Finish();
        outcome.environment_error = outcome.environment_error || planned.environment_error;
        outcome.failures += planned.failures;
    }
    std::fprintf(stderr, "stability and plans: %.0f s in a second process, beside the render\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return outcome;
}

// Runs the render and, when asked for, the stability and plan stages at the same time, each in a
// process of its own. Processes rather than threads: llvmpipe's contexts in one process share
// one rasteriser lock, so a second rendering thread bought no throughput (one thread rendered
// the default matrix in 83 s, two in 122 s) and frames timed beside it moved by more than their
// interval (the low-resolution water row read -4% quiet and 0% loaded). A second process has a
// rasteriser of its own. Must be called while the process has one thread (fork).
StageEnds RenderBesideSideStages(const VariantConfig& config, const std::vector<Variant>& variants,
                                 const runner::RunOptions& run, runner::BackendKind backend,
                                 const SideStages& side, const std::string& config_path,
                                 const std::filesystem::path& results_path) {
    std::vector<std::function<StageOutcome()>> stages;
    stages.emplace_back([&] { return RenderStage(config, run, backend, results_path); });
    if (side.stability || side.plans) {
        stages.emplace_back([&] {
            return SideStage(config, variants, side, backend, run.host.lp_num_threads, config_path,
                             run.out_dir);
        });
    }
    const std::vector<base::WorkerItemResult> ended = base::RunInWorkerProcesses(
            stages.size(), static_cast<int>(stages.size()), base::WorkerLimits{},
            [&](std::size_t i, const base::ProgressNote&) {
                const StageOutcome outcome = stages[i]();
                std::fflush(nullptr);  // the worker process ends with _exit
                return fmt::format("{} {}", outcome.environment_error ? 1 : 0, outcome.failures);
            });
    StageEnds ends;
    for (std::size_t i = 0; i < ended.size(); ++i) {
        StageOutcome& outcome = i == 0 ? ends.render : ends.side;
        int environment_error = 1;
        if (ended[i].failure != base::WorkerFailure::kNone ||
            std::sscanf(ended[i].payload.c_str(), "%d %d", &environment_error, &outcome.failures) !=
                    2) {
            std::fprintf(stderr, "error: the %s process ended without a result: %s\n",
                         i == 0 ? "render" : "stability and plans", ended[i].detail.c_str());
        }
        outcome.environment_error = environment_error != 0;
    }
    return ends;
}

int RunAll(const RunCommandOptions& options) {
    using namespace tidepool::runner;
    const auto start = std::chrono::steady_clock::now();
    int width = 0;
    int height = 0;
    if (!ParseSizeOption("--size", options.size, 1, &width, &height)) {
        return kExitUsage;
    }
    BackendKind backend = BackendKind::kAuto;
    if (!ParseBackendOption(options.backend, &backend)) {
        return kExitUsage;
    }
    if (!CheckTimingFlags(options.timing)) {
        return kExitUsage;
    }
    if (!(options.plan_resolution > 0 && options.plan_resolution <= 50)) {
        std::fprintf(stderr,
                     "error: --plan-resolution must be above 0 and at most 50 percent "
                     "points, not %g\n",
                     options.plan_resolution);
        return kExitUsage;
    }
    if (!CheckFourierOptions(options.fourier)) {
        return kExitUsage;
    }
    int stability_width = 0;
    int stability_height = 0;
    if (!ParseSizeOption("--stability-size", options.stability_size, 1, &stability_width,
                         &stability_height)) {
        return kExitUsage;
    }
    int plan_width = 0;
    int plan_height = 0;
    // SSIM needs its 11x11 window inside the image, as `tidepool plan` requires.
    if (!ParseSizeOption("--plan-size", options.plan_size, 16, &plan_width, &plan_height)) {
        return kExitUsage;
    }
    if (options.name.empty() || options.name.find('/') != std::string::npos ||
        options.name == "manifest" || options.name == "render" || options.name[0] == '.') {
        std::fprintf(stderr,
                     "error: --name must be a plain folder name other than 'manifest' "
                     "and 'render', not '%s'\n",
                     options.name.c_str());
        return kExitUsage;
    }
    const std::filesystem::path out(options.out);
    const std::filesystem::path manifest_path = out / "manifest" / "manifest.json";
    const std::filesystem::path render_dir = out / "render";

    // 1. Validate: the manifest.
    const LoadedMatrix loaded = LoadAndExpand(options.config);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    const VariantConfig& config = *loaded.config;
    const ExpansionResult& expansion = loaded.expansion;
    // Both outputs are checked before any work: neither a user's manifest.json nor a render
    // folder tidepool did not write is ever replaced.
    if (const int code = WriteManifestInto(manifest_path.parent_path(), "", true); code != 0) {
        return code;
    }
    // The render folder (images, results.json, stability.json, plans.json) is staged whole and
    // published before the report reads it, so a killed run leaves the previous one intact.
    int begin_code = kExitOk;
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(render_dir, "tidepool run", &begin_code);
    if (!publisher) {
        return begin_code;
    }
    const std::filesystem::path& staging = publisher->Staging();
    ValidationOptions validation_options;
    validation_options.jobs = DefaultJobs();
    validation_options.targets = config.targets;
    const std::unique_ptr<base::ContentCache> cache = OpenCache(options.cache);
    validation_options.cache = cache.get();
    const ValidationReport validation =
            ValidateVariants(config, expansion.variants, validation_options);
    WarnAboutCache(cache.get());
    PrintDiagnostics(validation.diagnostics);
    for (const VariantVerdict& verdict : validation.verdicts) {
        PrintDiagnostics(verdict.diagnostics);
    }
    const nlohmann::json manifest = BuildManifest(config, expansion, &validation);
    if (const int code =
                WriteManifestInto(manifest_path.parent_path(), JsonText(manifest, 2) + "\n");
        code != 0) {
        return code;
    }
    std::fprintf(stderr, "validate: %zu variants, %llu pruned, %d invalid; manifest in %s\n",
                 expansion.variants.size(), static_cast<unsigned long long>(expansion.pruned_total),
                 validation.InvalidCount(), manifest_path.c_str());

    // 2. Render, and beside it 3. numerical stability and 4. scene plans, each in a process of
    // its own with its own GL context, both writing into the staging folder.
    const ConfigurationSet configurations = BuildDefaultConfigurations(config, expansion.variants);
    PrintDiagnostics(configurations.diagnostics);
    if (HasErrors(configurations.diagnostics) || configurations.configurations.empty()) {
        return kExitUsage;
    }
    RunOptions run;
    run.configurations = configurations.configurations;
    run.views = DefaultViews();
    run.settings.width = width;
    run.settings.height = height;
    run.settings.fourier = options.fourier;
    run.out_dir = staging;
    run.config_path = options.config;
    run.host = DescribeHost("run", options.config);
    ApplyTimingFlags(options.timing, backend, &run);
    SideStages side;
    side.stability = !options.no_stability;
    side.plans = !options.no_plans;
    side.stability_width = stability_width;
    side.stability_height = stability_height;
    side.plan_width = plan_width;
    side.plan_height = plan_height;
    side.plan_rule = run.rule;
    side.plan_rule.resolution_points = options.plan_resolution;
    const std::filesystem::path results_path = render_dir / "results.json";
    const StageEnds ends = RenderBesideSideStages(config, expansion.variants, run, backend, side,
                                                  options.config, results_path);
    if (ends.render.environment_error) {
        return kExitEnvironment;
    }
    if (const base::PublishError e = publisher->Publish(); e.Failed()) {
        std::fprintf(stderr, "error: %s\n", e.message.c_str());
        return PublishExitCode(e);
    }

    // 5. Report (written even when a stage above failed: it says what is missing and why).
    const int report_code = BuildAndWriteReport(manifest_path, results_path, options.name, out);
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "run: %.0f s in all\n", seconds);
    if (report_code == kExitUsage || report_code == kExitEnvironment) {
        return report_code;
    }
    if (ends.side.environment_error) {
        return kExitEnvironment;
    }
    return ends.render.failures > 0 || validation.InvalidCount() > 0 ||
                           report_code == kExitShaderErrors || ends.side.failures > 0
                   ? kExitShaderErrors
                   : kExitOk;
}

}  // namespace

void RegisterRunCommand(CLI::App& app, int& exit_code) {
    auto run_options = std::make_shared<RunCommandOptions>();
    CLI::App* run = app.add_subcommand("run", GlCommandSummary("run"));
    run->add_option("--config", run_options->config, "variants.yaml to read")
            ->capture_default_str();
    run->add_option("--name", run_options->name, "report folder name under --out")
            ->capture_default_str();
    run->add_option("--out", run_options->out, "output folder")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    run->add_option("--size", run_options->size, "render size WxH")->capture_default_str();
    AddTimingFlags(run, &run_options->timing);
    run->add_option("--backend", run_options->backend, "auto (EGL, then OSMesa), egl or osmesa")
            ->capture_default_str();
    AddFourierOptions(run, &run_options->fourier);
    run->add_flag("--no-stability", run_options->no_stability,
                  "skip the numerical-stability catalogue (the report then says how to make it)");
    run->add_flag("--no-plans", run_options->no_plans,
                  "skip the scene plans (the report then says how to make them)");
    run->add_option("--stability-size", run_options->stability_size,
                    "render size WxH of the stability GL cases")
            ->capture_default_str();
    run->add_option("--plan-size", run_options->plan_size, "render size WxH of the scene plans")
            ->capture_default_str();
    run->add_option("--plan-resolution", run_options->plan_resolution,
                    "time each plan candidate against the full effect to this half-width "
                    "(percent points)")
            ->capture_default_str();
    AddCacheFlags(run, &run_options->cache);
    run->callback([run_options, &exit_code] { exit_code = RunAll(*run_options); });
}

}  // namespace tidepool::cli
