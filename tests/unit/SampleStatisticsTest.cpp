// Median, Quantile, the summary of frame times with its median interval, and Spearman's rank
// correlation (base/include/tidepool/base/SampleStatistics.h).
#include "tidepool/base/SampleStatistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace tidepool::base {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// --- Median and Quantile ---------------------------------------------------------------------

TEST(SampleStatisticsTest, MedianOfOddCountIsTheMiddleValue) {
    EXPECT_DOUBLE_EQ(Median({5, 1, 4, 2, 3}), 3);
}

TEST(SampleStatisticsTest, MedianOfEvenCountIsTheMeanOfTheMiddleTwo) {
    EXPECT_DOUBLE_EQ(Median({1, 10, 3, 2}), 2.5);
}

TEST(SampleStatisticsTest, MedianOfEmptyOrNaNSamplesIsNaN) {
    EXPECT_TRUE(std::isnan(Median({})));
    EXPECT_TRUE(std::isnan(Median({1, kNaN, 2})));
}

TEST(SampleStatisticsTest, QuantileInterpolatesBetweenOrderStatisticsAsType7) {
    const std::vector<double> sorted = {1, 2, 3, 10};
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0), 1);
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.25), 1.75);  // position 0.75 between 1 and 2
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.5), 2.5);
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.75), 4.75);  // position 2.25 between 3 and 10
    EXPECT_DOUBLE_EQ(Quantile(sorted, 1), 10);
}

TEST(SampleStatisticsTest, QuantileOfEmptySamplesOrOutOfRangeLevelIsNaN) {
    EXPECT_TRUE(std::isnan(Quantile({}, 0.5)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, -0.1)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, 1.1)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, kNaN)));
}

TEST(SampleStatisticsTest, EmptyInputFailsTheSameWayEverywhere) {
    EXPECT_TRUE(std::isnan(Median({})));
    EXPECT_TRUE(std::isnan(Quantile({}, 0.5)));
    EXPECT_TRUE(std::isnan(StandardDeviation({})));
    EXPECT_TRUE(std::isnan(SpearmanRho({}, {})));
    EXPECT_EQ(ComputeSampleStatistics({}).count, 0);
}

// --- StandardDeviation ------------------------------------------------------------------------

TEST(SampleStatisticsTest, StandardDeviationDividesByOneLessThanTheCount) {
    // Mean 5, squared deviations 9 + 1 + 1 + 9 = 20, over n - 1 = 3.
    EXPECT_DOUBLE_EQ(StandardDeviation({2, 4, 6, 8}), std::sqrt(20.0 / 3.0));
    EXPECT_DOUBLE_EQ(StandardDeviation({7, 7, 7}), 0.0);
}

TEST(SampleStatisticsTest, StandardDeviationOfFewerThanTwoSamplesIsNaN) {
    EXPECT_TRUE(std::isnan(StandardDeviation({3})));
}

// --- ComputeSampleStatistics -----------------------------------------------------------------

TEST(SampleStatisticsTest, MedianAndQuartilesOfKnownSamples) {
    const SampleStatistics s = ComputeSampleStatistics({5, 1, 4, 2, 3});
    EXPECT_EQ(s.count, 5);
    EXPECT_DOUBLE_EQ(s.median, 3);
    EXPECT_DOUBLE_EQ(s.q1, 2);  // type 7: position 0.25 * 4 = 1
    EXPECT_DOUBLE_EQ(s.q3, 4);
    EXPECT_DOUBLE_EQ(s.iqr, 2);
    EXPECT_DOUBLE_EQ(s.min, 1);
    EXPECT_DOUBLE_EQ(s.max, 5);
    EXPECT_DOUBLE_EQ(s.mean, 3);
}

TEST(SampleStatisticsTest, EvenCountInterpolatesTheMedian) {
    const SampleStatistics s = ComputeSampleStatistics({1, 2, 3, 10});
    EXPECT_DOUBLE_EQ(s.median, 2.5);
    EXPECT_DOUBLE_EQ(s.q1, 1.75);  // position 0.75 between 1 and 2
    EXPECT_DOUBLE_EQ(s.q3, 4.75);  // position 2.25 between 3 and 10
}

// For n = 10 the 95% interval is [x(2), x(9)]: 1 - 2 P(B <= 1) = 1 - 2 * 11/1024 = 0.978516,
// while j = 3 would cover only 1 - 2 * 56/1024 = 0.890625.
TEST(SampleStatisticsTest, MedianIntervalOfTenSamplesUsesSecondAndNinthOrderStatistic) {
    const SampleStatistics s = ComputeSampleStatistics({10, 9, 8, 7, 6, 5, 4, 3, 2, 1});
    EXPECT_DOUBLE_EQ(s.ci_low, 2);
    EXPECT_DOUBLE_EQ(s.ci_high, 9);
    EXPECT_NEAR(s.ci_coverage, 1.0 - 2.0 * 11.0 / 1024.0, 1e-9);
}

// n = 30 (the render defaults give 3 rounds x 3 frames = 9; bench 10 x 5 = 50): the textbook
// 95% interval for n = 30 is [x(10), x(21)] with coverage 0.9572.
TEST(SampleStatisticsTest, MedianIntervalOfThirtySamplesMatchesTables) {
    std::vector<double> samples;
    for (int i = 1; i <= 30; ++i) {
        samples.push_back(i);
    }
    const SampleStatistics s = ComputeSampleStatistics(samples);
    EXPECT_DOUBLE_EQ(s.ci_low, 10);
    EXPECT_DOUBLE_EQ(s.ci_high, 21);
    EXPECT_NEAR(s.ci_coverage, 0.9572, 1e-4);
}

TEST(SampleStatisticsTest, TooFewSamplesGiveTheRangeWithItsTrueCoverage) {
    const SampleStatistics s = ComputeSampleStatistics({3, 1, 2});
    EXPECT_DOUBLE_EQ(s.ci_low, 1);
    EXPECT_DOUBLE_EQ(s.ci_high, 3);
    EXPECT_DOUBLE_EQ(s.ci_coverage, 0.75);  // 1 - 2 * (1/2)^3
}

TEST(SampleStatisticsTest, EmptySamplesGiveZeroCount) {
    EXPECT_EQ(ComputeSampleStatistics({}).count, 0);
}

// --- AverageRanks and SpearmanRho -------------------------------------------------------------

TEST(SampleStatisticsTest, AverageRanksGiveTiesTheMeanOfTheirPositions) {
    EXPECT_EQ(AverageRanks({30, 10, 20, 20}), (std::vector<double>{4, 1, 2.5, 2.5}));
    EXPECT_EQ(AverageRanks({5, 5, 5}), (std::vector<double>{2, 2, 2}));
    EXPECT_TRUE(AverageRanks({}).empty());
}

TEST(SampleStatisticsTest, SpearmanOfAnyIncreasingRelationIsOne) {
    EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {1, 8, 27, 64, 125}), 1.0);
}

TEST(SampleStatisticsTest, SpearmanOfAReversedOrderIsMinusOne) {
    EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {50, 40, 30, 20, 10}), -1.0);
}

TEST(SampleStatisticsTest, SpearmanGivesTiesTheirAverageRank) {
    // x ranks 1, 2.5, 2.5, 4, 5; y ranks 1, 3, 2, 5, 4. Around the mean rank 3 the sums are
    // sum dx dy = 8.5, sum dx^2 = 9.5, sum dy^2 = 10, so rho = 8.5 / sqrt(95) = 0.872082...
    // (scipy.stats.spearmanr gives the same).
    EXPECT_NEAR(SpearmanRho({10, 20, 20, 30, 40}, {1, 3, 2, 5, 4}), 8.5 / std::sqrt(95.0), 1e-12);
}

TEST(SampleStatisticsTest, SpearmanOfTextbookMarksMatchesTheClassicFormula) {
    // Laerd Statistics' worked example (English and maths marks of ten students, no ties):
    // sum d^2 = 54, so rho = 1 - 6 * 54 / (10 * (10^2 - 1)) = 0.6727...
    const std::vector<double> english = {56, 75, 45, 71, 62, 64, 58, 80, 76, 61};
    const std::vector<double> maths = {66, 70, 40, 60, 65, 56, 59, 77, 67, 63};
    EXPECT_NEAR(SpearmanRho(english, maths), 1.0 - 6.0 * 54.0 / (10.0 * 99.0), 1e-12);
}

TEST(SampleStatisticsTest, SpearmanWithTiesOnBothSidesIsThePearsonCorrelationOfAverageRanks) {
    // x ranks 1, 3, 3, 3, 5; y ranks 1.5, 1.5, 3, 4.5, 4.5. Around 3: sum dx dy = 6,
    // sum dx^2 = 8, sum dy^2 = 9, so rho = 6 / sqrt(72) = 0.707107... (scipy agrees), where the
    // no-ties shortcut 1 - 6 sum d^2 / (n (n^2 - 1)) would give 0.75.
    EXPECT_NEAR(SpearmanRho({1, 2, 2, 2, 3}, {1, 1, 2, 3, 3}), 6.0 / std::sqrt(72.0), 1e-12);
}

TEST(SampleStatisticsTest, SpearmanFailsOnMismatchedConstantOrTooShortInput) {
    EXPECT_TRUE(std::isnan(SpearmanRho({1, 2, 3}, {1, 2})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1, 2, 3}, {4, 4, 4})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1}, {1})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1, kNaN, 3}, {1, 2, 3})));
}

}  // namespace
}  // namespace tidepool::base
