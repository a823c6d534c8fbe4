// A configuration's unit of the render (runner/src/ConfigurationImages.h): its verdict, an image
// per view compared with the reference's while in memory, and its coarse frames.
#include "tidepool/runner/Results.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <mutex>
#include <string>
#include <vector>

#include "ConfigurationImages.h"
#include "SharedWaterRenderer.h"

namespace tidepool::runner {
namespace {

using test_support::WaterConfiguration;

RunOptions TwoConfigurationsAtTwoViews() {
    RunOptions options;
    options.configurations = {WaterConfiguration({"ENABLE_FOG"}), WaterConfiguration({})};
    options.configurations[1].presets = {"fast", options.reference_preset};
    const std::vector<CameraView> views = DefaultViews();
    options.views = {views.at(0), views.at(1)};
    options.timing_view = views.at(1).name;
    options.settings.width = 32;
    options.settings.height = 24;
    options.coarse_frames = 3;
    options.write_images = false;
    return options;
}

TEST(ConfigurationImagesGlTest, TheTimingViewAndTheReferenceAreFoundByName) {
    RunOptions options = TwoConfigurationsAtTwoViews();
    EXPECT_EQ(TimingView(options), &options.views[1]);
    EXPECT_EQ(ReferenceConfiguration(options), 1U);
    options.timing_view.clear();
    EXPECT_EQ(TimingView(options), &options.views[0]);
    options.timing_view = "nowhere";
    EXPECT_EQ(TimingView(options), nullptr);
    options.reference_preset = "nobody";
    EXPECT_EQ(ReferenceConfiguration(options), std::nullopt);
}

// The run's order: the reference, every comparison's probe, the other compared configurations
// in the comparisons' order, then the comparisons (there are no other configurations here). A
// rule whose first look comes at the probe's pairs takes no probes.
TEST(ConfigurationImagesGlTest, TheRunsOrderProbesEveryComparisonBeforeTheirConfigurations) {
    RunOptions options = TwoConfigurationsAtTwoViews();
    options.configurations.resize(5, options.configurations[0]);  // the reference stays at 1
    auto compare = [](std::size_t baseline, std::size_t candidate) {
        TimedComparison c;
        c.baseline = baseline;
        c.candidate = candidate;
        return c;
    };
    options.comparisons = {compare(1, 3), compare(4, 2), compare(3, 0), compare(9, 0)};
    struct Unit {
        bool comparison;
        std::size_t index;
        bool probe;
    };
    auto expect_order = [&](const std::vector<Unit>& expected) {
        const std::vector<WorkUnit> units = RunWorkOrder(options);
        ASSERT_EQ(units.size(), expected.size());
        for (std::size_t u = 0; u < units.size(); ++u) {
            EXPECT_EQ(units[u].comparison, expected[u].comparison) << u;
            EXPECT_EQ(units[u].index, expected[u].index) << u;
            EXPECT_EQ(units[u].probe, expected[u].probe) << u;
        }
    };
    // The probes from both ends of the comparisons' list in turn (base::ProbeOrder).
    const std::vector<Unit> probed = {{false, 1, false}, {true, 0, true},   {true, 3, true},
                                      {true, 1, true},   {true, 2, true},   {false, 3, false},
                                      {false, 4, false}, {false, 2, false}, {false, 0, false},
                                      {true, 0, false},  {true, 1, false},  {true, 2, false},
                                      {true, 3, false}};
    ASSERT_GT(options.rule.min_pairs, kProbePairs);
    expect_order(probed);
    // Without probes: the same order less the probes.
    std::vector<Unit> unprobed;
    std::copy_if(probed.begin(), probed.end(), std::back_inserter(unprobed),
                 [](const Unit& u) { return !u.probe; });
    options.rule.min_pairs = kProbePairs;
    expect_order(unprobed);
}

TEST(ConfigurationImagesGlTest, ImagesAreComparedWithTheReferencesOnceItHasRendered) {
    test_support::SharedRenderer& shared = test_support::SharedWaterRenderer();
    ASSERT_TRUE(shared.context) << shared.error;
    const RunOptions options = TwoConfigurationsAtTwoViews();
    RenderWorker w;
    std::string error;
    w.renderer = WaterRenderer::Create(*shared.context, *shared.config, options.settings, &error);
    ASSERT_TRUE(w.renderer) << error;
    w.timer = std::make_unique<FrameTimer>(*w.renderer, FrameClock::kWall);
    ReferenceImages references;
    std::mutex errors_mutex;
    std::vector<std::string> write_errors;
    const ImageUnitContext context{options, references, nullptr, errors_mutex, write_errors};

    ConfigurationResult before;
    before.configuration = options.configurations[0];
    RenderConfigurationUnit(w, context, 0, before);
    ASSERT_TRUE(before.verdict.valid);
    ASSERT_EQ(before.views.size(), 2U);
    EXPECT_FALSE(before.views[0].accuracy);  // no reference image yet

    ConfigurationResult reference;
    reference.configuration = options.configurations[1];
    RenderConfigurationUnit(w, context, 1, reference);
    ASSERT_EQ(reference.views.size(), 2U);
    for (const ViewResult& view : reference.views) {
        ASSERT_TRUE(view.accuracy) << view.view;
        EXPECT_TRUE(std::isinf(view.accuracy->psnr_db)) << view.view;  // itself
    }
    EXPECT_EQ(reference.cpu_samples_ms.size(), 3U);
    EXPECT_EQ(reference.samples_ms.size(), 3U);
    EXPECT_EQ(reference.passes, reference.views[1].frame.passes);  // at the timing view

    ConfigurationResult after;
    after.configuration = options.configurations[0];
    RenderConfigurationUnit(w, context, 0, after);
    ASSERT_TRUE(after.views[0].accuracy);
    EXPECT_LT(after.views[0].accuracy->ssim, 1.0);  // fog changes the image
    EXPECT_TRUE(write_errors.empty());
    EXPECT_EQ(FramesPerConfiguration(options), 5);
}

}  // namespace
}  // namespace tidepool::runner
