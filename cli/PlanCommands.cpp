// `tidepool plan`: flags → plan options → PlanScene per scene → print → plans.json → exit code.
#include "PlanCommands.h"

#include "tidepool/Manifest.h"
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/lab/ScenePlanner.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

// SSIM needs its 11x11 window inside the image several times over; 16 is the smallest side.
constexpr int kMinPlanSide = 16;

struct PlanCommandOptions {
    std::string config = "variants.yaml";
    std::vector<std::string> scenes;
    bool all = false;
    std::string size = "320x240";
    double resolution = 3.0;
    std::string backend = "auto";
    int threads = 0;
    bool json = false;
    std::string out;
};

void PrintPlan(const runner::ScenePlan& plan) {
    std::printf("scene %s: %s\n", plan.scene.name.c_str(), plan.scene.description.c_str());
    for (const Diagnostic& d : plan.diagnostics) {
        std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
    }
    if (plan.chosen < 0) {
        return;
    }
    for (const std::string& need : plan.needed) {
        std::printf("  needs   %s\n", need.c_str());
    }
    for (const runner::PlanCandidate& c : plan.candidates) {
        if (!c.valid) {
            std::printf("  skip    %-64s invalid\n", c.configuration.id.c_str());
            continue;
        }
        std::printf(
                "  %s %-64s %6.2f ms %+5.0f%%  %5.1f dB  ssim %.3f  visible %5.1f%%  "
                "passes %d draws %d\n",
                &c == &plan.candidates[static_cast<std::size_t>(plan.chosen)] ? "chosen "
                                                                              : "       ",
                c.configuration.id.c_str(), c.time_ms, c.time_change_percent, c.error.psnr_db,
                c.error.ssim, 100.0 * c.error.share_visible, c.frame.passes, c.frame.draw_calls);
    }
    for (const runner::DroppedEffect& d : plan.dropped) {
        std::printf("  %s\n", d.reason.c_str());
    }
    for (const runner::DroppedEffect& k : plan.kept) {
        std::printf("  %s\n", k.reason.c_str());
    }
    const runner::PlanCandidate& chosen = plan.candidates[static_cast<std::size_t>(plan.chosen)];
    std::printf(
            "  => %s: %.2f ms vs %.2f ms full (%+.0f%%), %.1f dB, target %s; %d passes and "
            "%d draws saved\n",
            chosen.configuration.id.c_str(), chosen.time_ms, plan.candidates.front().time_ms,
            chosen.time_change_percent, chosen.error.psnr_db, plan.met ? "met" : "NOT met",
            plan.passes_saved, plan.draws_saved);
}

int RunPlan(const PlanCommandOptions& options) {
    using namespace tidepool::runner;
    PlanOptions plan_options;
    if (!ParseSizeOption("--size", options.size, kMinPlanSide, &plan_options.settings.width,
                         &plan_options.settings.height)) {
        return kExitUsage;
    }
    BackendKind backend = BackendKind::kAuto;
    if (!ParseBackendOption(options.backend, &backend)) {
        return kExitUsage;
    }
    if (!(options.resolution > 0 && options.resolution <= 50) || options.threads < 0 ||
        options.threads > 64) {
        std::fprintf(stderr,
                     "error: --resolution must be above 0 and at most 50 percent points, "
                     "--threads between 0 and 64\n");
        return kExitUsage;
    }
    if (options.all == !options.scenes.empty()) {
        std::fprintf(stderr, "error: give either --scene NAME (repeatable) or --all\n");
        return kExitUsage;
    }
    plan_options.rule.resolution_points = options.resolution;

    ConfigResult loaded = LoadVariantConfig(options.config);
    for (const Diagnostic& d : loaded.diagnostics) {
        std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
    }
    if (!loaded.config) {
        return kExitUsage;
    }
    const VariantConfig& config = *loaded.config;
    const std::filesystem::path scene_dir = config.base_dir / "scenes";
    std::vector<std::filesystem::path> paths;
    if (options.all) {
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(scene_dir, ec)) {
            if (entry.path().extension() == ".yaml") {
                paths.push_back(entry.path());
            }
        }
        std::sort(paths.begin(), paths.end());
        if (paths.empty()) {
            std::fprintf(stderr, "error: no scenes/*.yaml next to %s\n", options.config.c_str());
            return kExitUsage;
        }
    } else {
        for (const std::string& name : options.scenes) {
            paths.push_back(scene_dir / (name + ".yaml"));
        }
    }
    std::vector<SceneDescription> scenes;
    bool bad = false;
    for (const std::filesystem::path& path : paths) {
        SceneResult scene = LoadSceneDescription(path);
        for (const Diagnostic& d : scene.diagnostics) {
            std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
        }
        if (scene.scene) {
            scenes.push_back(std::move(*scene.scene));
        } else {
            bad = true;
        }
    }
    if (bad) {
        return kExitUsage;
    }

    // The output folder (plans.json and the candidates' images) is published whole: a folder
    // that is not tidepool's is refused before any rendering, and a killed run leaves the
    // previous plans as they were.
    std::string out = options.out;
    if (out.empty() && options.all) {
        out = "reports/out/plan";
    }
    std::unique_ptr<base::FolderPublisher> publisher;
    if (!out.empty()) {
        int begin_code = kExitOk;
        publisher = BeginPublishing(out, "tidepool plan", &begin_code);
        if (!publisher) {
            return begin_code;
        }
        plan_options.out_dir = publisher->Staging();
    }

    // llvmpipe reads its thread count when the first context is created.
    const std::string threads = std::to_string(options.threads);
    setenv("LP_NUM_THREADS", threads.c_str(), 1);
    GlContextResult context = CreateGlContext(backend);
    if (!context.context) {
        std::fprintf(stderr, "error: %s\n", context.error.c_str());
        return kExitEnvironment;
    }
    plan_options.clock = ChooseFrameClock(context.context->Environment().renderer, threads,
                                          context.context->Environment().timer_query)
                                 .clock;
    std::vector<ScenePlan> plans;
    int failed = 0;
    for (const SceneDescription& scene : scenes) {
        plans.push_back(PlanScene(*context.context, config, scene, plan_options));
        if (!options.json) {
            PrintPlan(plans.back());
        }
        failed += plans.back().chosen < 0 ? 1 : 0;
    }
    const nlohmann::json json = PlansToJson(plans, plan_options);
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    }
    if (publisher) {
        const std::string error = base::WriteFileAtomically(
                publisher->Staging() / report::kPlansFileName, JsonText(json, 2) + "\n");
        if (!error.empty()) {
            std::fprintf(stderr, "error: %s\n", error.c_str());
            return kExitEnvironment;
        }
        if (const base::PublishError e = publisher->Publish(); e.Failed()) {
            std::fprintf(stderr, "error: %s\n", e.message.c_str());
            return PublishExitCode(e);
        }
        const std::filesystem::path path = publisher->Target() / report::kPlansFileName;
        std::fprintf(stderr, "plan: %zu scenes; plans in %s\n", plans.size(), path.c_str());
    }
    return failed > 0 ? kExitShaderErrors : kExitOk;
}

}  // namespace

void RegisterPlanCommands(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<PlanCommandOptions>();
    CLI::App* plan = app.add_subcommand("plan", GlCommandSummary("plan"));
    plan->add_option("--config", options->config, "variants.yaml to read; scenes/ lies next to it")
            ->capture_default_str();
    plan->add_option("--scene", options->scenes, "plan scenes/NAME.yaml (repeatable)");
    plan->add_flag("--all", options->all, "plan every scenes/*.yaml and write plans.json");
    plan->add_option("--size", options->size, "render size WxH")->capture_default_str();
    plan->add_option("--resolution", options->resolution,
                     "time each candidate against the full effect, pair by pair, until its 95% "
                     "interval is this narrow (half-width, percent points)")
            ->capture_default_str();
    plan->add_option("--backend", options->backend, "auto (EGL, then OSMesa), egl or osmesa")
            ->capture_default_str();
    plan->add_option("--threads", options->threads,
                     "llvmpipe threads (LP_NUM_THREADS; 0 renders on the calling thread)")
            ->capture_default_str();
    plan->add_flag("--json", options->json, "print plans.json to stdout");
    plan->add_option("--out", options->out,
                     "folder for plans.json (default reports/out/plan with --all)")
            ->transform(NormaliseOutPath);
    plan->callback([options, &exit_code] { exit_code = RunPlan(*options); });
}

}  // namespace tidepool::cli
