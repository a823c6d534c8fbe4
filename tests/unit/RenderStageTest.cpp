// PrepareRender needs no GL: it loads the matrix and chooses configurations and views.
#include "tidepool/pipeline/RenderStage.h"

#include <gtest/gtest.h>

#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;

RenderSelection DefaultMatrix() {
    RenderSelection selection;
    selection.config = TIDEPOOL_SOURCE_ROOT "/variants.yaml";
    return selection;
}

TEST(RenderStageTest, AnUnknownViewIsAUsageErrorListingTheViews) {
    RenderSelection selection = DefaultMatrix();
    selection.views = {"sideways"};
    const PreparedRender prepared = PrepareRender(selection);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(prepared.outcome.diagnostics),
              "error: unknown view 'sideways'; the views are three_quarter, grazing, high, "
              "shore\n");
}

// It was rendered and timed twice.
TEST(RenderStageTest, AViewGivenTwiceIsAUsageError) {
    RenderSelection selection = DefaultMatrix();
    selection.views = {"high", "grazing", "high"};
    const PreparedRender prepared = PrepareRender(selection);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(prepared.outcome.diagnostics),
              "error: --view 'high' is given twice; give it once\n");
}

TEST(RenderStageTest, APresetThatMatchesNothingIsAUsageError) {
    RenderSelection selection = DefaultMatrix();
    selection.filters = {"nothing:*"};
    const PreparedRender prepared = PrepareRender(selection);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(prepared.outcome.diagnostics));
    EXPECT_FALSE(prepared.config.has_value());
}

TEST(RenderStageTest, ChosenPresetsAndViewsBecomeTheRunsOptions) {
    RenderSelection selection = DefaultMatrix();
    selection.presets = {"full"};
    selection.views = {"grazing"};
    selection.width = 32;
    selection.height = 24;
    selection.write_images = false;
    const PreparedRender prepared = PrepareRender(selection);
    ASSERT_EQ(prepared.outcome.status, Status::kOk) << Formatted(prepared.outcome.diagnostics);
    ASSERT_EQ(prepared.run.configurations.size(), 1U);
    ASSERT_EQ(prepared.run.views.size(), 1U);
    EXPECT_EQ(prepared.run.views[0].name, "grazing");
    EXPECT_EQ(prepared.run.settings.width, 32);
    EXPECT_FALSE(prepared.run.write_images);
    EXPECT_EQ(prepared.run.config_path, selection.config);
}

}  // namespace
}  // namespace tidepool::pipeline
