// The scene planner through Mesa: it drops an effect where the scene hides it and keeps it where
// it shows, never picks an invalid variant, and the passes and draws match the scene. Small
// images and few timing rounds keep the file to a few seconds; the choices asserted here are
// between configurations a whole render pass apart, so timing noise cannot decide them.
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/lab/ScenePlanner.h"
#include "tidepool/runner/GlBackend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "GlTestEnvironment.h"
#include "TempDir.h"
#include <fmt/format.h>

namespace tidepool::lab {
namespace {

// Small enough to plan a scene in a few seconds on llvmpipe, large enough for SSIM's window and
// for the island and objects to cover many pixels.
constexpr int kWidth = 96;
constexpr int kHeight = 72;

PlanOptions SmallOptions() {
    PlanOptions options;
    options.settings.width = kWidth;
    options.settings.height = kHeight;
    // Candidates a whole pass apart resolve within the minimum pairs; the cap keeps the file to
    // a few seconds when two candidates tie.
    options.warmup_frames = 1;
    options.rule = {3.0, 10, 40, 10};
    options.clock = FrameClock::kProcessCpu;
    return options;
}

SceneDescription LoadScene(const std::string& name) {
    const SceneResult result = LoadSceneDescription(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) /
                                                    "scenes" / (name + ".yaml"));
    EXPECT_TRUE(result.scene) << name;
    return result.scene.value_or(SceneDescription{});
}

// The binary's one context and the shipped variants.yaml.
test_support::GlTestEnvironment& Get() {
    return test_support::SharedGlEnvironment();
}

// Each plan is made on first use: every test runs in a process of its own (CTest), and a plan
// takes most of a test's time, so a test plans only the scenes it asserts on.
const ScenePlan& MurkyPlan() {
    static const ScenePlan plan =
            PlanScene(*Get().context, *Get().config, LoadScene("murky_pond"), SmallOptions());
    return plan;
}

const ScenePlan& LakePlan() {
    static const ScenePlan plan =
            PlanScene(*Get().context, *Get().config, LoadScene("clear_lake"), SmallOptions());
    return plan;
}

#define REQUIRE_GL()                                          \
    do {                                                      \
        if (!Get().error.empty()) {                           \
            GTEST_SKIP() << "no GL context: " << Get().error; \
        }                                                     \
    } while (false)

const PlanCandidate* Dropping(const ScenePlan& plan, const std::string& effect) {
    for (const PlanCandidate& c : plan.candidates) {
        if (c.drops == effect) {
            return &c;
        }
    }
    return nullptr;
}

const PlanCandidate& Chosen(const ScenePlan& plan) {
    return plan.candidates.at(static_cast<std::size_t>(plan.chosen));
}

bool HasPass(const FrameReport& frame, const std::string& name) {
    return std::find(frame.pass_names.begin(), frame.pass_names.end(), name) !=
           frame.pass_names.end();
}

TEST(ScenePlannerGlTest, MurkyPondDropsRefractionWithinTarget) {
    REQUIRE_GL();
    const ScenePlan& plan = MurkyPlan();
    ASSERT_GE(plan.chosen, 0);
    const PlanCandidate* drop = Dropping(plan, "refraction");
    ASSERT_NE(drop, nullptr);
    ASSERT_TRUE(drop->valid);
    EXPECT_TRUE(drop->meets_quality) << drop->error.psnr_db << " dB";
    EXPECT_TRUE(plan.met);
    const PlanCandidate& chosen = Chosen(plan);
    EXPECT_FALSE(chosen.configuration.Has("ENABLE_REFRACTION")) << chosen.configuration.id;
    EXPECT_FALSE(HasPass(chosen.frame, "refraction"));
    // One pass fewer (refraction), one more fewer when the sky cube map replaced the reflection
    // pass, one back when the water moved to a low-resolution pass.
    const bool planar = !chosen.configuration.Has("REFLECTION_CUBEMAP") &&
                        !chosen.configuration.Has("REFLECTION_FOURIER");
    EXPECT_EQ(plan.passes_saved,
              1 + (planar ? 0 : 1) - (chosen.configuration.passes.low_res_water ? 1 : 0))
            << chosen.configuration.id;
    const bool explained =
            std::any_of(plan.dropped.begin(), plan.dropped.end(), [](const DroppedEffect& d) {
                return d.effect == "refraction" && d.reason.find("dB PSNR") != std::string::npos;
            });
    EXPECT_TRUE(explained);
}

TEST(ScenePlannerGlTest, ClearLakeKeepsRefractionBecauseDroppingItBreaksTheTarget) {
    REQUIRE_GL();
    const ScenePlan& plan = LakePlan();
    ASSERT_GE(plan.chosen, 0);
    const PlanCandidate* drop = Dropping(plan, "refraction");
    ASSERT_NE(drop, nullptr);
    ASSERT_TRUE(drop->valid);
    EXPECT_FALSE(drop->meets_quality) << drop->error.psnr_db << " dB";
    const PlanCandidate& chosen = Chosen(plan);
    EXPECT_TRUE(chosen.configuration.Has("ENABLE_REFRACTION")) << chosen.configuration.id;
    EXPECT_TRUE(HasPass(chosen.frame, "refraction"));
    EXPECT_TRUE(plan.met);
}

// The time a kept effect's reason quotes is the estimate with its interval and pairs: the drop
// was timed coarsely (it misses the target), and its change alone would read as a firm saving.
TEST(ScenePlannerGlTest, AKeptEffectQuotesItsTimeWithTheIntervalAndPairs) {
    REQUIRE_GL();
    const ScenePlan& plan = LakePlan();
    const PlanCandidate* drop = Dropping(plan, "refraction");
    ASSERT_NE(drop, nullptr);
    const auto kept = std::find_if(plan.kept.begin(), plan.kept.end(),
                                   [](const DroppedEffect& k) { return k.effect == "refraction"; });
    ASSERT_NE(kept, plan.kept.end());
    // One decimal, the minus sign the report writes.
    const auto figure = [](double value) {
        const double tenths = std::round(value * 10.0) / 10.0;
        return fmt::format("{}{:.1f}", tenths < 0 ? "\u2212" : "+", std::fabs(tenths));
    };
    const std::string quoted =
            fmt::format("time {}% [{}, {}] over {} pairs", figure(drop->time_change_percent),
                        figure(drop->time_change_low), figure(drop->time_change_high), drop->pairs);
    EXPECT_NE(kept->reason.find(quoted), std::string::npos) << quoted << " in: " << kept->reason;
    EXPECT_GT(drop->time_change_high, drop->time_change_low);
}

// `scene` planned under a resolution no interval reaches: a candidate timed to the resolution
// runs to the cap of kCapPairs, one timed coarsely stops at the fewest, kFewestPairs.
constexpr int kFewestPairs = 10;
constexpr int kCapPairs = 24;
ScenePlan PlanToTheCap(const SceneDescription& scene) {
    PlanOptions options = SmallOptions();
    options.rule = {0.01, kFewestPairs, kCapPairs, 10};
    return PlanScene(*Get().context, *Get().config, scene, options);
}

// A candidate whose image misses the scene's target is never chosen while another meets it, so
// it is timed for the rule's fewest pairs only; one that meets it goes on as the rule says.
TEST(ScenePlannerGlTest, ACandidateThatMissesTheTargetIsTimedForTheFewestPairsOnly) {
    REQUIRE_GL();
    const ScenePlan plan = PlanToTheCap(LoadScene("murky_pond"));
    int missing = 0;
    int meeting = 0;
    for (std::size_t i = 1; i < plan.candidates.size(); ++i) {
        const PlanCandidate& c = plan.candidates[i];
        if (!c.valid) {
            continue;
        }
        EXPECT_EQ(c.pairs, c.meets_quality ? kCapPairs : kFewestPairs) << c.configuration.id;
        (c.meets_quality ? meeting : missing) += 1;
    }
    EXPECT_GT(missing, 0);
    EXPECT_GT(meeting, 0);
}

// With a frame budget the fastest candidate of all may be chosen when none that meets the image
// bounds fits it, so one that misses them is timed like the others.
TEST(ScenePlannerGlTest, WithAFrameBudgetEveryCandidateIsTimedToTheResolution) {
    REQUIRE_GL();
    SceneDescription scene = LoadScene("murky_pond");
    scene.target.frame_budget_ms = 1000.0;
    const ScenePlan plan = PlanToTheCap(scene);
    int missing = 0;
    for (std::size_t i = 1; i < plan.candidates.size(); ++i) {
        const PlanCandidate& c = plan.candidates[i];
        if (c.valid) {
            EXPECT_EQ(c.pairs, kCapPairs) << c.configuration.id;
            missing += c.meets_quality ? 0 : 1;
        }
    }
    EXPECT_GT(missing, 0);
}

// The tie rule (ChooseCandidate) may keep a more accurate candidate over one faster by less
// than their intervals, but never one that another qualifying candidate beats beyond both.
// The choice rule on real plans (PlannerChoiceTest has it on synthetic measures): the fastest
// qualifying candidate faster than full beyond its interval and the direction margin is chosen,
// or one that ties with it (the intervals overlap, or the changes differ by less than the
// planner's resolution) and is at least as accurate; with none, the full effect is kept. A
// qualifying candidate a point or two faster than the chosen one is therefore allowed: that is
// the tie the rule keeps for accuracy, and timing noise may put it either side.
TEST(ScenePlannerGlTest, EveryChoiceMeetsTheTargetAndNoneThatDoesIsFasterBeyondTheTieRule) {
    REQUIRE_GL();
    const double resolution = SmallOptions().rule.resolution_points;
    for (const ScenePlan* plan : {&MurkyPlan(), &LakePlan()}) {
        const PlanCandidate& chosen = Chosen(*plan);
        EXPECT_TRUE(chosen.valid && chosen.meets_quality);
        EXPECT_FALSE(plan->choice_reason.empty());
        const PlanCandidate* fastest = nullptr;
        for (std::size_t i = 1; i < plan->candidates.size(); ++i) {
            const PlanCandidate& c = plan->candidates[i];
            if (c.valid && c.meets_quality && c.time_change_high < -base::kDirectionMarginPoints &&
                (fastest == nullptr || c.time_change_percent < fastest->time_change_percent)) {
                fastest = &c;
            }
        }
        if (fastest == nullptr) {
            EXPECT_EQ(plan->chosen, 0) << plan->choice_reason;
            continue;
        }
        EXPECT_NE(plan->chosen, 0) << plan->choice_reason;
        EXPECT_LT(chosen.time_change_high, -base::kDirectionMarginPoints) << plan->choice_reason;
        const bool overlaps = chosen.time_change_low <= fastest->time_change_high &&
                              fastest->time_change_low <= chosen.time_change_high;
        const bool within_resolution =
                chosen.time_change_percent - fastest->time_change_percent < resolution;
        EXPECT_TRUE(&chosen == fastest || overlaps || within_resolution)
                << chosen.configuration.id << " vs the fastest " << fastest->configuration.id
                << ": " << plan->choice_reason;
        EXPECT_GE(chosen.error.psnr_db, fastest->error.psnr_db) << plan->choice_reason;
    }
}

TEST(ScenePlannerGlTest, ReflectionDrawsOnlyWhatIsAboveTheWater) {
    REQUIRE_GL();
    const ScenePlan& plan = LakePlan();
    const Scene scene = BuildSceneFromDescription(plan.scene);
    // The clear lake keeps its submerged rocks; the reflection pass must leave them out.
    int above = 0;
    int below = 0;
    for (const Mesh& mesh : scene.objects) {
        (IsEntirelyBelow(mesh, scene.water_height - RenderSettings{}.clip_plane_offset) ? below
                                                                                        : above)++;
    }
    ASSERT_GT(below, 0);
    const FrameReport& frame = plan.candidates.front().frame;
    ASSERT_EQ(frame.pass_names.front(), "reflection");
    // Sky, terrain and every object not wholly under the water.
    EXPECT_EQ(frame.pass_draw_calls.front(), 1 + 1 + above);
    ASSERT_EQ(frame.pass_names.size(), frame.pass_pixels.size());
    EXPECT_EQ(frame.pass_pixels.back(), static_cast<long long>(kWidth) * kHeight);
}

TEST(ScenePlannerGlTest, OpenSeaReflectsOnlyTheSkyAndRefractsNothingTheFogHides) {
    REQUIRE_GL();
    const SceneDescription sea = LoadScene("open_sea");
    const Scene scene = BuildSceneFromDescription(sea);
    EXPECT_TRUE(scene.objects.empty());
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.rcp_max_fog_depth = 1.0F / sea.fog_depth;
    std::string error;
    auto renderer = WaterRenderer::Create(*Get().context, *Get().config, settings, &error, &scene);
    ASSERT_TRUE(renderer) << error;
    std::vector<Diagnostic> diagnostics;
    const std::vector<PlanCandidate> candidates =
            ProposeCandidates(*Get().config, sea, "full", settings, &diagnostics);
    ASSERT_FALSE(candidates.empty());
    const RenderConfiguration& full = candidates.front().configuration;
    ASSERT_TRUE(renderer->Prepare(full).valid);
    const FrameReport frame = renderer->RenderFrame(full, SceneCameraView(sea));
    ASSERT_EQ(frame.pass_names, (std::vector<std::string>{"reflection", "refraction", "main"}));
    EXPECT_EQ(frame.pass_draw_calls[0], 1);  // the sky only: the floor lies 200 down
    EXPECT_EQ(frame.pass_draw_calls[1], 0);  // fog hides the floor; the sky is left out under fog
}

TEST(ScenePlannerGlTest, InvalidVariantIsNeverChosen) {
    REQUIRE_GL();
    // A copy of the configuration whose water-colour block does not compile.
    testing::TempDir dir;
    const std::filesystem::path root(TIDEPOOL_SOURCE_ROOT);
    std::filesystem::copy(root / "shaders", dir.Path() / "shaders",
                          std::filesystem::copy_options::recursive);
    std::filesystem::copy_file(root / "variants.yaml", dir.Path() / "variants.yaml");
    const std::filesystem::path fragment = dir.Path() / "shaders" / "water.fsh";
    std::ifstream in(fragment);
    std::stringstream broken;
    std::string line;
    int blocks = 0;
    while (std::getline(in, line)) {
        broken << line << "\n";
        if (line.rfind("#ifdef ENABLE_WATER_COLOUR", 0) == 0) {
            broken << "    this_function_does_not_exist();\n";
            ++blocks;
        }
    }
    in.close();
    ASSERT_GT(blocks, 0);
    std::ofstream(fragment) << broken.str();
    ConfigResult loaded = LoadVariantConfig(dir.Path() / "variants.yaml");
    ASSERT_TRUE(loaded.config);
    const ScenePlan plan =
            PlanScene(*Get().context, *loaded.config, LoadScene("murky_pond"), SmallOptions());
    ASSERT_GE(plan.chosen, 0);
    int invalid = 0;
    for (const PlanCandidate& c : plan.candidates) {
        if (c.configuration.Has("ENABLE_WATER_COLOUR")) {
            EXPECT_FALSE(c.valid) << c.configuration.id;
            ++invalid;
        }
    }
    EXPECT_GT(invalid, 0);
    const PlanCandidate& chosen = Chosen(plan);
    EXPECT_TRUE(chosen.valid);
    EXPECT_FALSE(chosen.configuration.Has("ENABLE_WATER_COLOUR")) << chosen.configuration.id;
}

}  // namespace
}  // namespace tidepool::lab
