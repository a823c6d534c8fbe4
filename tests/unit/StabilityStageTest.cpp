// The stability stage's refusals, which come before any GL context is made
// (pipeline/include/tidepool/pipeline/StabilityStage.h): someone else's stability.json and a
// matrix that does not load. The catalogue's runs are StabilityReportTest's and
// StabilityReportGlTest's; the whole command is CliTest's.
#include "tidepool/pipeline/StabilityStage.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "FileContents.h"
#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::ReadText;
using testing::TempDir;

TEST(StabilityStageTest, SomeoneElsesStabilityJsonIsRefusedAndKept) {
    const TempDir dir;
    const std::filesystem::path theirs = dir.Write("out/stability.json", "{\"schema\": \"mine\"}");
    StabilityOptions options;
    options.config = std::string(TIDEPOOL_SOURCE_ROOT) + "/variants.yaml";
    options.out = dir.Path() / "out";
    const StabilityResult result = RunStability(options);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_NE(Formatted(result.outcome.diagnostics).find(theirs.string()), std::string::npos)
            << Formatted(result.outcome.diagnostics);
    EXPECT_EQ(ReadText(theirs), "{\"schema\": \"mine\"}");
    EXPECT_EQ(result.json, "");
}

TEST(StabilityStageTest, AMatrixThatDoesNotLoadIsAUsageErrorAndWritesNothing) {
    const TempDir dir;
    StabilityOptions options;
    options.config = (dir.Path() / "missing.yaml").string();
    options.out = dir.Path() / "out";
    const StabilityResult result = RunStability(options);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(result.outcome.diagnostics));
    EXPECT_EQ(result.path, options.out / "stability.json");
    EXPECT_FALSE(std::filesystem::exists(result.path));
    EXPECT_TRUE(result.report.cases.empty());
}

}  // namespace
}  // namespace tidepool::pipeline
