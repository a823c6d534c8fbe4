#include "tidepool/pipeline/MatrixLoading.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::SmallMatrix;

TEST(MatrixLoadingTest, WholeNumbersAreDigitsWithinTheRangeOnly) {
    struct Case {
        const char* text;
        bool accepted;
        std::uint64_t value;
    };
    const Case cases[] = {{"1", true, 1},    {"65536", true, 65536},
                          {"0", false, 0},   {"65537", false, 0},
                          {"-1", false, 0},  {"+5", false, 0},
                          {"1e3", false, 0}, {"2.0", false, 0},
                          {"", false, 0},    {"18446744073709551616", false, 0}};
    for (const Case& c : cases) {
        std::uint64_t value = 0;
        EXPECT_EQ(ParseWholeNumber(c.text, 1, 65536, &value), c.accepted) << c.text;
        EXPECT_EQ(value, c.value) << c.text;
    }
}

TEST(MatrixLoadingTest, WholeNumberErrorNamesTheFlagTheRangeAndTheHint) {
    EXPECT_EQ(WholeNumberError("--pruned-limit", "x", 1, 10, ""),
              "--pruned-limit must be a whole number from 1 to 10, not 'x'");
    EXPECT_EQ(WholeNumberError("--max-variants", "0", 1, 10, "(hint)"),
              "--max-variants must be a whole number from 1 to 10 (hint), not '0'");
}

TEST(MatrixLoadingTest, LoadsAndExpandsEveryProgram) {
    const SmallMatrix matrix;
    const LoadedMatrix loaded = LoadMatrix(matrix.Config());
    ASSERT_TRUE(loaded.config.has_value()) << Formatted(loaded.outcome.diagnostics);
    EXPECT_EQ(loaded.outcome.status, Status::kOk);
    EXPECT_EQ(loaded.expansion.variants.size(), 5U);  // p: 4 subsets of {A, B}; q: 1
}

TEST(MatrixLoadingTest, MaxVariantsOutOfRangeStopsBeforeReadingTheFile) {
    MatrixLimits limits;
    limits.max_variants = "0";
    const LoadedMatrix loaded = LoadMatrix("/nonexistent/v.yaml", limits);
    EXPECT_FALSE(loaded.config.has_value());
    EXPECT_EQ(loaded.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(loaded.outcome.diagnostics),
              "error: --max-variants must be a whole number from 1 to 65536 (up to 16777216 with "
              "--allow-large-matrix), not '0'\n");
}

TEST(MatrixLoadingTest, TooManyValidVariantsIsAUsageError) {
    const SmallMatrix matrix;
    MatrixLimits limits;
    limits.max_variants = "2";
    const LoadedMatrix loaded = LoadMatrix(matrix.Config(), limits);
    EXPECT_FALSE(loaded.config.has_value());
    EXPECT_EQ(loaded.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(loaded.outcome.diagnostics));
}

TEST(MatrixLoadingTest, AMissingFileIsAUsageErrorNamingIt) {
    const LoadedMatrix loaded = LoadMatrix("/nonexistent/v.yaml");
    EXPECT_FALSE(loaded.config.has_value());
    EXPECT_EQ(loaded.outcome.status, Status::kUsage);
    EXPECT_NE(Formatted(loaded.outcome.diagnostics).find("/nonexistent/v.yaml"), std::string::npos);
}

// The small matrix loaded, then narrowed to `program`.
LoadedMatrix LoadOnly(const SmallMatrix& matrix, const std::string& program) {
    LoadedMatrix loaded = LoadMatrix(matrix.Config());
    EXPECT_TRUE(loaded.config.has_value()) << Formatted(loaded.outcome.diagnostics);
    if (loaded.config) {
        KeepOnlyProgram(&loaded, program);
    }
    return loaded;
}

TEST(MatrixLoadingTest, KeepOnlyProgramNarrowsVariantsAndPrograms) {
    const SmallMatrix matrix;
    const LoadedMatrix loaded = LoadOnly(matrix, "q");
    ASSERT_TRUE(loaded.config.has_value());
    EXPECT_EQ(loaded.outcome.status, Status::kOk);
    ASSERT_EQ(loaded.config->programs.size(), 1U);
    EXPECT_EQ(loaded.config->programs[0].name, "q");
    ASSERT_EQ(loaded.expansion.variants.size(), 1U);
    EXPECT_EQ(loaded.expansion.variants[0].program, "q");
}

TEST(MatrixLoadingTest, KeepOnlyAnUnknownProgramNamesThePrograms) {
    const SmallMatrix matrix;
    const LoadedMatrix loaded = LoadOnly(matrix, "r");
    EXPECT_FALSE(loaded.config.has_value());
    EXPECT_EQ(loaded.outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(loaded.outcome.diagnostics),
              "error: --program r: " + matrix.Config() + " has no such program; it has p, q\n");
}

}  // namespace
}  // namespace tidepool::pipeline
