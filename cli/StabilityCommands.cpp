// `tidepool stability`: flags → pipeline::RunStability → a line per case → exit code.
#include "StabilityCommands.h"

#include "tidepool/pipeline/StabilityStage.h"

#include <cstdio>
#include <memory>
#include <string>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"

namespace tidepool::cli {
namespace {

struct StabilityCommandOptions {
    pipeline::StabilityOptions stability;
    std::string out = "reports/out/render";
    std::string backend = "auto";
    bool json = false;
};

// RGBA32F targets: 4096² is already 256 MiB each.
constexpr int kMaxStabilitySide = 4096;

void PrintStability(const pipeline::StabilityResult& result) {
    using namespace tidepool::lab;  // and, through it, the runner
    for (const StabilityCaseResult& r : result.report.cases) {
        std::printf("%-4s %-34s %s  max_error %.3g (bound %.3g)\n", r.passed ? "ok" : "FAIL",
                    r.name.c_str(), r.kind.c_str(), r.max_error, r.bound);
    }
    for (const PrecisionRow& p : result.report.precision) {
        std::printf("%-9s %s (fp16 rel %.3g)\n", p.loses_precision ? "mediump!" : "mediump",
                    p.expression.c_str(), p.max_rel_error_fp16);
    }
    for (const GuardResult& g : result.report.guards) {
        std::printf("guard %s: %.3g (tolerance %.3g)\n", g.guard.c_str(),
                    g.max_channel_diff_normal_views, g.tolerance);
    }
    std::printf("%zu cases, %d failed; wrote %s\n", result.report.cases.size(), result.failed,
                result.path.string().c_str());
}

int RunStability(StabilityCommandOptions options) {
    pipeline::StabilityOptions& stability = options.stability;
    if (!ParseSizeOption("--size", stability.run.size, 1, &stability.run.width,
                         &stability.run.height, kMaxStabilitySide) ||
        !ParseBackendOption(options.backend, &stability.backend)) {
        return kExitUsage;
    }
    if (stability.threads < 0 || stability.threads > 64) {
        std::fprintf(stderr, "error: --threads must be between 0 and 64, as for render, not %d\n",
                     stability.threads);
        return kExitUsage;
    }
    stability.out = options.out;
    stability.run.config_path = stability.config;
    const pipeline::StabilityResult result = pipeline::RunStability(stability);
    if (const int code = PrintOutcome(result.outcome); result.outcome.Stopped()) {
        return code;
    }
    if (options.json) {
        std::fputs(result.json.c_str(), stdout);
    } else {
        PrintStability(result);
    }
    return pipeline::ExitCode(result.outcome.status);
}

}  // namespace

void RegisterStabilityCommands(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<StabilityCommandOptions>();
    options->stability.run.size = "64x48";
    CLI::App* command = app.add_subcommand("stability", GlCommandSummary("stability"));
    command->add_option("--config", options->stability.config, "variants.yaml to read")
            ->capture_default_str();
    command->add_option("--out", options->out, "folder for stability.json")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    command->add_option("--backend", options->backend, "auto, egl or osmesa")
            ->capture_default_str();
    command->add_option("--size", options->stability.run.size, "render size WxH of the GL cases")
            ->capture_default_str();
    command->add_option("--threads", options->stability.threads, "LP_NUM_THREADS for llvmpipe")
            ->capture_default_str();
    command->add_flag("--json", options->json, "print stability.json instead of a summary");
    command->callback([options, &exit_code] { exit_code = RunStability(*options); });
}

}  // namespace tidepool::cli
