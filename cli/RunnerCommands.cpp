// `tidepool render` and `tidepool bench`: flags → run options → RunRender → print → exit code.
#include "tidepool/Manifest.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Results.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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

struct RunnerOptions {
    std::string command;
    std::string config = "variants.yaml";
    std::vector<std::string> filters;
    std::vector<std::string> presets;
    std::vector<std::string> views;
    std::string size = "640x480";
    TimingFlags timing;
    std::string backend = "auto";
    std::string out = "reports/out/render";
    bool json = false;
    bool no_images = false;
    tidepool::runner::FourierSettings fourier;
};

int RunRunner(const RunnerOptions& options) {
    using namespace tidepool::runner;
    int width = 0;
    int height = 0;
    if (!ParseSizeOption("--size", options.size, 1, &width, &height)) {
        return kExitUsage;
    }
    BackendKind backend = BackendKind::kAuto;
    if (!ParseBackendOption(options.backend, &backend)) {
        return kExitUsage;
    }
    if (!CheckTimingFlags(options.timing) || !CheckFourierOptions(options.fourier)) {
        return kExitUsage;
    }

    const LoadedMatrix loaded = LoadAndExpand(options.config);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    const VariantConfig& config = *loaded.config;
    const ExpansionResult& expansion = loaded.expansion;
    const ConfigurationSet all = BuildDefaultConfigurations(config, expansion.variants);
    const ConfigurationSet selected =
            FilterConfigurations(all, ConfigurationFilter{options.filters, options.presets});
    PrintDiagnostics(selected.diagnostics);
    if (HasErrors(selected.diagnostics)) {
        return kExitUsage;
    }
    if (selected.configurations.empty()) {
        std::fprintf(stderr, "error: no configuration matches the --filter/--preset given\n");
        return kExitUsage;
    }
    const std::vector<CameraView> default_views = DefaultViews();
    std::vector<CameraView> views;
    for (const std::string& name : options.views) {
        const CameraView* view = FindView(default_views, name);
        if (view == nullptr) {
            std::string known;
            for (const CameraView& v : default_views) {
                known += (known.empty() ? "" : ", ") + v.name;
            }
            std::fprintf(stderr, "error: unknown view '%s'; the views are %s\n", name.c_str(),
                         known.c_str());
            return kExitUsage;
        }
        views.push_back(*view);
    }
    if (views.empty()) {
        views = default_views;
    }

    RunOptions run;
    run.configurations = selected.configurations;
    run.views = views;
    run.settings.width = width;
    run.settings.height = height;
    run.settings.fourier = options.fourier;
    run.write_images = !options.no_images;
    run.config_path = options.config;
    run.host = DescribeHost(options.command, options.config);
    ApplyTimingFlags(options.timing, backend, &run);
    const std::string& threads = run.host.lp_num_threads;
    // The whole folder (images, then results.json) is staged and published with one rename, so
    // a killed or failed render leaves the previous good output as it was.
    int begin_code = kExitOk;
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(options.out, "tidepool " + options.command, &begin_code);
    if (!publisher) {
        return begin_code;
    }
    run.out_dir = publisher->Staging();
    GlContextResult context = CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: %s\n", context.error.c_str());
        return kExitEnvironment;
    }

    const GlEnvironment& gl = context.context->Environment();
    std::fprintf(stderr,
                 "%s: %zu configurations x %zu views at %dx%d on %s (%s, %s), "
                 "LP_NUM_THREADS=%s, %d workers, %zu comparisons to +/-%.1f points\n",
                 options.command.c_str(), run.configurations.size(), run.views.size(), width,
                 height, gl.renderer.c_str(), gl.backend.c_str(), gl.version.c_str(),
                 threads.c_str(), run.workers, run.comparisons.size(), run.rule.resolution_points);
    const RunResults results = RunRender(*context.context, config, run, MakeProgressPrinter());
    FinishProgress();
    PrintDiagnostics(results.diagnostics);

    const nlohmann::json json = ResultsToJson(results);
    const std::filesystem::path results_path = publisher->Target() / "results.json";
    std::string write_error = base::WriteFileAtomically(publisher->Staging() / "results.json",
                                                        JsonText(json, 2) + "\n");
    int publish_code = kExitOk;
    if (write_error.empty() && results.write_errors.empty()) {
        if (const base::PublishError e = publisher->Publish(); e.Failed()) {
            write_error = e.message;
            publish_code = PublishExitCode(e);
        }
    }
    if (!write_error.empty()) {
        std::fprintf(stderr, "error: %s\n", write_error.c_str());
    }
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    }
    for (const std::string& e : results.write_errors) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
    }

    int failed = 0;
    for (const ConfigurationResult& r : results.configurations) {
        failed += r.Ok() ? 0 : 1;
        if (!options.json && r.Ok() && r.statistics.count > 0) {
            std::printf("%-72s median %7.2f ms %s (wall %.2f)  passes %d  draws %d\n",
                        r.configuration.id.c_str(), r.cpu_statistics.median,
                        std::string(FrameClockName(results.clock.clock)).c_str(),
                        r.statistics.median, r.passes, r.draw_calls);
        } else if (!options.json && !r.Ok()) {
            std::printf("%-72s FAILED%s%s\n", r.configuration.id.c_str(),
                        r.verdict.valid ? "" : " (driver compile/link)",
                        r.gl_error.empty() ? "" : (" (" + r.gl_error + ")").c_str());
        }
    }
    for (const ComparisonResult& c : results.comparisons) {
        const base::PairedEstimate& e = c.timing.estimate;
        if (options.json) {
            break;
        }
        if (!c.error.empty()) {
            std::printf("%-40s no estimate: %s\n", c.comparison.label.c_str(), c.error.c_str());
        } else {
            std::printf("%-40s %+6.1f%% [%+.1f, %+.1f] frame rate, %d pairs (%s)\n",
                        c.comparison.label.c_str(), e.change_percent, e.change_low, e.change_high,
                        e.pairs, base::StopDecisionName(c.timing.decision));
        }
    }
    for (const VerdictDisagreement& d : results.disagreements) {
        std::fprintf(stderr, "note: glslang says %s, Mesa says %s: %s\n",
                     d.glslang_valid ? "valid" : "invalid", d.mesa_valid ? "valid" : "invalid",
                     d.variant.c_str());
    }
    std::fprintf(stderr,
                 "%s: %zu configurations, %d failed, %zu glslang/Mesa disagreements, "
                 "%s wall; results in %s\n",
                 options.command.c_str(), results.configurations.size(), failed,
                 results.disagreements.size(), FormatDuration(results.wall_seconds).c_str(),
                 results_path.c_str());
    if (publish_code != kExitOk) {
        return publish_code;
    }
    if (!write_error.empty() || !results.write_errors.empty()) {
        return kExitEnvironment;  // nothing published: the previous output stays
    }
    return failed > 0 ? kExitShaderErrors : kExitOk;
}

void AddRunnerFlags(CLI::App* command, RunnerOptions* options) {
    command->add_option("--config", options->config, "variants.yaml to read")
            ->capture_default_str();
    command->add_option("--filter", options->filters,
                        "keep configurations whose id matches this glob (repeatable), e.g. "
                        "'water:*ENABLE_FOG*'");
    command->add_option("--preset", options->presets, "keep this preset (repeatable)");
    command->add_option("--view", options->views,
                        "render this view only (repeatable): three_quarter, grazing, high, shore");
    command->add_option("--size", options->size, "render size WxH")->capture_default_str();
    AddTimingFlags(command, &options->timing);
    command->add_option("--backend", options->backend, "auto (EGL, then OSMesa), egl or osmesa")
            ->capture_default_str();
    command->add_option("--out", options->out,
                        "folder for results.json and images/, replaced whole when the render "
                        "succeeds; an existing folder must be tidepool's own output")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    command->add_flag("--json", options->json, "print the results JSON to stdout");
    command->add_flag("--no-images", options->no_images, "do not write PNG files");
    AddFourierOptions(command, &options->fourier);
}

}  // namespace

void RegisterRunnerCommands(CLI::App& app, int& exit_code) {
    auto render_options = std::make_shared<RunnerOptions>();
    render_options->command = "render";
    CLI::App* render = app.add_subcommand("render", GlCommandSummary("render"));
    AddRunnerFlags(render, render_options.get());
    render->callback([render_options, &exit_code] { exit_code = RunRunner(*render_options); });

    auto bench_options = std::make_shared<RunnerOptions>();
    bench_options->command = "bench";
    // Timing focus: a finer resolution and more frames alone, images only where cheap to keep.
    bench_options->timing.warmup = 3;
    bench_options->timing.resolution = 1.0;
    bench_options->timing.coarse_frames = 15;
    bench_options->views = {"three_quarter"};
    bench_options->out = "reports/out/bench";
    CLI::App* bench = app.add_subcommand("bench", GlCommandSummary("bench"));
    AddRunnerFlags(bench, bench_options.get());
    bench->callback([bench_options, &exit_code] { exit_code = RunRunner(*bench_options); });
}

}  // namespace tidepool::cli
