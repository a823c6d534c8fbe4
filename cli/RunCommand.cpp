// `tidepool run` (validate, render with the stability catalogue and the scene plans beside it,
// and report in one go): flags → pipeline::Run → pipeline::BuildReport → print → exit code.
// Built into `tidepool-gl`.
#include "tidepool/pipeline/RunStage.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"
#include "StderrProgressSink.h"

namespace tidepool::cli {
namespace {

// `run` times through the one timing engine (TimingFlags): each configuration coarsely on its
// own, each compared pair of presets pair by pair until its interval is +/-1.5 points. The
// stability and plan sizes are pipeline::RunRequest's.
struct RunCommandOptions {
    std::string config = "variants.yaml";
    std::string name = "default";
    std::string out = "reports/out";
    std::string size = "640x480";
    TimingFlags timing;
    std::string backend = "auto";
    bool no_stability = false;
    bool no_plans = false;
    std::string stability_size = "64x48";
    std::string plan_size = "160x120";
    double plan_resolution = 3.0;
    tidepool::runner::FourierSettings fourier;
    CacheFlags cache;
    std::string progress_log;
};

// The flags as a request, or false after printing why they cannot be used.
bool ToRequest(const RunCommandOptions& options, pipeline::RunRequest* request) {
    if (!ParseSizeOption("--size", options.size, 1, &request->width, &request->height) ||
        !ParseBackendOption(options.backend, &request->backend) ||
        !CheckTimingFlags(options.timing) || !CheckFourierOptions(options.fourier) ||
        !ParseSizeOption("--stability-size", options.stability_size, 1, &request->stability_width,
                         &request->stability_height) ||
        // SSIM needs its 11x11 window inside the image, as `tidepool plan` requires.
        !ParseSizeOption("--plan-size", options.plan_size, 16, &request->plan_width,
                         &request->plan_height)) {
        return false;
    }
    if (!(options.plan_resolution > 0 && options.plan_resolution <= 50)) {
        std::fprintf(stderr,
                     "error: --plan-resolution must be above 0 and at most 50 percent "
                     "points, not %g\n",
                     options.plan_resolution);
        return false;
    }
    if (!CheckReportName(options.name, {"manifest", "render"})) {
        return false;
    }
    request->config = options.config;
    request->out = options.out;
    request->fourier = options.fourier;
    request->cache = options.cache;
    request->stability = !options.no_stability;
    request->plans = !options.no_plans;
    request->plan_resolution = options.plan_resolution;
    const runner::BackendKind backend = request->backend;
    request->prepare_timing = [options, backend](runner::RunOptions* run) {
        run->host = pipeline::DescribeHost("run", options.config);
        pipeline::ApplyTiming(options.timing, backend, run);
    };
    return true;
}

int RunAll(const RunCommandOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    pipeline::RunRequest request;
    if (!ToRequest(options, &request)) {
        return kExitUsage;
    }
    StderrProgressSink progress;
    if (!options.progress_log.empty() && !progress.OpenLog(options.progress_log)) {
        return kExitUsage;
    }
    const pipeline::RunResult run = pipeline::Run(request, progress);
    if (!run.rendered) {
        return pipeline::ExitCode(run.outcome.status);
    }
    // The report is written even when a stage failed: it says what is missing and why.
    const int report_code =
            BuildAndWriteReport(run.manifest_path, run.results_path, options.name, request.out);
    std::fprintf(stderr, "run: %.0f s in all\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (report_code == kExitUsage || report_code == kExitEnvironment) {
        return report_code;
    }
    if (run.outcome.status == pipeline::Status::kEnvironment) {
        return kExitEnvironment;
    }
    return run.outcome.status == pipeline::Status::kInvalid || report_code == kExitShaderErrors
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
    AddProgressLogFlag(run, &run_options->progress_log);
    run->callback([run_options, &exit_code] { exit_code = RunAll(*run_options); });
}

}  // namespace tidepool::cli
