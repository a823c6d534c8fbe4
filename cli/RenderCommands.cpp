// `tidepool render` and `tidepool bench`: flags → pipeline::PrepareRender and pipeline::Render →
// a line per configuration and comparison → exit code.
#include "tidepool/Manifest.h"
#include "tidepool/pipeline/RenderStage.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"
#include "StderrProgressSink.h"

namespace tidepool::cli {
namespace {

struct RenderCommandOptions {
    std::string command;
    pipeline::RenderSelection selection;
    std::string size = "640x480";
    TimingFlags timing;
    std::string backend = "auto";
    std::string out = "reports/out/render";
    bool json = false;
    bool no_images = false;
    std::string progress_log;
};

// What the render found: a line per configuration and per comparison, then the summary.
void PrintRender(const RenderCommandOptions& options, const pipeline::RenderResult& rendered) {
    using namespace tidepool::runner;
    const RunResults& results = rendered.results;
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
        const base::PairedEstimate& e = c.timing.stated;
        if (options.json) {
            break;
        }
        if (!c.error.empty()) {
            std::printf("%-40s no estimate: %s\n", c.comparison.label.c_str(), c.error.c_str());
        } else {
            const base::PairedEstimate& busy = c.timing.contended_estimate;
            const std::string contended =
                    busy.pairs > 0 ? fmt::format(", {:+.1f}% with its core shared ({} pairs)",
                                                 busy.change_percent, busy.pairs)
                                   : std::string();
            std::printf("%-40s %+6.1f%% [%+.1f, %+.1f] frame rate, %d pairs%s (%s)\n",
                        c.comparison.label.c_str(), e.change_percent, e.change_low, e.change_high,
                        e.pairs, contended.c_str(), base::StopDecisionName(c.timing.decision));
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
                 rendered.results_path.c_str());
}

int RunRenderCommand(RenderCommandOptions options) {
    pipeline::RenderSelection& selection = options.selection;
    runner::BackendKind backend = runner::BackendKind::kAuto;
    if (!ParseSizeOption("--size", options.size, 1, &selection.width, &selection.height) ||
        !ParseBackendOption(options.backend, &backend) || !CheckTimingFlags(options.timing) ||
        !CheckFourierOptions(selection.fourier)) {
        return kExitUsage;
    }
    selection.write_images = !options.no_images;
    pipeline::PreparedRender prepared = pipeline::PrepareRender(selection);
    if (const int code = PrintOutcome(prepared.outcome); prepared.outcome.Stopped()) {
        return code;
    }
    prepared.run.host = pipeline::DescribeHost(options.command, selection.config);
    pipeline::ApplyTiming(options.timing, backend, &prepared.run);
    StderrProgressSink progress;
    if (!options.progress_log.empty() && !progress.OpenLog(options.progress_log)) {
        return kExitUsage;
    }
    const pipeline::RenderResult result = pipeline::Render(prepared, backend, options.out,
                                                           "tidepool " + options.command, progress);
    const int code = PrintOutcome(result.outcome);
    if (!result.rendered) {
        return code;
    }
    if (options.json) {
        std::printf("%s\n", JsonText(result.json, 2).c_str());
    }
    PrintRender(options, result);
    return code;
}

void AddRenderFlags(CLI::App* command, RenderCommandOptions* options) {
    pipeline::RenderSelection& selection = options->selection;
    command->add_option("--config", selection.config, "variants.yaml to read")
            ->capture_default_str();
    command->add_option("--filter", selection.filters,
                        "keep configurations whose id matches this glob (repeatable), e.g. "
                        "'water:*ENABLE_FOG*'");
    command->add_option("--preset", selection.presets, "keep this preset (repeatable)");
    command->add_option("--view", selection.views,
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
    AddFourierOptions(command, &selection.fourier);
    AddProgressLogFlag(command, &options->progress_log);
}

}  // namespace

void RegisterRunnerCommands(CLI::App& app, int& exit_code) {
    auto render_options = std::make_shared<RenderCommandOptions>();
    render_options->command = "render";
    CLI::App* render = app.add_subcommand("render", GlCommandSummary("render"));
    AddRenderFlags(render, render_options.get());
    render->callback(
            [render_options, &exit_code] { exit_code = RunRenderCommand(*render_options); });

    auto bench_options = std::make_shared<RenderCommandOptions>();
    bench_options->command = "bench";
    // Timing focus: a finer resolution and more frames alone, images only where cheap to keep.
    bench_options->timing.warmup = 3;
    bench_options->timing.resolution = 1.0;
    bench_options->timing.coarse_frames = 15;
    bench_options->selection.views = {"three_quarter"};
    bench_options->out = "reports/out/bench";
    CLI::App* bench = app.add_subcommand("bench", GlCommandSummary("bench"));
    AddRenderFlags(bench, bench_options.get());
    bench->callback([bench_options, &exit_code] { exit_code = RunRenderCommand(*bench_options); });
}

}  // namespace tidepool::cli
