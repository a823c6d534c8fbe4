// `tidepool plan`: flags → pipeline::PreparePlans and pipeline::PlanScenes → each plan → exit
// code.
#include "PlanCommands.h"

#include "tidepool/Manifest.h"
#include "tidepool/pipeline/PlanStage.h"

#include <cstdio>
#include <memory>
#include <string>

#include "CliSupport.h"
#include "Commands.h"
#include "GlCliSupport.h"

namespace tidepool::cli {
namespace {

// SSIM needs its 11x11 window inside the image several times over; 16 is the smallest side.
constexpr int kMinPlanSide = 16;

struct PlanCommandOptions {
    pipeline::PlanRequest request;
    std::string size = "320x240";
    std::string backend = "auto";
    bool json = false;
};

void PrintPlan(const lab::ScenePlan& plan) {
    std::printf("scene %s: %s\n", plan.scene.name.c_str(), plan.scene.description.c_str());
    PrintDiagnostics(plan.diagnostics);
    if (plan.chosen < 0) {
        return;
    }
    for (const std::string& need : plan.needed) {
        std::printf("  needs   %s\n", need.c_str());
    }
    for (const lab::PlanCandidate& c : plan.candidates) {
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
    for (const lab::DroppedEffect& d : plan.dropped) {
        std::printf("  %s\n", d.reason.c_str());
    }
    for (const lab::DroppedEffect& k : plan.kept) {
        std::printf("  %s\n", k.reason.c_str());
    }
    const lab::PlanCandidate& chosen = plan.candidates[static_cast<std::size_t>(plan.chosen)];
    std::printf(
            "  => %s: %.2f ms vs %.2f ms full (%+.0f%%), %.1f dB, target %s; %d passes and "
            "%d draws saved\n",
            chosen.configuration.id.c_str(), chosen.time_ms, plan.candidates.front().time_ms,
            chosen.time_change_percent, chosen.error.psnr_db, plan.met ? "met" : "NOT met",
            plan.passes_saved, plan.draws_saved);
}

int RunPlan(PlanCommandOptions options) {
    pipeline::PlanRequest& request = options.request;
    if (!ParseSizeOption("--size", options.size, kMinPlanSide, &request.width, &request.height) ||
        !ParseBackendOption(options.backend, &request.backend)) {
        return kExitUsage;
    }
    if (!(request.resolution > 0 && request.resolution <= 50) ||
        !(request.contended_share >= 0 && request.contended_share <= 4) || request.threads < 0 ||
        request.threads > 64) {
        std::fprintf(stderr,
                     "error: --resolution must be above 0 and at most 50 percent points, "
                     "--contended-share between 0 and 4, --threads between 0 and 64\n");
        return kExitUsage;
    }
    if (request.all == !request.scenes.empty()) {
        std::fprintf(stderr, "error: give either --scene NAME (repeatable) or --all\n");
        return kExitUsage;
    }
    pipeline::PreparedPlans prepared = pipeline::PreparePlans(request);
    if (const int code = PrintOutcome(prepared.outcome); prepared.outcome.Stopped()) {
        return code;
    }
    const pipeline::PlanResult result = pipeline::PlanScenes(prepared);
    if (options.json) {
        std::printf("%s\n", JsonText(stagefiles::ToJson(result.file), 2).c_str());
    } else {
        for (const lab::ScenePlan& plan : result.plans) {
            PrintPlan(plan);
        }
    }
    const int code = PrintOutcome(result.outcome);
    if (!result.outcome.Stopped() && !result.path.empty()) {
        std::fprintf(stderr, "plan: %zu scenes; plans in %s\n", result.plans.size(),
                     result.path.c_str());
    }
    return code;
}

}  // namespace

void RegisterPlanCommands(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<PlanCommandOptions>();
    CLI::App* plan = app.add_subcommand("plan", GlCommandSummary("plan"));
    plan->add_option("--config", options->request.config,
                     "variants.yaml to read; scenes/ lies next to it")
            ->capture_default_str();
    plan->add_option("--scene", options->request.scenes, "plan scenes/NAME.yaml (repeatable)");
    plan->add_flag("--all", options->request.all, "plan every scenes/*.yaml and write plans.json");
    plan->add_option("--size", options->size, "render size WxH")->capture_default_str();
    plan->add_option("--resolution", options->request.resolution,
                     "time each candidate against the full effect, pair by pair, until its 95% "
                     "interval is this narrow (half-width, percent points)")
            ->capture_default_str();
    plan->add_option("--contended-share", options->request.contended_share,
                     "pairs of frames timed with a competing thread on the rendering thread's "
                     "core, per pair timed as the machine runs; each candidate's interval spans "
                     "both (0: none)")
            ->capture_default_str();
    plan->add_option("--backend", options->backend, "auto (EGL, then OSMesa), egl or osmesa")
            ->capture_default_str();
    plan->add_option("--threads", options->request.threads,
                     "llvmpipe threads (LP_NUM_THREADS; 0 renders on the calling thread)")
            ->capture_default_str();
    plan->add_flag("--json", options->json, "print plans.json to stdout");
    plan->add_option("--out", options->request.out,
                     "folder for plans.json (default reports/out/plan with --all)")
            ->transform(NormaliseOutPath);
    plan->callback([options, &exit_code] { exit_code = RunPlan(*options); });
}

}  // namespace tidepool::cli
