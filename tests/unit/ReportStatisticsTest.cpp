// Paired frame-time ratios, whitepaper conversions and verdicts, ranks and the Pareto frontier.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "tidepool/report/Statistics.h"

namespace tidepool::report {
namespace {

using Rounds = std::vector<std::vector<double>>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A uniform double in [0, 1) from the engine's raw output (53 bits), so the test data is the
// same on every standard library.
double Uniform(std::mt19937_64& engine) {
    return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

// `rounds` rounds of `frames` frame times around `centre` seconds, each round scaled by a
// drift factor (as thermal state or other load would) and each frame jittered by up to +-5%.
Rounds NoisyRounds(double centre, int rounds, int frames, std::mt19937_64& engine) {
    Rounds result;
    for (int r = 0; r < rounds; ++r) {
        const double drift = 1.0 + 0.2 * Uniform(engine);
        std::vector<double> round;
        round.reserve(static_cast<std::size_t>(frames));
        for (int f = 0; f < frames; ++f) {
            round.push_back(centre * drift * (0.95 + 0.1 * Uniform(engine)));
        }
        result.push_back(round);
    }
    return result;
}

Rounds Scaled(const Rounds& rounds, double factor) {
    Rounds result = rounds;
    for (auto& round : result) {
        for (double& sample : round) {
            sample *= factor;
        }
    }
    return result;
}

PairedRatio Measured(double ratio, double low, double high) {
    PairedRatio measured;
    measured.ratio = ratio;
    measured.ci = {low, high};
    measured.rounds = 10;
    return measured;
}

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
    std::mt19937_64 engine(42);
    const Rounds baseline = NoisyRounds(0.010, 12, 5, engine);
    const PairedRatio paired = ComparePaired(baseline, Scaled(baseline, 1.5));
    EXPECT_TRUE(paired.error.empty()) << paired.error;
    EXPECT_EQ(paired.rounds, 12);
    EXPECT_NEAR(paired.ratio, 1.5, 1e-12);  // 1e-12: log/exp rounding only
    EXPECT_LE(paired.ci.low, 1.5 + 1e-12);
    EXPECT_GE(paired.ci.high, 1.5 - 1e-12);
}

TEST(ReportStatisticsTest, RoundDriftCancelsBecauseRatiosArePairedByRound) {
    // Round medians drift from 10 ms to 30 ms, but every round the candidate takes twice as long.
    const Rounds baseline = {{0.010, 0.011, 0.009}, {0.020, 0.021, 0.019}, {0.030, 0.031, 0.029}};
    const Rounds candidate = {{0.020, 0.022, 0.018}, {0.040, 0.042, 0.038}, {0.060, 0.062, 0.058}};
    const PairedRatio paired = ComparePaired(baseline, candidate);
    EXPECT_NEAR(paired.ratio, 2.0, 1e-12);
    EXPECT_NEAR(paired.ci.low, 2.0, 1e-12);
    EXPECT_NEAR(paired.ci.high, 2.0, 1e-12);
}

TEST(ReportStatisticsTest, NoisyComparisonIsReproducibleForTheSameSeed) {
    std::mt19937_64 engine(2024);
    const Rounds baseline = NoisyRounds(0.010, 15, 7, engine);
    const Rounds candidate = NoisyRounds(0.012, 15, 7, engine);
    const PairedRatio first = ComparePaired(baseline, candidate, 7);
    const PairedRatio second = ComparePaired(baseline, candidate, 7);
    EXPECT_EQ(first.ratio, second.ratio);
    EXPECT_EQ(first.ci.low, second.ci.low);
    EXPECT_EQ(first.ci.high, second.ci.high);
    // The true ratio is 1.2; with independent 0..20% drift per round the estimate is near it.
    EXPECT_NEAR(first.ratio, 1.2, 0.1);
    EXPECT_LT(first.ci.low, first.ratio);
    EXPECT_GT(first.ci.high, first.ratio);
    EXPECT_LT(first.ci.low, 1.2);
    EXPECT_GT(first.ci.high, 1.2);
}

TEST(ReportStatisticsTest, SwappingBaselineAndCandidateInvertsRatioAndInterval) {
    std::mt19937_64 engine(5);
    const Rounds a = NoisyRounds(0.010, 10, 5, engine);
    const Rounds b = NoisyRounds(0.025, 10, 5, engine);
    const PairedRatio forward = ComparePaired(a, b);
    const PairedRatio backward = ComparePaired(b, a);
    EXPECT_NEAR(forward.ratio * backward.ratio, 1.0, 1e-12);
    EXPECT_NEAR(forward.ci.low * backward.ci.high, 1.0, 1e-9);  // 1e-9: interpolation rounding
    EXPECT_NEAR(forward.ci.high * backward.ci.low, 1.0, 1e-9);
}

TEST(ReportStatisticsTest, OneDisturbedRoundDoesNotMoveTheEstimate) {
    Rounds baseline(9, std::vector<double>{0.010});
    Rounds candidate(9, std::vector<double>{0.015});
    candidate[4] = {0.080};  // a background job ran during round 5
    EXPECT_NEAR(ComparePaired(baseline, candidate).ratio, 1.5, 1e-12);
}

TEST(ReportStatisticsTest, SingleRoundHasAnUnboundedInterval) {
    const PairedRatio paired = ComparePaired({{0.010, 0.012}}, {{0.020, 0.024}});
    EXPECT_NEAR(paired.ratio, 2.0, 1e-12);
    EXPECT_EQ(paired.ci.low, 0.0);
    EXPECT_EQ(paired.ci.high, kInfinity);
}

TEST(ReportStatisticsTest, NoRoundsFailWithNaN) {
    const PairedRatio paired = ComparePaired({}, {});
    EXPECT_TRUE(std::isnan(paired.ratio));
    EXPECT_EQ(paired.rounds, 0);
    EXPECT_EQ(paired.error, "no timing rounds to compare");
}

TEST(ReportStatisticsTest, DifferentRoundCountsFailWithNaN) {
    const PairedRatio paired = ComparePaired({{1.0}, {1.0}}, {{1.0}});
    EXPECT_TRUE(std::isnan(paired.ratio));
    EXPECT_TRUE(std::isnan(paired.ci.low));
    EXPECT_EQ(paired.error, "the baseline has 2 timing rounds but the candidate has 1");
}

TEST(ReportStatisticsTest, EmptyRoundFailsNamingTheRound) {
    const PairedRatio paired = ComparePaired({{1.0}, {1.0}}, {{1.0}, {}});
    EXPECT_TRUE(std::isnan(paired.ratio));
    EXPECT_EQ(paired.error, "candidate round 2 has no frame samples");
}

TEST(ReportStatisticsTest, NonPositiveOrNonFiniteFrameTimeFails) {
    EXPECT_EQ(ComparePaired({{0.0}}, {{1.0}}).error,
              "baseline round 1 has a frame time of 0, not a finite positive time");
    EXPECT_TRUE(std::isnan(ComparePaired({{1.0}}, {{-1.0}}).ratio));
    EXPECT_TRUE(std::isnan(ComparePaired({{1.0}}, {{kNaN}}).ratio));
    EXPECT_TRUE(std::isnan(ComparePaired({{kInfinity}}, {{1.0}}).ratio));
}

// --- Whitepaper conversions ------------------------------------------------------------------

// The whitepaper's wording against frame-time ratios: "reduced by p%" means the frame rate
// became (1 - p) of what it was, so frame time grew by 1 / (1 - p).
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
    std::mt19937_64 engine(9);
    const Rounds half_baseline = NoisyRounds(0.010, 5, 5, engine);
    const Rounds half_candidate = NoisyRounds(0.013, 5, 5, engine);
    Rounds baseline;
    Rounds candidate;
    for (std::size_t r = 0; r < half_baseline.size(); ++r) {  // each round twice in a row
        baseline.insert(baseline.end(), 2, half_baseline[r]);
        candidate.insert(candidate.end(), 2, half_candidate[r]);
    }
    const SplitHalf split = CompareSplitHalves(baseline, candidate);
    EXPECT_EQ(split.odd.rounds, 5);
    EXPECT_EQ(split.even.rounds, 5);
    EXPECT_EQ(split.odd.ratio, split.even.ratio);
    EXPECT_EQ(split.disagreement_percent_points, 0.0);
}

TEST(ReportStatisticsTest, SplitHalfDisagreementIsInPercentPointsOfPerformanceChange) {
    // Odd rounds: ratio 1.25 (-20%); even rounds: ratio 2 (-50%).
    const Rounds baseline = {{1.0}, {1.0}, {1.0}, {1.0}};
    const Rounds candidate = {{1.25}, {2.0}, {1.25}, {2.0}};
    const SplitHalf split = CompareSplitHalves(baseline, candidate);
    EXPECT_NEAR(split.odd.ratio, 1.25, 1e-12);
    EXPECT_NEAR(split.even.ratio, 2.0, 1e-12);
    EXPECT_NEAR(split.disagreement_percent_points, 30, 1e-9);
}

TEST(ReportStatisticsTest, SplitHalfOfOneRoundFails) {
    const SplitHalf split = CompareSplitHalves({{1.0}}, {{2.0}});
    EXPECT_TRUE(std::isnan(split.disagreement_percent_points));
    EXPECT_EQ(split.odd.error, "a split-half check needs at least two timing rounds");
    EXPECT_EQ(split.even.error, split.odd.error);
}

TEST(ReportStatisticsTest, SplitHalfOfMismatchedRoundsFails) {
    const SplitHalf split = CompareSplitHalves({{1.0}, {1.0}, {1.0}}, {{2.0}, {2.0}});
    EXPECT_TRUE(std::isnan(split.disagreement_percent_points));
    EXPECT_FALSE(split.odd.error.empty());
}

// --- Verdicts against the whitepaper ---------------------------------------------------------

struct VerdictCase {
    const char* why;
    double whitepaper_percent;
    PairedRatio measured;
    double tolerance;
    Agreement expected;
};

TEST(ReportStatisticsTest, VerdictsOnConstructedMeasurements) {
    const VerdictCase cases[] = {
            {"-58.3% within 10 points of -60%", -60, Measured(2.4, 2.3, 2.5), 10,
             Agreement::kSameDirectionAndMagnitude},
            {"-44% is 16 points off, but the CI -33%..-67% holds -60%", -60,
             Measured(1.8, 1.5, 3.0), 5, Agreement::kSameDirectionAndMagnitude},
            {"-20% is slower, as claimed, but far from -60%", -60, Measured(1.25, 1.2, 1.3), 10,
             Agreement::kSameDirectionOnly},
            {"+25% is faster where -60% was claimed", -60, Measured(0.8, 0.75, 0.85), 10,
             Agreement::kOpposite},
            {"+25% measured for a +25% claim", 25, Measured(0.8, 0.78, 0.82), 0,
             Agreement::kSameDirectionAndMagnitude},
            {"+5% where +25% was claimed", 25, Measured(1 / 1.05, 0.94, 0.96), 10,
             Agreement::kSameDirectionOnly},
            {"CI -9%..+11% straddles 0", -60, Measured(1.0, 0.9, 1.1), 10,
             Agreement::kInconclusive},
            {"CI ending exactly at ratio 1 does not establish a direction", -60,
             Measured(1.5, 1.0, 2.0), 10, Agreement::kInconclusive},
            {"a failed measurement", -60, PairedRatio{}, 10, Agreement::kInconclusive},
            {"a single round's unbounded CI", -60, Measured(2.5, 0, kInfinity), 10,
             Agreement::kInconclusive},
            {"a NaN figure", kNaN, Measured(2.4, 2.3, 2.5), 10, Agreement::kInconclusive},
            {"a 0% claim and a CI holding 0", 0, Measured(1.0, 0.95, 1.05), 0,
             Agreement::kSameDirectionAndMagnitude},
            {"a 0% claim and -2% within tolerance", 0, Measured(1.0 / 0.98, 1.01, 1.03), 5,
             Agreement::kSameDirectionAndMagnitude},
            {"a 0% claim and a definite -33%", 0, Measured(1.5, 1.4, 1.6), 10,
             Agreement::kOpposite},
            {"a NaN tolerance counts as 0", -60, Measured(1.25, 1.2, 1.3), kNaN,
             Agreement::kSameDirectionOnly},
    };
    for (const VerdictCase& c : cases) {
        EXPECT_EQ(CompareWithWhitepaper(c.whitepaper_percent, c.measured, c.tolerance), c.expected)
                << c.why << ": got "
                << AgreementName(
                           CompareWithWhitepaper(c.whitepaper_percent, c.measured, c.tolerance));
    }
}

TEST(ReportStatisticsTest, VerdictOfARealComparisonUsesItsBootstrapInterval) {
    std::mt19937_64 engine(77);
    const Rounds baseline = NoisyRounds(0.010, 20, 5, engine);
    const PairedRatio measured = ComparePaired(baseline, Scaled(baseline, 2.5));
    EXPECT_EQ(CompareWithWhitepaper(-60, measured, kWhitepaperMagnitudeTolerancePercentPoints),
              Agreement::kSameDirectionAndMagnitude);
    EXPECT_EQ(CompareWithWhitepaper(+60, measured, kWhitepaperMagnitudeTolerancePercentPoints),
              Agreement::kOpposite);
}

TEST(ReportStatisticsTest, AgreementNamesAreStable) {
    EXPECT_EQ(AgreementName(Agreement::kSameDirectionAndMagnitude), "same-direction-and-magnitude");
    EXPECT_EQ(AgreementName(Agreement::kSameDirectionOnly), "same-direction-only");
    EXPECT_EQ(AgreementName(Agreement::kOpposite), "opposite");
    EXPECT_EQ(AgreementName(Agreement::kInconclusive), "inconclusive");
}

// --- Spearman --------------------------------------------------------------------------------

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
