// PreparePlans stops before it creates a GL context when the configuration or scenes are wrong,
// so those cases need no GL.
#include "tidepool/pipeline/PlanStage.h"

#include <gtest/gtest.h>

#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::SmallMatrix;

TEST(PlanStageTest, AllWithoutScenesIsAUsageErrorNamingTheConfiguration) {
    const SmallMatrix matrix;
    PlanRequest request;
    request.config = matrix.Config();
    request.all = true;
    const PreparedPlans prepared = PreparePlans(request);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(prepared.outcome.diagnostics),
              "error: no scenes/*.yaml next to " + matrix.Config() + "\n");
    EXPECT_EQ(prepared.context, nullptr);
}

TEST(PlanStageTest, AMissingSceneIsAUsageError) {
    const SmallMatrix matrix;
    PlanRequest request;
    request.config = matrix.Config();
    request.scenes = {"nowhere"};
    const PreparedPlans prepared = PreparePlans(request);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_NE(Formatted(prepared.outcome.diagnostics).find("nowhere.yaml"), std::string::npos)
            << Formatted(prepared.outcome.diagnostics);
    EXPECT_EQ(prepared.publisher, nullptr);
}

TEST(PlanStageTest, AMissingConfigurationIsAUsageError) {
    PlanRequest request;
    request.config = "/nonexistent/v.yaml";
    request.all = true;
    const PreparedPlans prepared = PreparePlans(request);
    EXPECT_EQ(prepared.outcome.status, Status::kUsage);
    EXPECT_FALSE(prepared.config.has_value());
}

}  // namespace
}  // namespace tidepool::pipeline
