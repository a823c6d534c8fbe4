#include "tidepool/pipeline/CompilerStages.h"

#include <gtest/gtest.h>

#include <fstream>

#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::SmallMatrix;

TEST(CompilerStagesTest, ExpandWithoutOutWritesNothingAndBuildsTheManifest) {
    const SmallMatrix matrix;
    ExpandOptions options;
    options.config = matrix.Config();
    const ExpandResult result = Expand(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kOk)
            << Formatted(result.matrix.outcome.diagnostics);
    EXPECT_EQ(result.manifest["variants"].size(), 5U);
    EXPECT_FALSE(std::filesystem::exists(matrix.Dir().Path() / "out"));
}

TEST(CompilerStagesTest, ExpandPublishesSourcesManifestAndDepfile) {
    const SmallMatrix matrix;
    ExpandOptions options;
    options.config = matrix.Config();
    options.program = "q";
    options.out = (matrix.Dir().Path() / "out").string();
    options.depfile = (matrix.Dir().Path() / "out.d").string();
    const ExpandResult result = Expand(options);
    ASSERT_EQ(result.matrix.outcome.status, Status::kOk)
            << Formatted(result.matrix.outcome.diagnostics);
    EXPECT_TRUE(std::filesystem::is_regular_file(matrix.Dir().Path() / "out" / "manifest.json"));
    EXPECT_TRUE(std::filesystem::is_directory(matrix.Dir().Path() / "out" / "100" / "q"));
    EXPECT_FALSE(std::filesystem::exists(matrix.Dir().Path() / "out" / "100" / "p"));
    EXPECT_TRUE(std::filesystem::is_regular_file(matrix.Dir().Path() / "out.d"));
}

TEST(CompilerStagesTest, ValidateMatrixOfValidShadersIsOkAndWritesTheManifest) {
    const SmallMatrix matrix;
    ValidateOptions options;
    options.config = matrix.Config();
    options.jobs = 1;
    options.cache.off = true;
    options.out = (matrix.Dir().Path() / "m").string();
    const ValidateResult result = ValidateMatrix(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kOk)
            << Formatted(result.matrix.outcome.diagnostics);
    EXPECT_EQ(result.report.InvalidCount(), 0);
    EXPECT_EQ(result.manifest["variants"].size(), 5U);
    EXPECT_TRUE(std::filesystem::is_regular_file(matrix.Dir().Path() / "m" / "manifest.json"));
}

TEST(CompilerStagesTest, ValidateMatrixWithAnErrorIsInvalidWithTheDiagnostic) {
    const SmallMatrix matrix;
    matrix.BreakFeatureB();
    ValidateOptions options;
    options.config = matrix.Config();
    options.jobs = 1;
    options.cache.off = true;
    const ValidateResult result = ValidateMatrix(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kInvalid);
    EXPECT_EQ(result.report.InvalidCount(), 2);  // p:B and p:A,B
    EXPECT_NE(Formatted(result.matrix.outcome.diagnostics).find("s.fsh:5:"), std::string::npos)
            << Formatted(result.matrix.outcome.diagnostics);
    EXPECT_TRUE(result.manifest.is_null());  // neither written nor wanted
}

TEST(CompilerStagesTest, ValidateMatrixRefusesAForeignManifestBeforeValidating) {
    const SmallMatrix matrix;
    matrix.Dir().Write("m/manifest.json", "{}");
    ValidateOptions options;
    options.config = matrix.Config();
    options.out = (matrix.Dir().Path() / "m").string();
    const ValidateResult result = ValidateMatrix(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kUsage);
    EXPECT_TRUE(result.report.verdicts.empty());
}

TEST(CompilerStagesTest, ValidateFilesNeedsAStageItCanTell) {
    const SmallMatrix matrix;
    const std::filesystem::path file = matrix.Dir().Write("shader.txt", "void main() {}\n");
    ValidateFilesOptions options;
    options.files = {file.string()};
    const ValidateFilesResult result = ValidateFiles(options);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(result.outcome.diagnostics),
              file.string() +
                      ": error: cannot tell the stage from the extension; use .vert/.vsh, "
                      ".frag/.fsh or --stage vert|frag\n");
}

TEST(CompilerStagesTest, ValidateFilesLinksAVertexAndAFragmentFile) {
    const SmallMatrix matrix;
    ValidateFilesOptions options;
    options.files = {(matrix.Dir().Path() / "s.vsh").string(),
                     (matrix.Dir().Path() / "s.fsh").string()};
    options.cache.off = true;
    const ValidateFilesResult result = ValidateFiles(options);
    EXPECT_EQ(result.outcome.status, Status::kOk) << Formatted(result.outcome.diagnostics);
    EXPECT_EQ(result.report.verdicts.size(), 1U);
}

TEST(CompilerStagesTest, StaticCostsHaveOneRowPerValidVariant) {
    const SmallMatrix matrix;
    StatsOptions options;
    options.config = matrix.Config();
    options.jobs = 1;
    const StatsResult result = MeasureStaticCosts(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kOk)
            << Formatted(result.matrix.outcome.diagnostics);
    ASSERT_EQ(result.costs.size(), 5U);
    for (std::size_t i = 0; i < result.costs.size(); ++i) {
        EXPECT_EQ(result.costs[i].id, result.matrix.expansion.variants[i].Id());
    }
}

TEST(CompilerStagesTest, StaticCostsLeaveOutInvalidVariantsAndSayWhy) {
    const SmallMatrix matrix;
    matrix.BreakFeatureB();
    StatsOptions options;
    options.config = matrix.Config();
    options.jobs = 1;
    const StatsResult result = MeasureStaticCosts(options);
    EXPECT_EQ(result.matrix.outcome.status, Status::kInvalid);
    EXPECT_EQ(result.costs.size(), 3U);  // p:B and p:A,B do not compile
    EXPECT_NE(Formatted(result.matrix.outcome.diagnostics).find("s.fsh:5:"), std::string::npos)
            << Formatted(result.matrix.outcome.diagnostics);
}

}  // namespace
}  // namespace tidepool::pipeline
