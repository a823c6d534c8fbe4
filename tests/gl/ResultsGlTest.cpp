// The render loop (runner/include/tidepool/runner/Results.h, RunRender): comparisons timed in
// pairs until the stopping rule, coarse timing per configuration, the run's glslang verdicts
// reused, a second rendering worker. Tiny images so the suite stays fast.
#include "tidepool/GlslValidator.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "ConfigurationImages.h"
#include "SharedWaterRenderer.h"

namespace tidepool::runner {
namespace {

using test_support::WaterConfiguration;

TEST(ResultsGlTest, ComparisonsArePairedUntilTheStoppingRuleAndConfigurationsTimedCoarsely) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    RunOptions options;
    options.configurations = {WaterConfiguration({}), WaterConfiguration({"ENABLE_FOG"}),
                              WaterConfiguration({"ENABLE_REFRACTION"})};
    options.views = {DefaultViews().front()};
    options.settings.width = 32;
    options.settings.height = 24;
    options.warmup_frames = 0;
    options.coarse_frames = 3;
    options.comparisons = {{"fog", 0, 1}, {"refraction", 0, 2}};
    // A resolution this tight is out of reach in 20 pairs, so both stop at the cap.
    options.rule = {0.001, 10, 20, 10};
    options.pass_frames = 2;
    options.write_images = false;
    options.compare_with_glslang = false;
    const RunResults results = RunRender(*shared.context, *shared.config, options, nullptr);
    ASSERT_EQ(results.configurations.size(), 3U);
    for (const ConfigurationResult& r : results.configurations) {
        EXPECT_EQ(r.cpu_samples_ms.size(), 3U) << r.configuration.id;
        EXPECT_EQ(r.samples_ms.size(), 3U) << r.configuration.id;
    }
    ASSERT_EQ(results.comparisons.size(), 2U);
    for (const ComparisonResult& c : results.comparisons) {
        EXPECT_EQ(c.error, "") << c.comparison.label;
        EXPECT_EQ(c.timing.samples.baseline_ms.size(), 20U) << c.comparison.label;
        EXPECT_EQ(c.timing.samples.candidate_ms.size(), 20U) << c.comparison.label;
        EXPECT_EQ(c.timing.decision, base::StopDecision::kCapped) << c.comparison.label;
        EXPECT_TRUE(c.timing.estimate.Valid()) << c.timing.estimate.error;
        // Each comparison has both sides' per-pass times of its own.
        EXPECT_GT(c.timing.baseline_passes.pass_ms.count("main"), 0U) << c.comparison.label;
        EXPECT_GT(c.timing.candidate_passes.pass_ms.count("main"), 0U) << c.comparison.label;
        EXPECT_GT(c.timing.baseline_passes.frame_ms, 0.0) << c.comparison.label;
        EXPECT_GT(c.timing.candidate_passes.frame_ms, 0.0) << c.comparison.label;
    }
    EXPECT_EQ(results.comparisons[1].timing.candidate_passes.pass_ms.count("refraction"), 1U);
    EXPECT_EQ(results.comparisons[1].timing.baseline_passes.pass_ms.count("refraction"), 0U);
    // Every compared configuration has per-pass times; the refraction one has that pass.
    EXPECT_EQ(results.configurations[2].pass_ms.count("refraction"), 1U);
    EXPECT_EQ(results.configurations[0].pass_ms.count("refraction"), 0U);
    EXPECT_GT(results.configurations[0].pass_ms.at("main"), 0.0);
}

// The progress line counts what the render does: every frame of the images, every pair of a
// comparison with its contended pairs, and the frames a comparison renders besides them (both
// sides' warm-up again after its probe, the per-pass pairs), so that it ends with all of its
// expected frames done and none left. (A worker's first-use warm-up of a configuration is not
// counted.)
TEST(ResultsGlTest, ProgressCountsAComparisonsPairsWarmUpAndPerPassFramesAndEndsWithNoneLeft) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    RunOptions options;
    options.configurations = {WaterConfiguration({}), WaterConfiguration({"ENABLE_FOG"})};
    options.views = {DefaultViews().front()};
    options.settings.width = 32;
    options.settings.height = 24;
    options.warmup_frames = 1;
    options.coarse_frames = 2;
    options.comparisons = {{"fog", 0, 1}};
    // Out of reach: the comparison takes its probe, then pairs up to the cap of 30 in one state
    // (as run, or with the core shared where those pairs narrow the stated interval more).
    options.rule.resolution_points = 0.001;
    options.rule.min_pairs = 20;
    options.rule.max_pairs = 30;
    options.rule.contended_share = 0.5;
    options.pass_frames = 2;
    options.write_images = false;
    options.compare_with_glslang = false;
    ASSERT_TRUE(ProbesComparisons(options));
    std::vector<RunProgress> seen;
    const ProgressCallback progress = [&](const RunProgress& p) { seen.push_back(p); };
    const RunResults results = RunRender(*shared.context, *shared.config, options, progress);
    ASSERT_EQ(results.comparisons.size(), 1U);
    const ComparisonTiming& timing = results.comparisons[0].timing;
    ASSERT_EQ(results.comparisons[0].error, "");
    ASSERT_EQ(timing.decision, base::StopDecision::kCapped);
    ASSERT_EQ(std::max(timing.samples.baseline_ms.size(), timing.contended.baseline_ms.size()),
              30U);
    ASSERT_FALSE(timing.contended.baseline_ms.empty());
    ASSERT_FALSE(seen.empty());
    const long pairs = static_cast<long>(timing.samples.baseline_ms.size() +
                                         timing.contended.baseline_ms.size());
    const long overhead = 2L * (options.warmup_frames + options.pass_frames);
    const long images = 2 * FramesPerConfiguration(options);
    EXPECT_EQ(seen.back().done, images + 2 * pairs + overhead);
    EXPECT_EQ(seen.back().total, seen.back().done);
    EXPECT_DOUBLE_EQ(seen.back().percent, 100.0);
    // The per-pass frames are counted last, after the warm-up and the pairs.
    EXPECT_EQ(seen[seen.size() - 2].done, images + 2 * pairs + 2L * options.warmup_frames);
}

// Two configurations (none and fog) at one view, 32x24, timed coarsely only, no images, no
// glslang comparison.
RunOptions TinyRunWithoutComparisons(int coarse_frames) {
    RunOptions options;
    options.configurations = {WaterConfiguration({}), WaterConfiguration({"ENABLE_FOG"})};
    options.views = {DefaultViews().front()};
    options.settings.width = 32;
    options.settings.height = 24;
    options.coarse_frames = coarse_frames;
    options.write_images = false;
    options.compare_with_glslang = false;
    return options;
}

TEST(ResultsGlTest, GlslangVerdictsGivenByTheRunsValidationAreUsedNotFoundAgain) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    RunOptions options = TinyRunWithoutComparisons(1);
    options.compare_with_glslang = true;
    // A verdict glslang would never give (both variants are valid): the render must take it
    // from here, so Mesa's acceptance shows as a disagreement for that variant only.
    ValidationReport validated;
    VariantVerdict said_invalid;
    said_invalid.variant = options.configurations[1].variant;
    said_invalid.target = GlslTarget::kEs100;
    said_invalid.valid = false;
    validated.verdicts.push_back(said_invalid);
    options.validated = &validated;
    const RunResults results = RunRender(*shared.context, *shared.config, options, nullptr);
    ASSERT_EQ(results.disagreements.size(), 1U);
    EXPECT_EQ(results.disagreements[0].variant, options.configurations[1].variant.Id());
    EXPECT_FALSE(results.disagreements[0].glslang_valid);
    EXPECT_TRUE(results.disagreements[0].mesa_valid);
}

TEST(ResultsGlTest, SecondWorkerRendersOnItsOwnContext) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    RunOptions options = TinyRunWithoutComparisons(2);
    options.workers = 2;
    options.make_context = [] { return CreateGlContext(BackendKind::kAuto).context; };
    const RunResults results = RunRender(*shared.context, *shared.config, options, nullptr);
    EXPECT_EQ(results.workers, 2);
    for (const ConfigurationResult& r : results.configurations) {
        EXPECT_TRUE(r.Ok()) << r.configuration.id << " " << r.gl_error;
        EXPECT_EQ(r.cpu_samples_ms.size(), 2U);
    }
}

}  // namespace
}  // namespace tidepool::runner
