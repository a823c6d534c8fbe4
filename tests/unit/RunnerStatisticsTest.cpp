// Order statistics of frame times: median, quartiles and the binomial CI of the median.
#include "tidepool/runner/Statistics.h"

#include <gtest/gtest.h>

namespace tidepool::runner {
namespace {

TEST(RunnerStatisticsTest, MedianAndQuartilesOfKnownSamples) {
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

TEST(RunnerStatisticsTest, EvenCountInterpolatesTheMedian) {
    const SampleStatistics s = ComputeSampleStatistics({1, 2, 3, 10});
    EXPECT_DOUBLE_EQ(s.median, 2.5);
    EXPECT_DOUBLE_EQ(s.q1, 1.75);  // position 0.75 between 1 and 2
    EXPECT_DOUBLE_EQ(s.q3, 4.75);  // position 2.25 between 3 and 10
}

// For n = 10 the 95% interval is [x(2), x(9)]: 1 - 2 P(B <= 1) = 1 - 2 * 11/1024 = 0.978516,
// while j = 3 would cover only 1 - 2 * 56/1024 = 0.890625.
TEST(RunnerStatisticsTest, MedianIntervalOfTenSamplesUsesSecondAndNinthOrderStatistic) {
    const SampleStatistics s = ComputeSampleStatistics({10, 9, 8, 7, 6, 5, 4, 3, 2, 1});
    EXPECT_DOUBLE_EQ(s.ci_low, 2);
    EXPECT_DOUBLE_EQ(s.ci_high, 9);
    EXPECT_NEAR(s.ci_coverage, 1.0 - 2.0 * 11.0 / 1024.0, 1e-9);
}

// n = 30 (the render defaults give 3 rounds x 3 frames = 9; bench 10 x 5 = 50): the textbook
// 95% interval for n = 30 is [x(10), x(21)] with coverage 0.9572.
TEST(RunnerStatisticsTest, MedianIntervalOfThirtySamplesMatchesTables) {
    std::vector<double> samples;
    for (int i = 1; i <= 30; ++i) {
        samples.push_back(i);
    }
    const SampleStatistics s = ComputeSampleStatistics(samples);
    EXPECT_DOUBLE_EQ(s.ci_low, 10);
    EXPECT_DOUBLE_EQ(s.ci_high, 21);
    EXPECT_NEAR(s.ci_coverage, 0.9572, 1e-4);
}

TEST(RunnerStatisticsTest, TooFewSamplesGiveTheRangeWithItsTrueCoverage) {
    const SampleStatistics s = ComputeSampleStatistics({3, 1, 2});
    EXPECT_DOUBLE_EQ(s.ci_low, 1);
    EXPECT_DOUBLE_EQ(s.ci_high, 3);
    EXPECT_DOUBLE_EQ(s.ci_coverage, 0.75);  // 1 - 2 * (1/2)^3
}

TEST(RunnerStatisticsTest, EmptySamplesGiveZeroCount) {
    EXPECT_EQ(ComputeSampleStatistics({}).count, 0);
}

}  // namespace
}  // namespace tidepool::runner
