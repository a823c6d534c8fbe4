// Units shared with a second process (runner/src/SharedUnits.cpp): what the second process
// renders or times and hands over is what the render process would have recorded itself. Both
// sides run here one after the other in one process, on the shared context: the second process's
// side first, so that it takes every unit but the reference's.
#include "tidepool/base/SharedClaims.h"
#include "tidepool/runner/Results.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ConfigurationImages.h"
#include "FileContents.h"
#include "SharedWaterRenderer.h"
#include "TempDir.h"

namespace tidepool::runner {
namespace {

using test_support::WaterConfiguration;

// Four configurations (the first the reference) at two views, 32x24, no comparisons, images
// written under `out`.
RunOptions FourConfigurations(const std::filesystem::path& out) {
    RunOptions options;
    options.configurations = {WaterConfiguration({}), WaterConfiguration({"ENABLE_FOG"}),
                              WaterConfiguration({"ENABLE_REFRACTION"}),
                              WaterConfiguration({"ENABLE_FOG", "ENABLE_REFRACTION"})};
    options.configurations[0].presets = {options.reference_preset};
    const std::vector<CameraView> views = DefaultViews();
    options.views = {views.at(0), views.at(1)};
    options.settings.width = 32;
    options.settings.height = 24;
    options.coarse_frames = 2;
    options.compare_with_glslang = false;
    options.out_dir = out;
    return options;
}

struct SharedRun {
    std::unique_ptr<base::SharedClaims> claims;
    RunOptions options;
};

// The four configurations and a comparison of the reference with the second: five units.
SharedRun WithASecondProcess(const std::filesystem::path& out) {
    SharedRun run{base::SharedClaims::Create(5), FourConfigurations(out)};
    // The second process takes the comparison too: the per-pass times of its two configurations
    // are then the second process's, and must survive the configurations' own units.
    run.options.comparisons = {{"fog", 0, 1}};
    run.options.rule = {50.0, 4, 4, 4};
    run.options.pass_frames = 1;
    run.options.warmup_frames = 0;
    run.options.shared = {run.claims.get(), out / ".second-process"};
    return run;
}

// What a unit records apart from its frame times, which differ from frame to frame.
stagefiles::ResultsConfiguration WithoutTimes(stagefiles::ResultsConfiguration entry) {
    entry.samples_ms.clear();
    entry.cpu_samples_ms.clear();
    entry.statistics.reset();
    entry.cpu_statistics.reset();
    entry.plan_ms_median = 0;
    entry.pass_ms.clear();
    entry.instrumented_frame_ms = 0;
    return entry;
}

TEST(SharedUnitsGlTest, UnitsTheSecondProcessRenderedEqualTheRenderProcesssOwn) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    const testing::TempDir alone_dir;
    const testing::TempDir shared_dir;
    const RunResults alone = RunRender(*shared.context, *shared.config,
                                       FourConfigurations(alone_dir.Path()), nullptr);
    SharedRun run = WithASecondProcess(shared_dir.Path());
    ASSERT_TRUE(run.claims);
    const SharedUnitsDone done = RenderSharedUnits(*shared.context, *shared.config, run.options);
    EXPECT_EQ(done.error, "");
    EXPECT_EQ(done.configurations, 3);  // every unit but the reference's
    EXPECT_EQ(done.comparisons, 1);
    const RunResults together = RunRender(*shared.context, *shared.config, run.options, nullptr);
    EXPECT_EQ(together.shared_configurations, 3);
    EXPECT_EQ(together.SharedComparisons(), 1);
    for (std::size_t compared : {0U, 1U}) {
        EXPECT_GT(together.configurations[compared].pass_ms.count("main"), 0U) << compared;
        EXPECT_GT(together.configurations[compared].instrumented_frame_ms, 0.0) << compared;
    }
    // The comparison's own per-pass times come back from the second process's unit too.
    ASSERT_EQ(together.comparisons.size(), 1U);
    EXPECT_GT(together.comparisons[0].timing.baseline_passes.pass_ms.count("main"), 0U);
    EXPECT_GT(together.comparisons[0].timing.candidate_passes.frame_ms, 0.0);
    EXPECT_TRUE(together.comparisons[0].timed_by_second_process);
    for (const ComparisonResult& c : alone.comparisons) {
        EXPECT_FALSE(c.timed_by_second_process) << c.comparison.label;
    }

    const stagefiles::ResultsFile expected = ToResultsFile(alone);
    const stagefiles::ResultsFile got = ToResultsFile(together);
    ASSERT_EQ(got.configurations.size(), expected.configurations.size());
    for (std::size_t i = 0; i < got.configurations.size(); ++i) {
        const stagefiles::ResultsConfiguration& g = got.configurations[i];
        EXPECT_EQ(WithoutTimes(g), WithoutTimes(expected.configurations[i])) << g.id;
        EXPECT_EQ(g.cpu_samples_ms.size(), 2U) << g.id;
        for (const stagefiles::ResultsViewResult& view : g.views) {
            ASSERT_TRUE(view.accuracy) << g.id << " " << view.view;
            EXPECT_EQ(testing::ReadText(shared_dir.Path() / view.image),
                      testing::ReadText(alone_dir.Path() / view.image))
                    << view.image;
        }
    }
}

// Its samples in the order taken, the estimate over them, the decision and the label.
TEST(SharedUnitsGlTest, AComparisonTheSecondProcessTimedIsReadBackWhole) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    const testing::TempDir out;
    SharedRun run = WithASecondProcess(out.Path());
    ASSERT_TRUE(run.claims);
    run.options.rule = {50.0, 10, 10, 10};  // enough pairs for a 95% interval
    ASSERT_EQ(RenderSharedUnits(*shared.context, *shared.config, run.options).comparisons, 1);
    const stagefiles::ReadResult<stagefiles::ResultsFile> unit =
            stagefiles::ReadResultsFile(out.Path() / ".second-process/4.json");
    ASSERT_TRUE(unit.value);
    ASSERT_EQ(unit.value->comparisons.size(), 1U);
    const stagefiles::ResultsComparison& handed = unit.value->comparisons.front();
    EXPECT_EQ(handed.pairs, 10);
    ASSERT_TRUE(std::isfinite(handed.change_low) && std::isfinite(handed.change_high));

    const RunResults results = RunRender(*shared.context, *shared.config, run.options, nullptr);
    ASSERT_EQ(results.SharedComparisons(), 1);
    const ComparisonResult& c = results.comparisons.front();
    EXPECT_EQ(c.error, "");
    EXPECT_EQ(c.comparison.label, "fog");
    EXPECT_EQ(c.comparison.baseline, 0U);
    EXPECT_EQ(c.comparison.candidate, 1U);
    EXPECT_EQ(c.timing.samples.baseline_ms, handed.baseline_ms);
    EXPECT_EQ(c.timing.samples.candidate_ms, handed.candidate_ms);
    EXPECT_EQ(c.timing.samples.candidate_wall_ms, handed.candidate_wall_ms);
    EXPECT_EQ(base::StopDecisionName(c.timing.decision), handed.decision);
    EXPECT_EQ(c.timing.estimate.pairs, 10);
    EXPECT_DOUBLE_EQ(c.timing.estimate.change_percent, handed.change_percent);
    EXPECT_DOUBLE_EQ(c.timing.estimate.change_low, handed.change_low);
    EXPECT_DOUBLE_EQ(c.timing.estimate.change_high, handed.change_high);
    // The second process writes its unit as its own render's; the render process, reading it
    // back, records it as the second process's.
    EXPECT_EQ(handed.timed_by, "render");
    EXPECT_TRUE(c.timed_by_second_process);
    EXPECT_EQ(ToResultsFile(results).comparisons.front().timed_by, "second_process");
}

// The render probes every comparison first, but a probe claims nothing: a second process that
// runs out of other units before the render goes on with the comparison takes it whole, and its
// results replace the probe's.
TEST(SharedUnitsGlTest, AComparisonTheRenderProbedIsStillTheSecondProcesssToTakeWhole) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    const testing::TempDir out;
    SharedRun run = WithASecondProcess(out.Path());
    ASSERT_TRUE(run.claims);
    run.options.rule = {50.0, kProbePairs + 2, kProbePairs + 2, kProbePairs + 2};
    ASSERT_TRUE(ProbesComparisons(run.options));
    // The second process's results file of the comparison, from a claim table of its own.
    const std::unique_ptr<base::SharedClaims> earlier = base::SharedClaims::Create(5);
    ASSERT_TRUE(earlier);
    RunOptions helper_options = run.options;
    helper_options.shared.claims = earlier.get();
    ASSERT_EQ(RenderSharedUnits(*shared.context, *shared.config, helper_options).comparisons, 1);
    const stagefiles::ReadResult<stagefiles::ResultsFile> unit =
            stagefiles::ReadResultsFile(out.Path() / ".second-process/4.json");
    ASSERT_TRUE(unit.value);
    ASSERT_EQ(unit.value->comparisons.size(), 1U);

    // The second process claims and hands over the comparison right after its probe's first
    // frames: what it could do once the render had probed them all.
    bool probed = false;
    bool claimed = false;
    const RunResults results =
            RunRender(*shared.context, *shared.config, run.options, [&](const RunProgress& p) {
                if (p.stage == "comparisons" && !probed) {
                    probed = true;
                    claimed = run.claims->ClaimForHelper(4) && run.claims->FinishForHelper(4);
                }
            });
    EXPECT_TRUE(probed);
    EXPECT_TRUE(claimed);
    ASSERT_EQ(results.comparisons.size(), 1U);
    const ComparisonResult& c = results.comparisons.front();
    EXPECT_TRUE(c.timed_by_second_process);
    EXPECT_EQ(c.timing.samples.baseline_ms, unit.value->comparisons.front().baseline_ms);
    EXPECT_EQ(c.timing.samples.candidate_ms, unit.value->comparisons.front().candidate_ms);
    EXPECT_EQ(c.timing.estimate.pairs, kProbePairs + 2);
}

// Both sides, with the second process's results file of claim-table unit `unit` cut short: the
// render process must do that unit itself.
RunResults WithAUnitCutShort(std::size_t unit) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    const testing::TempDir out;
    SharedRun run = WithASecondProcess(out.Path());
    EXPECT_TRUE(run.claims);
    const SharedUnitsDone done = RenderSharedUnits(*shared.context, *shared.config, run.options);
    EXPECT_EQ(done.configurations, 3);
    EXPECT_EQ(done.comparisons, 1);
    out.Write(".second-process/" + std::to_string(unit) + ".json", "{\"schema\": ");
    return RunRender(*shared.context, *shared.config, run.options, nullptr);
}

TEST(SharedUnitsGlTest, AComparisonWhoseResultsCannotBeReadIsTimedByTheRenderProcess) {
    ASSERT_TRUE(test_support::SharedWaterRenderer().context);
    const RunResults results = WithAUnitCutShort(4);
    EXPECT_EQ(results.SharedComparisons(), 0);
    EXPECT_EQ(results.shared_configurations, 3);
    const ComparisonResult& c = results.comparisons.front();
    EXPECT_EQ(c.error, "");
    EXPECT_EQ(c.timing.estimate.pairs, 4);
    for (std::size_t compared : {0U, 1U}) {
        EXPECT_GT(results.configurations[compared].pass_ms.count("main"), 0U) << compared;
    }
}

TEST(SharedUnitsGlTest, AUnitWhoseResultsCannotBeReadIsRenderedByTheRenderProcess) {
    ASSERT_TRUE(test_support::SharedWaterRenderer().context);
    const RunResults results = WithAUnitCutShort(2);
    EXPECT_EQ(results.shared_configurations, 2);
    EXPECT_EQ(results.SharedComparisons(), 1);
    for (const ConfigurationResult& r : results.configurations) {
        EXPECT_TRUE(r.Ok()) << r.configuration.id;
        EXPECT_EQ(r.views.size(), 2U) << r.configuration.id;
        EXPECT_EQ(r.cpu_samples_ms.size(), 2U) << r.configuration.id;
    }
}

TEST(SharedUnitsGlTest, WithoutClaimsTheSecondProcessRendersNothing) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    const testing::TempDir out;
    const SharedUnitsDone done =
            RenderSharedUnits(*shared.context, *shared.config, FourConfigurations(out.Path()));
    EXPECT_EQ(done.configurations, 0);
    EXPECT_EQ(done.error, "");
    EXPECT_FALSE(std::filesystem::exists(out.Path() / "images"));
}

}  // namespace
}  // namespace tidepool::runner
