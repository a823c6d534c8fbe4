// `tidepool report` (build the report from a saved manifest and results) and `tidepool run`
// (validate, render, stability catalogue, scene plans and report in one go): flags → options →
// library calls → print → exit code.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "CliSupport.h"
#include "Commands.h"
#include "tidepool/AtomicFile.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/report/ImageMetrics.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Results.h"
#include "tidepool/runner/ScenePlanner.h"
#include "tidepool/runner/StabilityReport.h"

namespace tidepool::cli {
namespace {

struct ReportCommandOptions {
    std::string manifest = "reports/out/manifest/manifest.json";
    std::string results = "reports/out/render/results.json";
    std::string name = "default";
    std::string out = "reports/out";
};

// `run` renders with more rounds than `render` so the paired intervals mean something: 20 rounds
// of 2 frames (40 samples; 20 paired ratios per comparison, above the 10 that percentile
// intervals of a median need, see Statistics.h) after 2 warm-up frames. Measured on the default
// matrix (146 configurations x 4 views at 640x480, 2 quiet cores): about 6 minutes for the whole
// run, 5 of them rendering. More rounds of fewer frames pair baseline and candidate more often,
// which is what cancels drift; 12 rounds left verdicts flipping between runs.
struct RunCommandOptions {
    std::string config = "variants.yaml";
    std::string name = "default";
    std::string out = "reports/out";
    std::string size = "640x480";
    int rounds = 20;
    int frames = 2;
    // The 14 preset configurations decide the whitepaper verdicts; with 2 frames a round their
    // per-round medians were noisy enough that two quiet runs disagreed on 3 of 11 verdicts.
    int preset_frames = 8;
    int warmup = 2;
    std::string backend = "auto";
    int threads = 2;
    // Stability and plans run after the render so the report has every section. Their sizes
    // keep them to under a minute of the default run: the stability cases look for NaN,
    // Inf and bounds, which do not depend on resolution (64x48 is `tidepool stability`'s own
    // default); the plans compare images against the scene's full-effect image at 160x120
    // (above the 11x11 SSIM window many times over) with 3 rounds of 2 frames, enough to rank
    // candidates whose times differ by tens of percent (docs/SCENES.md), not to quote them.
    bool no_stability = false;
    bool no_plans = false;
    std::string stability_size = "64x48";
    std::string plan_size = "160x120";
    int plan_rounds = 3;
    int plan_frames = 2;
    tidepool::runner::FourierSettings fourier;
};

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buffer[32] = {0};
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

// Loads the inputs, builds and writes the report, prints the table; returns the exit code.
int BuildAndWriteReport(const std::filesystem::path& manifest, const std::filesystem::path& results,
                        const std::string& name, const std::filesystem::path& out) {
    using namespace tidepool::report;
    const auto start = std::chrono::steady_clock::now();
    ReportInputsResult loaded = LoadReportInputs(manifest, results);
    if (!loaded.inputs) {
        std::fprintf(stderr, "error: %s\n", loaded.error.c_str());
        return kExitUsage;
    }
    if (!loaded.inputs->stability_error.empty()) {
        std::fprintf(stderr, "warning: %s (the report says so)\n",
                     loaded.inputs->stability_error.c_str());
    }
    if (!loaded.inputs->plans_error.empty()) {
        std::fprintf(stderr, "warning: %s (the report says so)\n",
                     loaded.inputs->plans_error.c_str());
    }
    ReportOptions options;
    options.name = name;
    options.generated_utc = UtcNow();
    ReportModelResult model = BuildReportModel(*loaded.inputs, options);
    if (!model.model) {
        std::fprintf(stderr, "error: %s\n", model.error.c_str());
        return kExitUsage;
    }
    const WrittenReport written = WriteReport(*model.model, out);
    if (!written.error.empty()) {
        std::fprintf(stderr, "error: %s\n", written.error.c_str());
        return kExitUsage;
    }
    std::printf("%s", WhitepaperTableText(*model.model).c_str());
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("report: %zu configurations (%d failed), %zu on the Pareto frontier, static-cost "
                "Spearman rho %.3f; written in %.1f s to %s/ (index.html %.1f MB%s, report.md, "
                "data.json, %zu files)\n",
                model.model->accuracy.size(), model.model->failed_configurations,
                model.model->frontier.size(), model.model->static_cost.spearman_rho, seconds,
                written.folder.c_str(), static_cast<double>(written.html_bytes) / 1e6,
                written.image_downscale > 1
                        ? fmt::format(", images downscaled {}x", written.image_downscale).c_str()
                        : "",
                written.files.size());
    return model.model->failed_configurations > 0 ? kExitShaderErrors : kExitOk;
}

int RunReport(const ReportCommandOptions& options) {
    return BuildAndWriteReport(options.manifest, options.results, options.name, options.out);
}

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
    report.environment = {{"backend", env.backend},
                          {"renderer", env.renderer},
                          {"version", env.version},
                          {"mesa_version", env.mesa_version},
                          {"lp_num_threads", threads},
                          {"size", fmt::format("{}x{}", width, height)},
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
    if (std::string e = WriteFileAtomically(path, StabilityReportJson(report)); !e.empty()) {
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
    std::fprintf(stderr, "stability: %zu cases at %dx%d, %d failed, %.0f s; %s\n",
                 report.cases.size(), width, height, outcome.failures,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 path.c_str());
    return outcome;
}

// Image error with the report's metrics, as `tidepool plan` measures it.
runner::ImageError MeasureImageError(const runner::ImageRgba8& reference,
                                     const runner::ImageRgba8& candidate) {
    const report::RgbaImage a{reference.width, reference.height, reference.pixels};
    const report::RgbaImage b{candidate.width, candidate.height, candidate.pixels};
    runner::ImageError error;
    error.psnr_db = report::Psnr(a, b);
    error.ssim = report::Ssim(a, b);
    error.share_visible = report::ShareAboveThreshold(a, b, report::kVisibleDifferenceThreshold);
    return error;
}

// Every scenes/*.yaml planned (the library calls `tidepool plan --all` makes) into
// render_dir/plans.json, candidate images under render_dir/images/.
StageOutcome RunPlanStage(runner::GlContext& context, const VariantConfig& config, int width,
                          int height, int rounds, int frames,
                          const std::filesystem::path& render_dir) {
    using namespace tidepool::runner;
    StageOutcome outcome;
    const auto start = std::chrono::steady_clock::now();
    const std::filesystem::path scene_dir = config.base_dir / "scenes";
    std::vector<std::filesystem::path> paths;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(scene_dir, ec)) {
        if (entry.path().extension() == ".yaml") {
            paths.push_back(entry.path());
        }
    }
    std::sort(paths.begin(), paths.end());
    if (paths.empty()) {
        std::fprintf(stderr, "error: plans: no scenes/*.yaml in %s\n", scene_dir.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    PlanOptions plan_options;
    plan_options.settings.width = width;
    plan_options.settings.height = height;
    plan_options.rounds = rounds;
    plan_options.frames_per_round = frames;
    plan_options.out_dir = render_dir;
    std::vector<ScenePlan> plans;
    for (const std::filesystem::path& path : paths) {
        SceneResult scene = LoadSceneDescription(path);
        PrintDiagnostics(scene.diagnostics);
        if (!scene.scene) {
            ++outcome.failures;  // a bad scene file cannot meet its target
            continue;
        }
        plans.push_back(PlanScene(context, config, *scene.scene, plan_options, MeasureImageError));
        const ScenePlan& plan = plans.back();
        PrintDiagnostics(plan.diagnostics);
        if (plan.chosen < 0 || !plan.met) {
            ++outcome.failures;
            std::fprintf(stderr, "plans: scene %s %s\n", plan.scene.name.c_str(),
                         plan.chosen < 0 ? "could not be planned" : "misses its target");
        }
    }
    const std::filesystem::path path = render_dir / report::kPlansFileName;
    if (std::string e = WriteJsonAtomically(path, PlansToJson(plans, plan_options)); !e.empty()) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
        outcome.environment_error = true;
        return outcome;
    }
    std::fprintf(stderr, "plans: %zu scenes at %dx%d, %d rounds x %d frames, %d not met, %.0f s; "
                         "%s\n",
                 plans.size(), width, height, rounds, frames, outcome.failures,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 path.c_str());
    return outcome;
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
    if (options.frames < 1 || options.rounds < 1 || options.warmup < 0 || options.threads < 0 ||
        options.plan_rounds < 1 || options.plan_frames < 1) {
        std::fprintf(stderr, "error: --frames, --rounds, --plan-rounds and --plan-frames must be "
                             "at least 1, --warmup and --threads at least 0\n");
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
        std::fprintf(stderr, "error: --name must be a plain folder name other than 'manifest' "
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
    ValidationOptions validation_options;
    validation_options.jobs = DefaultJobs();
    validation_options.targets = config.targets;
    const ValidationReport validation =
            ValidateVariants(config, expansion.variants, validation_options);
    PrintDiagnostics(validation.diagnostics);
    for (const VariantVerdict& verdict : validation.verdicts) {
        PrintDiagnostics(verdict.diagnostics);
    }
    const nlohmann::json manifest = BuildManifest(config, expansion, &validation);
    if (std::string error = WriteFileAtomically(manifest_path, JsonText(manifest, 2) + "\n");
        !error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitUsage;
    }
    std::fprintf(stderr, "validate: %zu variants, %zu pruned, %d invalid; manifest in %s\n",
                 expansion.variants.size(), expansion.pruned.size(), validation.InvalidCount(),
                 manifest_path.c_str());

    // 2. Render: images at every view and interleaved timing rounds.
    const ConfigurationSet configurations = BuildDefaultConfigurations(config, expansion.variants);
    PrintDiagnostics(configurations.diagnostics);
    if (HasErrors(configurations.diagnostics) || configurations.configurations.empty()) {
        return kExitUsage;
    }
    const std::string threads = std::to_string(options.threads);
    // llvmpipe reads its thread count when the first context is created.
    setenv("LP_NUM_THREADS", threads.c_str(), 1);
    GlContextResult context = CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: %s\n", context.error.c_str());
        return kExitEnvironment;
    }
    RunOptions run;
    run.configurations = configurations.configurations;
    run.views = DefaultViews();
    run.settings.width = width;
    run.settings.height = height;
    run.settings.fourier = options.fourier;
    run.warmup_frames = options.warmup;
    run.rounds = options.rounds;
    run.frames_per_round = options.frames;
    run.preset_frames_per_round = options.preset_frames;
    run.out_dir = render_dir;
    run.config_path = options.config;
    run.host.cpu_model = CpuModel();
    run.host.lp_num_threads = threads;
#ifdef NDEBUG
    run.host.build_type = "release (NDEBUG)";
#else
    run.host.build_type = "debug (assertions on)";
#endif
    run.host.git_revision = GitRevision(std::filesystem::absolute(options.config).parent_path());
    run.host.command = "run";
    const GlEnvironment& gl = context.context->Environment();
    std::fprintf(stderr, "render: %zu configurations x %zu views at %dx%d on %s, "
                         "LP_NUM_THREADS=%s, %d warm-up frames, %d rounds x %d frames\n",
                 run.configurations.size(), run.views.size(), width, height, gl.renderer.c_str(),
                 threads.c_str(), options.warmup, options.rounds, options.frames);
    std::string last_stage;
    double last_print = -1e9;
    auto progress = [&](const RunProgress& p) {
        // Plain lines (logs and terminals alike): on every stage change and every 15 seconds.
        if (p.stage != last_stage || p.elapsed_seconds - last_print >= 15.0) {
            std::fprintf(stderr, "[%3.0f%%] %s (elapsed %.0fs, ETA %.0fs)\n",
                         p.total > 0 ? 100.0 * static_cast<double>(p.done) /
                                               static_cast<double>(p.total)
                                     : 100.0,
                         p.stage.c_str(), p.elapsed_seconds, p.eta_seconds);
            last_print = p.elapsed_seconds;
        }
        last_stage = p.stage;
    };
    const RunResults results = RunRender(*context.context, config, run, progress);
    PrintDiagnostics(results.diagnostics);
    const std::filesystem::path results_path = render_dir / "results.json";
    if (std::string error = WriteJsonAtomically(results_path, ResultsToJson(results));
        !error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitEnvironment;
    }
    int failed = 0;
    for (const ConfigurationResult& r : results.configurations) {
        failed += r.Ok() ? 0 : 1;
    }
    std::fprintf(stderr, "render: %zu configurations, %d failed, %.0f s; results in %s\n",
                 results.configurations.size(), failed, results.wall_seconds,
                 results_path.c_str());

    // 3. Numerical stability and 4. scene plans, beside results.json where the report looks.
    StageOutcome stability;
    if (!options.no_stability) {
        stability = RunStabilityStage(*context.context, config, expansion.variants,
                                      stability_width, stability_height, threads, options.config,
                                      render_dir);
    }
    StageOutcome plans;
    if (!options.no_plans) {
        plans = RunPlanStage(*context.context, config, plan_width, plan_height,
                             options.plan_rounds, options.plan_frames, render_dir);
    }

    // 5. Report (written even when a stage above failed: it says what is missing and why).
    const int report_code = BuildAndWriteReport(manifest_path, results_path, options.name, out);
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "run: %.0f s in all\n", seconds);
    if (report_code == kExitUsage) {
        return kExitUsage;
    }
    if (stability.environment_error || plans.environment_error) {
        return kExitEnvironment;
    }
    return failed > 0 || validation.InvalidCount() > 0 || report_code == kExitShaderErrors ||
                           stability.failures > 0 || plans.failures > 0
                   ? kExitShaderErrors
                   : kExitOk;
}

}  // namespace

void RegisterReportCommands(CLI::App& app, int& exit_code) {
    auto report_options = std::make_shared<ReportCommandOptions>();
    CLI::App* report = app.add_subcommand(
            "report", "build the report (whitepaper table, accuracy vs time, static cost, "
                      "validation, images, method) from a saved manifest and results");
    report->add_option("--manifest", report_options->manifest,
                       "manifest.json written by `tidepool validate --out DIR`")
            ->capture_default_str();
    report->add_option("--results", report_options->results,
                       "results.json written by `tidepool render`")
            ->capture_default_str();
    report->add_option("--name", report_options->name, "report folder name under --out")
            ->capture_default_str();
    report->add_option("--out", report_options->out, "folder that receives <name>/")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    report->callback([report_options, &exit_code] { exit_code = RunReport(*report_options); });

    auto run_options = std::make_shared<RunCommandOptions>();
    CLI::App* run = app.add_subcommand(
            "run", "validate, render, run the stability catalogue and the scene plans, and "
                   "report in one go: <out>/manifest/, <out>/render/ (results.json, "
                   "stability.json, plans.json) and the report in <out>/<name>/");
    run->add_option("--config", run_options->config, "variants.yaml to read")
            ->capture_default_str();
    run->add_option("--name", run_options->name, "report folder name under --out")
            ->capture_default_str();
    run->add_option("--out", run_options->out, "output folder")
            ->transform(NormaliseOutPath)->capture_default_str();
    run->add_option("--size", run_options->size, "render size WxH")->capture_default_str();
    run->add_option("--rounds", run_options->rounds, "timing rounds")->capture_default_str();
    run->add_option("--preset-frames", run_options->preset_frames,
                    "timed frames per round for the presets' configurations (the whitepaper "
                    "comparisons; 0: as --frames)")
            ->capture_default_str();
    run->add_option("--frames", run_options->frames, "timed frames per configuration per round")
            ->capture_default_str();
    run->add_option("--warmup", run_options->warmup, "untimed frames per configuration first")
            ->capture_default_str();
    run->add_option("--backend", run_options->backend, "auto (EGL, then OSMesa), egl or osmesa")
            ->capture_default_str();
    run->add_option("--threads", run_options->threads, "llvmpipe threads (LP_NUM_THREADS)")
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
    run->add_option("--plan-rounds", run_options->plan_rounds, "paired timing rounds per plan")
            ->capture_default_str();
    run->add_option("--plan-frames", run_options->plan_frames,
                    "timed frames per plan candidate per round")
            ->capture_default_str();
    run->callback([run_options, &exit_code] { exit_code = RunAll(*run_options); });
}

}  // namespace tidepool::cli
