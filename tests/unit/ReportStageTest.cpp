#include "tidepool/pipeline/ReportStage.h"

#include <gtest/gtest.h>

#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::TempDir;

TEST(ReportStageTest, AMissingManifestStopsAsUsageNamingItAndWritesNothing) {
    const TempDir dir;
    const std::filesystem::path manifest = dir.Path() / "manifest.json";
    const ReportResult result =
            BuildReport({manifest, dir.Path() / "results.json", "default", dir.Path() / "out"});
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(result.outcome.diagnostics).rfind("error: " + manifest.string(), 0), 0U)
            << Formatted(result.outcome.diagnostics);
    EXPECT_FALSE(result.model.has_value());
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "out"));
}

TEST(ReportStageTest, AManifestOfAnotherSchemaStopsAsUsage) {
    const TempDir dir;
    const std::filesystem::path manifest = dir.Write("manifest.json", "{\"schema\": \"other\"}");
    const std::filesystem::path results = dir.Write("results.json", "{}");
    const ReportResult result = BuildReport({manifest, results, "default", dir.Path() / "out"});
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(result.outcome.diagnostics));
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "out"));
}

}  // namespace
}  // namespace tidepool::pipeline
