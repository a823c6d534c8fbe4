// PreparePlans stops before it creates a GL context when the configuration or scenes are wrong,
// so those cases need no GL.
#include "tidepool/pipeline/PlanStage.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

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

// "../variants" read the configuration as a scene; a scene twice wrote its images twice.
TEST(PlanStageTest, ASceneIsNamedOnceByItsFileNameInScenes) {
    const SmallMatrix matrix;
    struct Case {
        std::vector<std::string> scenes;
        const char* error;
    };
    for (const Case& c :
         {Case{{"../v"},
               "error: --scene '../v': a scene is named by its file in scenes/ without "
               "'.yaml'\n"},
          Case{{".hidden"},
               "error: --scene '.hidden': a scene is named by its file in scenes/ "
               "without '.yaml'\n"},
          Case{{"open_sea.yaml"},
               "error: --scene 'open_sea.yaml': name it without '.yaml': --scene open_sea\n"},
          Case{{"open_sea", "open_sea"},
               "error: --scene 'open_sea': it is given twice; give it once\n"}}) {
        PlanRequest request;
        request.config = matrix.Config();
        request.scenes = c.scenes;
        const PreparedPlans prepared = PreparePlans(request);
        EXPECT_EQ(prepared.outcome.status, Status::kUsage) << c.error;
        EXPECT_EQ(Formatted(prepared.outcome.diagnostics), c.error);
        EXPECT_EQ(prepared.publisher, nullptr);
    }
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
