// Paired frame-time ratios, whitepaper conversions and verdicts, ranks and the Pareto frontier.
#include "tidepool/report/Statistics.h"

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

// --- Median and Quantile ---------------------------------------------------------------------

TEST(ReportStatisticsTest, MedianOfOddCountIsTheMiddleValue) {
    EXPECT_DOUBLE_EQ(Median({5, 1, 4, 2, 3}), 3);
}

TEST(ReportStatisticsTest, MedianOfEvenCountIsTheMeanOfTheMiddleTwo) {
    EXPECT_DOUBLE_EQ(Median({1, 10, 3, 2}), 2.5);
}

TEST(ReportStatisticsTest, MedianOfEmptyOrNaNSamplesIsNaN) {
    EXPECT_TRUE(std::isnan(Median({})));
    EXPECT_TRUE(std::isnan(Median({1, kNaN, 2})));
}

TEST(ReportStatisticsTest, QuantileInterpolatesBetweenOrderStatisticsAsType7) {
    const std::vector<double> sorted = {1, 2, 3, 10};
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0), 1);
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.25), 1.75);  // position 0.75 between 1 and 2
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.5), 2.5);
    EXPECT_DOUBLE_EQ(Quantile(sorted, 0.75), 4.75);  // position 2.25 between 3 and 10
    EXPECT_DOUBLE_EQ(Quantile(sorted, 1), 10);
}

TEST(ReportStatisticsTest, QuantileOfEmptySamplesOrOutOfRangeLevelIsNaN) {
    EXPECT_TRUE(std::isnan(Quantile({}, 0.5)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, -0.1)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, 1.1)));
    EXPECT_TRUE(std::isnan(Quantile({1, 2}, kNaN)));
}

// --- ComparePaired ---------------------------------------------------------------------------

TEST(ReportStatisticsTest, CandidateExactlyOneAndAHalfTimesSlowerGivesRatioOnePointFive) {
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

TEST(ReportStatisticsTest, TooFewPairsGiveNoRatio) {
    const PairedRatio r = ComparePairs({1, 2, 3}, {1, 2, 3});
    EXPECT_TRUE(std::isnan(r.ratio));
    EXPECT_EQ(r.pairs, 0);
    EXPECT_EQ(r.error, "fewer than 10 pairs give no interval");
}

TEST(ReportStatisticsTest, RoundsBecomeOnePairEachFromTheirMedians) {
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

TEST(ReportStatisticsTest, WhitepaperFiguresRoundTripThroughFrameTimeRatios) {
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

TEST(ReportStatisticsTest, FrameRateAtFortyPercentIsSixtyPercentReduction) {
    EXPECT_NEAR(PerformanceChangePercent(1 / 0.4), -60, 1e-12);
}

TEST(ReportStatisticsTest, InvalidRatiosAndPercentagesConvertToNaN) {
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(0)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(-1)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(kInfinity)));
    EXPECT_TRUE(std::isnan(PerformanceChangePercent(kNaN)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(-100)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(-150)));
    EXPECT_TRUE(std::isnan(FrameTimeRatioFromPerformanceChange(kNaN)));
}

// --- Split-half reliability ------------------------------------------------------------------

TEST(ReportStatisticsTest, IdenticalHalvesDisagreeByZeroPoints) {
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

TEST(ReportStatisticsTest, SplitHalvesSeparateWhoRenderedFirst) {
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

TEST(ReportStatisticsTest, SplitHalfOfTooFewPairsFails) {
    const SplitHalf split =
            CompareSplitPairs(std::vector<double>(12, 1.0), std::vector<double>(12, 2.0));
    EXPECT_TRUE(std::isnan(split.disagreement_percent_points));
    EXPECT_FALSE(split.odd.error.empty());
}

TEST(ReportStatisticsTest, SpearmanOfAnyIncreasingRelationIsOne) {
    EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {1, 8, 27, 64, 125}), 1.0);
}

TEST(ReportStatisticsTest, SpearmanOfAReversedOrderIsMinusOne) {
    EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {50, 40, 30, 20, 10}), -1.0);
}

TEST(ReportStatisticsTest, SpearmanGivesTiesTheirAverageRank) {
    // x ranks 1, 2.5, 2.5, 4, 5; y ranks 1, 3, 2, 5, 4. Around the mean rank 3 the sums are
    // sum dx dy = 8.5, sum dx^2 = 9.5, sum dy^2 = 10, so rho = 8.5 / sqrt(95) = 0.872082...
    // (scipy.stats.spearmanr gives the same).
    EXPECT_NEAR(SpearmanRho({10, 20, 20, 30, 40}, {1, 3, 2, 5, 4}), 8.5 / std::sqrt(95.0), 1e-12);
}

TEST(ReportStatisticsTest, SpearmanOfTextbookMarksMatchesTheClassicFormula) {
    // Laerd Statistics' worked example (English and maths marks of ten students, no ties):
    // sum d^2 = 54, so rho = 1 - 6 * 54 / (10 * (10^2 - 1)) = 0.6727...
    const std::vector<double> english = {56, 75, 45, 71, 62, 64, 58, 80, 76, 61};
    const std::vector<double> maths = {66, 70, 40, 60, 65, 56, 59, 77, 67, 63};
    EXPECT_NEAR(SpearmanRho(english, maths), 1.0 - 6.0 * 54.0 / (10.0 * 99.0), 1e-12);
}

TEST(ReportStatisticsTest, SpearmanWithTiesOnBothSidesIsThePearsonCorrelationOfAverageRanks) {
    // x ranks 1, 3, 3, 3, 5; y ranks 1.5, 1.5, 3, 4.5, 4.5. Around 3: sum dx dy = 6,
    // sum dx^2 = 8, sum dy^2 = 9, so rho = 6 / sqrt(72) = 0.707107... (scipy agrees), where the
    // no-ties shortcut 1 - 6 sum d^2 / (n (n^2 - 1)) would give 0.75.
    EXPECT_NEAR(SpearmanRho({1, 2, 2, 2, 3}, {1, 1, 2, 3, 3}), 6.0 / std::sqrt(72.0), 1e-12);
}

TEST(ReportStatisticsTest, SpearmanFailsOnMismatchedConstantOrTooShortInput) {
    EXPECT_TRUE(std::isnan(SpearmanRho({1, 2, 3}, {1, 2})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1, 2, 3}, {4, 4, 4})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1}, {1})));
    EXPECT_TRUE(std::isnan(SpearmanRho({1, kNaN, 3}, {1, 2, 3})));
}

// --- Pareto frontier -------------------------------------------------------------------------

TEST(ReportStatisticsTest, ParetoFrontierKeepsUndominatedPointsSortedByTime) {
    //                                 0    1    2    3    4    5    6
    const std::vector<double> time = {4.0, 1.0, 3.0, 2.0, 5.0, 2.0, 6.0};
    const std::vector<double> error = {1.0, 5.0, 4.0, 3.0, 1.0, 3.0, 0.5};
    // 2 is beaten by 3 in both; 4 ties 0 on error but is slower; 3 and 5 are the same point.
    const std::vector<std::size_t> expected = {1, 3, 5, 0, 6};
    EXPECT_EQ(ParetoFrontier(time, error), expected);
}

TEST(ReportStatisticsTest, ParetoFrontierSkipsPointsWithNaN) {
    const std::vector<double> time = {1.0, kNaN, 0.5};
    const std::vector<double> error = {1.0, 0.0, kNaN};
    const std::vector<std::size_t> expected = {0};
    EXPECT_EQ(ParetoFrontier(time, error), expected);
}

TEST(ReportStatisticsTest, ParetoFrontierOfMismatchedOrEmptyInputIsEmpty) {
    EXPECT_TRUE(ParetoFrontier({1.0, 2.0}, {1.0}).empty());
    EXPECT_TRUE(ParetoFrontier({}, {}).empty());
}

}  // namespace
}  // namespace tidepool::report
