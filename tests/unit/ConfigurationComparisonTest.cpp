// Paired frame-time ratios, whitepaper conversions, split halves and the Pareto frontier
// (reports/include/tidepool/report/ConfigurationComparison.h).
#include "tidepool/report/ConfigurationComparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tidepool::report {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// --- ComparePaired ---------------------------------------------------------------------------

TEST(ConfigurationComparisonTest, CandidateExactlyOneAndAHalfTimesSlowerGivesRatioOnePointFive) {
    std::vector<double> a;
    std::vector<double> b;
    for (int i = 0; i < 20; ++i) {
        a.push_back(10.0 + 0.01 * i);
        b.push_back(1.5 * (10.0 + 0.01 * i));
    }
    const PairedRatio r = ComparePairs(a, b);
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_NEAR(r.ratio, 1.5, 1e-9);
    EXPECT_EQ(r.pairs, 20);
    EXPECT_LE(r.ci.low, r.ratio);
    EXPECT_GE(r.ci.high, r.ratio);
}

TEST(ConfigurationComparisonTest, TooFewPairsGiveNoRatio) {
    const PairedRatio r = ComparePairs({1, 2, 3}, {1, 2, 3});
    EXPECT_TRUE(std::isnan(r.ratio));
    EXPECT_EQ(r.pairs, 0);
    EXPECT_EQ(r.error, "fewer than 10 pairs give no interval");
}

TEST(ConfigurationComparisonTest, RoundsBecomeOnePairEachFromTheirMedians) {
    std::vector<double> a;
    std::vector<double> b;
    EXPECT_EQ(PairsFromRounds({{1, 2, 30}, {4, 5, 6}}, {{2, 2, 2}, {8}}, &a, &b), "");
    EXPECT_EQ(a, (std::vector<double>{2, 5}));
    EXPECT_EQ(b, (std::vector<double>{2, 8}));
    EXPECT_EQ(PairsFromRounds({{1}}, {{1}, {2}}, &a, &b),
              "the baseline has 1 rounds and the candidate 2");
    EXPECT_EQ(PairsFromRounds({{1}, {}}, {{1}, {2}}, &a, &b), "round 2 has no samples");
}

struct WhitepaperFigure {
    double percent;
    double frame_time_ratio;
};

TEST(ConfigurationComparisonTest, WhitepaperFiguresRoundTripThroughFrameTimeRatios) {
    const WhitepaperFigure table[] = {
            {-60, 2.5},   // "performance reduced by 60%"
            {-50, 2.0},   // halved frame rate: twice the frame time
            {-20, 1.25},  // "reduced by 20%"
            {0, 1.0},     // no change
            {25, 0.8},    // "increased by 25%"
            {100, 0.5},   // doubled frame rate
    };
    for (const WhitepaperFigure& figure : table) {
        SCOPED_TRACE(figure.percent);
        EXPECT_NEAR(FrameTimeRatioFromPerformanceChange(figure.percent), figure.frame_time_ratio,
                    1e-12);
        EXPECT_NEAR(PerformanceChangePercent(figure.frame_time_ratio), figure.percent, 1e-12);
        EXPECT_NEAR(PerformanceChangePercent(FrameTimeRatioFromPerformanceChange(figure.percent)),
                    figure.percent, 1e-12);
    }
}

TEST(ConfigurationComparisonTest, FrameRateAtFortyPercentIsSixtyPercentReduction) {
    EXPECT_NEAR(PerformanceChangePercent(1 / 0.4), -60, 1e-12);
}

TEST(ConfigurationComparisonTest, InvalidRatiosAndPercentagesConvertToNaN) {
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(0)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(-1)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(kInfinity)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(kNaN)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(-100)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(-150)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(kNaN)));
}

// --- Split-half reliability ------------------------------------------------------------------

TEST(ConfigurationComparisonTest, IdenticalHalvesDisagreeByZeroPoints) {
    std::vector<double> a(40, 10.0);
    std::vector<double> b;
    for (int i = 0; i < 40; ++i) {
        b.push_back(12.0 * (1.0 + 0.001 * (i / 2 % 5)));
    }
    const SplitHalf split = CompareSplitPairs(a, b);
    ASSERT_TRUE(split.odd.error.empty() && split.even.error.empty());
    EXPECT_EQ(split.odd.pairs, 20);
    EXPECT_EQ(split.even.pairs, 20);
    EXPECT_NEAR(split.disagreement_percent_points, 0.0, 1e-9);
}

TEST(ConfigurationComparisonTest, SplitHalvesSeparateWhoRenderedFirst) {
    // Even pairs (baseline first) 20% slower, odd pairs (candidate first) 25% slower.
    std::vector<double> a(40, 10.0);
    std::vector<double> b;
    for (int i = 0; i < 40; ++i) {
        b.push_back(i % 2 == 0 ? 12.0 : 12.5);
    }
    const SplitHalf split = CompareSplitPairs(a, b);
    EXPECT_NEAR(PerformanceChangePercent(split.even.ratio), (1 / 1.2 - 1) * 100, 1e-9);
    EXPECT_NEAR(PerformanceChangePercent(split.odd.ratio), (1 / 1.25 - 1) * 100, 1e-9);
    EXPECT_NEAR(split.disagreement_percent_points, (1 / 1.2 - 1 / 1.25) * 100, 1e-9);
}

TEST(ConfigurationComparisonTest, SplitHalfOfTooFewPairsFails) {
    const SplitHalf split =
            CompareSplitPairs(std::vector<double>(12, 1.0), std::vector<double>(12, 2.0));
    EXPECT_TRUE(std::isnan(split.disagreement_percent_points));
    EXPECT_FALSE(split.odd.error.empty());
}

// --- Pareto frontier -------------------------------------------------------------------------

TEST(ConfigurationComparisonTest, ParetoFrontierKeepsUndominatedPointsSortedByTime) {
    //                                 0    1    2    3    4    5    6
    const std::vector<double> time = {4.0, 1.0, 3.0, 2.0, 5.0, 2.0, 6.0};
    const std::vector<double> error = {1.0, 5.0, 4.0, 3.0, 1.0, 3.0, 0.5};
    // 2 is beaten by 3 in both; 4 ties 0 on error but is slower; 3 and 5 are the same point.
    const std::vector<std::size_t> expected = {1, 3, 5, 0, 6};
    EXPECT_EQ(ParetoFrontier(time, error), expected);
}

TEST(ConfigurationComparisonTest, ParetoFrontierSkipsPointsWithNaN) {
    const std::vector<double> time = {1.0, kNaN, 0.5};
    const std::vector<double> error = {1.0, 0.0, kNaN};
    const std::vector<std::size_t> expected = {0};
    EXPECT_EQ(ParetoFrontier(time, error), expected);
}

TEST(ConfigurationComparisonTest, ParetoFrontierOfMismatchedOrEmptyInputIsEmpty) {
    EXPECT_TRUE(ParetoFrontier({1.0, 2.0}, {1.0}).empty());
    EXPECT_TRUE(ParetoFrontier({}, {}).empty());
}

}  // namespace
}  // namespace tidepool::report
