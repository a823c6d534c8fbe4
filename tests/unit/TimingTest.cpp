#include "tidepool/pipeline/Host.h"
#include "tidepool/pipeline/Timing.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/runner/Results.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace tidepool::pipeline {
namespace {

runner::RenderConfiguration WithPresets(std::string id, std::vector<std::string> presets) {
    runner::RenderConfiguration c;
    c.id = std::move(id);
    c.presets = std::move(presets);
    return c;
}

TEST(TimingTest, SettingsBecomeTheRuleTheFramesAndOneThreadByDefault) {
    TimingSettings settings;
    settings.resolution = 0.75;
    settings.min_pairs = 30;
    settings.max_pairs = 90;
    settings.coarse_frames = 4;
    settings.warmup = 1;
    runner::RunOptions run;
    ApplyTiming(settings, runner::BackendKind::kAuto, &run);
    EXPECT_DOUBLE_EQ(run.rule.resolution_points, 0.75);
    EXPECT_EQ(run.rule.min_pairs, 30);
    EXPECT_EQ(run.rule.max_pairs, 90);
    EXPECT_EQ(run.coarse_frames, 4);
    EXPECT_EQ(run.warmup_frames, 1);
    EXPECT_EQ(run.workers, 1);
    EXPECT_TRUE(run.make_context);
    EXPECT_EQ(run.host.lp_num_threads, "0");
    EXPECT_STREQ(std::getenv("LP_NUM_THREADS"), "0");
    settings.workers = 0;  // one per core
    ApplyTiming(settings, runner::BackendKind::kAuto, &run);
    EXPECT_EQ(run.workers, DefaultJobs());
}

// Only pairs whose two presets are both rendered become comparisons, each named as the report
// names it and with its verdict's boundaries.
// results.json states the stopping rule the comparisons were timed by, its boundary clauses too,
// so that a replay of the file (bench/replay_comparisons) runs the rule the run ran.
TEST(TimingTest, TheResultsFileRecordsTheRuleItsComparisonsWereTimedBy) {
    TimingSettings settings;
    settings.resolution = 0.75;
    settings.min_pairs = 30;
    settings.max_pairs = 90;
    runner::RunResults results;
    ApplyTiming(settings, runner::BackendKind::kAuto, &results.options);
    results.options.rule.boundary_pairs = 96;
    results.options.rule.boundary_standard_errors = 2.0;
    const stagefiles::ResultsTiming timing = runner::ToResultsFile(results).timing;
    EXPECT_EQ(timing.resolution_points, 0.75);
    EXPECT_EQ(timing.min_pairs, 30);
    EXPECT_EQ(timing.max_pairs, 90);
    EXPECT_EQ(timing.batch_pairs, results.options.rule.batch_pairs);
    EXPECT_EQ(timing.contended_share, results.options.rule.contended_share);
    EXPECT_EQ(timing.boundary_pairs, 96);
    EXPECT_EQ(timing.boundary_standard_errors, 2.0);
}

TEST(TimingTest, ComparisonsAreTheComparedPresetPairsBothOfWhoseSidesAreRendered) {
    const report::PresetPair row = report::ComparedPresetPairs().front();
    runner::RunOptions run;
    run.configurations = {WithPresets("a", {row.baseline}), WithPresets("other", {"unrelated"}),
                          WithPresets("b", {row.candidate})};
    ApplyTiming(TimingSettings{}, runner::BackendKind::kAuto, &run);
    ASSERT_EQ(run.comparisons.size(), 1U);
    EXPECT_EQ(run.comparisons[0].label, row.label);
    EXPECT_EQ(run.comparisons[0].baseline, 0U);
    EXPECT_EQ(run.comparisons[0].candidate, 2U);
    // Row 1's magnitude band: timed until the interval clears where its verdict changes.
    EXPECT_FALSE(row.boundaries_points.empty());
    EXPECT_EQ(run.comparisons[0].boundaries_points, row.boundaries_points);
    run.configurations.pop_back();
    ApplyTiming(TimingSettings{}, runner::BackendKind::kAuto, &run);
    EXPECT_TRUE(run.comparisons.empty());
}

TEST(TimingTest, HostDescriptionNamesTheCommandAndTheBuild) {
    const runner::HostInfo host = DescribeHost("bench", "variants.yaml");
    EXPECT_EQ(host.command, "bench");
    EXPECT_FALSE(host.build_type.empty());
    EXPECT_FALSE(host.git_revision.empty());
}

}  // namespace
}  // namespace tidepool::pipeline
