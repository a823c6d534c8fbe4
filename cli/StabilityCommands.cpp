// `tidepool stability`: flags → catalogue run → stability.json → summary → exit code.
#include "StabilityCommands.h"

#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/runner/GlBackend.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

struct StabilityOptions {
    std::string config = "variants.yaml";
    std::string out = "reports/out/render";
    std::string backend = "auto";
    std::string size = "64x48";
    int threads = 2;
    bool json = false;
};

int WriteStabilityInto(const std::string& folder, const std::string& json,
                       bool check_only = false) {
    return WriteOwnJsonInto(folder, std::string(report::kStabilityFileName),
                            std::string(report::kStabilitySchemaName), "stability report", json,
                            check_only);
}

// RGBA32F targets: 4096² is already 256 MiB each.
constexpr int kMaxStabilitySide = 4096;

int RunStability(const StabilityOptions& options) {
    using namespace tidepool::runner;
    GlStabilityOptions gl_options;
    if (!ParseSizeOption("--size", options.size, 1, &gl_options.width, &gl_options.height,
                         kMaxStabilitySide)) {
        return kExitUsage;
    }
    BackendKind backend = BackendKind::kAuto;
    if (!ParseBackendOption(options.backend, &backend)) {
        return kExitUsage;
    }
    if (options.threads < 0) {
        std::fprintf(stderr, "error: --threads must be at least 0, not %d\n", options.threads);
        return kExitUsage;
    }
    // A stability.json of someone else's is refused before the catalogue runs; tidepool's own is
    // replaced atomically, so a killed run leaves the previous one whole.
    const std::filesystem::path path =
            std::filesystem::path(options.out) / report::kStabilityFileName;
    if (const int code = WriteStabilityInto(options.out, "", true); code != kExitOk) {
        return code;
    }
    const LoadedMatrix loaded = LoadAndExpand(options.config);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    const ExpansionResult& expansion = loaded.expansion;

    StabilityReport report;
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    for (const HardCase& hard_case : catalogue) {
        if (hard_case.kind == HardCaseKind::kCpu) {
            report.cases.push_back(RunCpuHardCase(hard_case));
        }
    }
    report.precision = RunPrecisionStudy();

    // llvmpipe reads its thread count when the first context is created.
    const std::string threads = std::to_string(options.threads);
    setenv("LP_NUM_THREADS", threads.c_str(), 1);
    GlContextResult context = CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: %s\n", context.error.c_str());
        return kExitEnvironment;
    }
    const GlEnvironment& env = context.context->Environment();
    report.environment = {{"backend", env.backend},    {"renderer", env.renderer},
                          {"version", env.version},    {"mesa_version", env.mesa_version},
                          {"lp_num_threads", threads}, {"size", options.size},
                          {"config", options.config}};
    std::string error;
    const std::vector<RenderConfiguration> configs = WaterVariantConfigurations(expansion.variants);
    std::vector<StabilityCaseResult> gl_cases = RunGlHardCases(
            *context.context, *loaded.config, configs, catalogue, gl_options, &error);
    if (!error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitEnvironment;
    }
    for (StabilityCaseResult& r : gl_cases) {
        report.cases.push_back(std::move(r));
    }
    report.guards = MeasureGuards(*context.context, *loaded.config, gl_options, &error);
    if (!error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitEnvironment;
    }

    const std::string json = StabilityReportJson(report);
    if (const int code = WriteStabilityInto(options.out, json); code != kExitOk) {
        return code;
    }
    int failed = 0;
    for (const StabilityCaseResult& r : report.cases) {
        failed += r.passed ? 0 : 1;
    }
    if (options.json) {
        std::fputs(json.c_str(), stdout);
    } else {
        for (const StabilityCaseResult& r : report.cases) {
            std::printf("%-4s %-34s %s  max_error %.3g (bound %.3g)\n", r.passed ? "ok" : "FAIL",
                        r.name.c_str(), HardCaseKindName(r.kind), r.max_error, r.bound);
        }
        for (const PrecisionRow& p : report.precision) {
            std::printf("%-9s %s (fp16 rel %.3g)\n", p.loses_precision ? "mediump!" : "mediump",
                        p.expression.c_str(), p.max_rel_error_fp16);
        }
        for (const GuardResult& g : report.guards) {
            std::printf("guard %s: %.3g (tolerance %.3g)\n", g.guard.c_str(),
                        g.max_channel_diff_normal_views, g.tolerance);
        }
        std::printf("%zu cases, %d failed; wrote %s\n", report.cases.size(), failed,
                    path.string().c_str());
    }
    return failed == 0 ? kExitOk : kExitShaderErrors;
}

}  // namespace

void RegisterStabilityCommands(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<StabilityOptions>();
    CLI::App* command = app.add_subcommand("stability", GlCommandSummary("stability"));
    command->add_option("--config", options->config, "variants.yaml to read")
            ->capture_default_str();
    command->add_option("--out", options->out, "folder for stability.json")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    command->add_option("--backend", options->backend, "auto, egl or osmesa")
            ->capture_default_str();
    command->add_option("--size", options->size, "render size WxH of the GL cases")
            ->capture_default_str();
    command->add_option("--threads", options->threads, "LP_NUM_THREADS for llvmpipe")
            ->capture_default_str();
    command->add_flag("--json", options->json, "print stability.json instead of a summary");
    command->callback([options, &exit_code] { exit_code = RunStability(*options); });
}

}  // namespace tidepool::cli
