// The paired estimate, its interval's coverage and the sequential stopping rule
// (base/include/tidepool/base/PairedEstimate.h).
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/base/SampleStatistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

namespace tidepool::base {
namespace {

// Frame times shaped like the ones measured on this project's 2-core machines (issue 11): a
// frame's log time has a standard deviation of about 12%, half of its variance a slow drift
// that adjacent frames share (AR(1), 0.95 from one frame to the next), the rest independent,
// plus an occasional disturbed frame (2% of frames, 30% slower). Pairs alternate which side
// renders first, as the timing engine does.
class FrameNoise {
public:
    explicit FrameNoise(std::uint64_t seed, double log_sd = 0.12) : random_(seed), sd_(log_sd) {}

    // One pair: baseline and candidate times of a true frame-time ratio `ratio`.
    std::pair<double, double> NextPair(double ratio, int index) {
        const double first = Next();
        const double second = Next();
        const double base = 20.0;
        const bool baseline_first = index % 2 == 0;
        const double a = base * std::exp(baseline_first ? first : second);
        const double b = base * ratio * std::exp(baseline_first ? second : first);
        return {a, b};
    }

private:
    double Next() {
        constexpr double kPhi = 0.95;
        const double drift_sd = sd_ / std::sqrt(2.0);
        const double independent_sd = sd_ / std::sqrt(2.0);
        drift_ = kPhi * drift_ + std::sqrt(1 - kPhi * kPhi) * drift_sd * normal_(random_);
        double value = drift_ + independent_sd * normal_(random_);
        if (uniform_(random_) < 0.02) {
            value += 0.3;
        }
        return value;
    }

    std::mt19937_64 random_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    std::uniform_real_distribution<double> uniform_{0.0, 1.0};
    double sd_;
    double drift_ = 0;
};

// Runs the sequential rule to its end on simulated pairs of a true ratio.
PairedEstimate RunSequential(double ratio, const StoppingRule& rule, std::uint64_t seed,
                             StopDecision* decision, double log_sd = 0.12) {
    FrameNoise noise(seed, log_sd);
    std::vector<double> a;
    std::vector<double> b;
    PairedEstimate estimate;
    for (;;) {
        const int batch = PairsBeforeNextLook(static_cast<int>(a.size()), rule);
        for (int k = 0; k < batch; ++k) {
            const auto [x, y] = noise.NextPair(ratio, static_cast<int>(a.size()));
            a.push_back(x);
            b.push_back(y);
        }
        estimate = EstimatePaired(a, b);
        *decision = DecideStop(estimate, rule);
        if (*decision != StopDecision::kContinue) {
            return estimate;
        }
    }
}

TEST(PairedEstimateTest, FivePercentEffectWithSmallNoiseGetsItsDirection) {
    std::mt19937_64 random(7);
    std::normal_distribution<double> noise(0.0, 0.01);
    std::vector<double> a;
    std::vector<double> b;
    for (int i = 0; i < 40; ++i) {
        a.push_back(20.0 * std::exp(noise(random)));
        b.push_back(21.0 * std::exp(noise(random)));  // 5% longer frames
    }
    const PairedEstimate e = EstimatePaired(a, b);
    ASSERT_TRUE(e.Valid()) << e.error;
    EXPECT_TRUE(e.ExcludesNoChange());
    EXPECT_LT(e.change_high, 0.0);  // slower
    EXPECT_NEAR(e.ratio, 1.05, 0.01);
    EXPECT_NEAR(e.change_percent, (1 / 1.05 - 1) * 100, 1.0);
}

TEST(PairedEstimateTest, ZeroEffectIsNeverGivenADirection) {
    // Symmetric pair differences around no change: +x and -x for every x.
    std::vector<double> a;
    std::vector<double> b;
    for (int i = 1; i <= 30; ++i) {
        const double x = 0.002 * i;
        a.push_back(20.0);
        b.push_back(20.0 * std::exp(i % 2 == 0 ? x : -x));
        a.push_back(20.0);
        b.push_back(20.0 * std::exp(i % 2 == 0 ? -x : x));
    }
    const PairedEstimate e = EstimatePaired(a, b);
    ASSERT_TRUE(e.Valid()) << e.error;
    EXPECT_NEAR(e.ratio, 1.0, 1e-12);
    EXPECT_FALSE(e.ExcludesNoChange());
    EXPECT_LT(e.change_low, 0.0);
    EXPECT_GT(e.change_high, 0.0);
}

TEST(PairedEstimateTest, SwappingTheSidesGivesTheReciprocal) {
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> u(10.0, 30.0);
    std::vector<double> a;
    std::vector<double> b;
    for (int i = 0; i < 25; ++i) {
        a.push_back(u(random));
        b.push_back(u(random));
    }
    const PairedEstimate ab = EstimatePaired(a, b);
    const PairedEstimate ba = EstimatePaired(b, a);
    EXPECT_NEAR(ab.ratio * ba.ratio, 1.0, 1e-12);
    EXPECT_NEAR(ab.ratio_low * ba.ratio_high, 1.0, 1e-12);
    EXPECT_NEAR(ab.ratio_high * ba.ratio_low, 1.0, 1e-12);
}

TEST(PairedEstimateTest, OneDisturbedPairDoesNotMoveTheEstimate) {
    std::vector<double> a(30, 20.0);
    std::vector<double> b;
    for (int i = 0; i < 30; ++i) {
        b.push_back(22.0 * (1.0 + 0.001 * (i % 5)));
    }
    const double before = EstimatePaired(a, b).ratio;
    b[4] = 200.0;  // a frame preempted for 180 ms
    EXPECT_NEAR(EstimatePaired(a, b).ratio, before, 0.002);
}

TEST(PairedEstimateTest, BadInputIsAnErrorNotANumber) {
    EXPECT_EQ(EstimatePaired({1, 2}, {1}).error, "the two sides have 2 and 1 samples");
    EXPECT_EQ(EstimatePaired({1, 0}, {1, 1}).error,
              "pair 1 holds a time that is not finite and positive");
    EXPECT_EQ(EstimatePaired({}, {}).error, "no pairs");
    const PairedEstimate few = EstimatePaired({1, 1, 1}, {2, 2, 2});
    EXPECT_EQ(few.error, "fewer than 10 pairs give no interval");
    EXPECT_NEAR(few.ratio, 2.0, 1e-12);
    EXPECT_FALSE(few.Valid());
    EXPECT_TRUE(std::isnan(few.HalfWidthPoints()));
}

// The 95% interval covers the true effect 93-97% of the time, with the stopping rule applied
// as the timing engine applies it, over 1,000 simulated comparisons of measured-shape noise.
TEST(PairedEstimateTest, NinetyFivePercentIntervalCoversTheTrueEffectUnderMeasuredNoise) {
    StoppingRule rule;  // the defaults the engine uses: ±1.5 points, 20..400 pairs
    constexpr double kRatio = 1.08;
    int covered = 0;
    int resolved = 0;
    long total_pairs = 0;
    constexpr int kRuns = 1000;
    for (int run = 0; run < kRuns; ++run) {
        StopDecision decision = StopDecision::kContinue;
        const PairedEstimate e =
                RunSequential(kRatio, rule, 1000 + static_cast<std::uint64_t>(run), &decision);
        total_pairs += e.pairs;
        covered += e.ratio_low <= kRatio && kRatio <= e.ratio_high ? 1 : 0;
        resolved += decision == StopDecision::kResolved ? 1 : 0;
    }
    const double coverage = static_cast<double>(covered) / kRuns;
    EXPECT_GE(coverage, 0.93);
    EXPECT_LE(coverage, 0.97);
    EXPECT_EQ(resolved, kRuns) << "the cap should not be reached at this noise";
    std::printf("coverage %.3f over %d runs, %.0f pairs on average\n", coverage, kRuns,
                static_cast<double>(total_pairs) / kRuns);
}

TEST(PairedEstimateTest, StoppingRuleStopsAtTheResolutionNotBefore) {
    StoppingRule rule;
    rule.resolution_points = 1.5;
    StopDecision decision = StopDecision::kContinue;
    const PairedEstimate e = RunSequential(1.0, rule, 42, &decision);
    EXPECT_EQ(decision, StopDecision::kResolved);
    EXPECT_LE(e.HalfWidthPoints(), 1.5);
    EXPECT_GT(e.pairs, rule.min_pairs);  // this noise needs more than the minimum
}

TEST(PairedEstimateTest, LooksComeAtTheMinimumThenEveryQuarterOfThePairsSoFar) {
    StoppingRule rule;
    rule.min_pairs = 20;
    rule.batch_pairs = 10;
    rule.max_pairs = 100;
    EXPECT_EQ(PairsBeforeNextLook(0, rule), 20);
    EXPECT_EQ(PairsBeforeNextLook(20, rule), 10);
    EXPECT_EQ(PairsBeforeNextLook(80, rule), 20);
    EXPECT_EQ(PairsBeforeNextLook(90, rule), 10);  // not past the cap
    EXPECT_EQ(PairsBeforeNextLook(100, rule), 0);
}

TEST(PairedEstimateTest, StoppingRuleCapsWhenTheResolutionIsOutOfReach) {
    StoppingRule rule;
    rule.resolution_points = 0.01;
    rule.max_pairs = 60;
    StopDecision decision = StopDecision::kContinue;
    const PairedEstimate e = RunSequential(1.2, rule, 5, &decision);
    EXPECT_EQ(decision, StopDecision::kCapped);
    EXPECT_EQ(e.pairs, 60);
    EXPECT_STREQ(StopDecisionName(decision), "capped");
}

TEST(PairedEstimateTest, EveryStopDecisionIsReadBackFromItsName) {
    for (StopDecision d :
         {StopDecision::kContinue, StopDecision::kResolved, StopDecision::kCapped}) {
        EXPECT_EQ(StopDecisionFromName(StopDecisionName(d)), d) << StopDecisionName(d);
    }
    EXPECT_FALSE(StopDecisionFromName("Resolved"));
    EXPECT_FALSE(StopDecisionFromName(""));
}

// An estimate with a given interval in percent points of performance change (+ = faster).
PairedEstimate EstimateWithInterval(int pairs, double low, double high) {
    PairedEstimate e;
    e.pairs = pairs;
    e.change_low = low;
    e.change_high = high;
    e.change_percent = (low + high) / 2;
    e.ratio = 1.0;
    return e;
}

TEST(PairedEstimateTest, AnIntervalEndingOnTheMarginKeepsGoingUntilItClearsIt) {
    StoppingRule rule;  // resolution 1.5, margin 1.5, 1.5 standard errors
    // Half-width 1.25 (a standard error of 0.64): the upper end -1.4 sits 0.1 from -1.5.
    EXPECT_TRUE(NearVerdictBoundary(EstimateWithInterval(150, -3.9, -1.4), rule));
    EXPECT_EQ(DecideStop(EstimateWithInterval(150, -3.9, -1.4), rule), StopDecision::kContinue);
    // The same width well clear of both margins stops.
    EXPECT_FALSE(NearVerdictBoundary(EstimateWithInterval(150, -1.0, +1.5), rule));
    EXPECT_EQ(DecideStop(EstimateWithInterval(150, -1.0, +1.5), rule), StopDecision::kResolved);
    EXPECT_EQ(DecideStop(EstimateWithInterval(150, -6.5, -4.0), rule), StopDecision::kResolved);
    // The lower end near +1.5 counts too.
    EXPECT_EQ(DecideStop(EstimateWithInterval(150, +1.6, +4.1), rule), StopDecision::kContinue);
    // At half the resolution it stops wherever it lies; at the cap it is capped.
    EXPECT_EQ(DecideStop(EstimateWithInterval(300, -2.9, -1.5), rule), StopDecision::kResolved);
    EXPECT_EQ(DecideStop(EstimateWithInterval(400, -3.9, -1.4), rule), StopDecision::kCapped);
}

TEST(PairedEstimateTest, ACoarseRuleStillResolvesTheMarginAtHalfTheMargin) {
    // The planner's rule: 3 points far from the margin, but near it as fine as the report's.
    const StoppingRule coarse{3.0, 20, 400, 10};
    EXPECT_DOUBLE_EQ(FinestHalfWidthPoints(coarse), 0.75);
    EXPECT_DOUBLE_EQ(FinestHalfWidthPoints(StoppingRule{}), 0.75);
    EXPECT_DOUBLE_EQ(FinestHalfWidthPoints(StoppingRule{0.5, 20, 400, 10}), 0.25);
    // Far from the margins (ends 4 points from them, beyond 1.5 standard errors of 1.28) it
    // stops at the coarse resolution, whether the effect is large or nothing.
    EXPECT_EQ(DecideStop(EstimateWithInterval(40, -10.5, -5.5), coarse), StopDecision::kResolved);
    EXPECT_EQ(DecideStop(EstimateWithInterval(40, -2.5, +2.5), coarse), StopDecision::kResolved);
    // -2.8 +/- 1.2: the upper end -1.6 sits on the margin. Half the resolution (1.5) would stop
    // here; the rule goes on until the end clears it or the half-width is 0.75.
    EXPECT_TRUE(NearVerdictBoundary(EstimateWithInterval(100, -4.0, -1.6), coarse));
    EXPECT_EQ(DecideStop(EstimateWithInterval(100, -4.0, -1.6), coarse), StopDecision::kContinue);
    EXPECT_EQ(DecideStop(EstimateWithInterval(300, -3.5, -2.0), coarse), StopDecision::kResolved);
    EXPECT_EQ(DecideStop(EstimateWithInterval(300, -2.9, -1.5), coarse), StopDecision::kResolved);
}

TEST(PairedEstimateTest, AnEffectOfThreePercentIsClaimedInMostRunsNotInAboutHalf) {
    // A true effect of -3% at the noise of the thread-CPU clock (row 8 of the default run: 150
    // pairs gave a half-width of 1.26 points, a pair's log ratio varying by about 8%). Without
    // the boundary clause a run stops with the interval's upper end anywhere around -1.5 and
    // claims the direction in about half of the runs, so two runs disagree often; with it, most
    // runs claim it. The clause narrows the band of effects whose verdict depends on the run;
    // effects right at the margin's reach stay in it (bench/verdict_stability.sh shows them).
    constexpr int kRuns = 120;
    constexpr double kPairNoise = 0.08;
    const double ratio = 1.0 / (1.0 - 0.03);
    auto claimed_share = [&](double boundary_standard_errors) {
        StoppingRule rule;
        rule.boundary_standard_errors = boundary_standard_errors;
        int claimed = 0;
        for (int run = 0; run < kRuns; ++run) {
            StopDecision decision = StopDecision::kContinue;
            const PairedEstimate e = RunSequential(
                    ratio, rule, static_cast<std::uint64_t>(1000 + run), &decision, kPairNoise);
            claimed += e.change_high < -kDirectionMarginPoints ? 1 : 0;
        }
        return static_cast<double>(claimed) / kRuns;
    };
    const double without = claimed_share(0.0);
    const double with = claimed_share(StoppingRule{}.boundary_standard_errors);
    std::printf("direction claimed in %.2f of runs without the clause, %.2f with it\n", without,
                with);
    EXPECT_LT(without, 0.75);
    EXPECT_GE(with, 0.85);
}

TEST(PairedEstimateTest, AnEstimateBeyondTheMarginKeepsGoingUntilTheIntervalClearsIt) {
    const StoppingRule coarse{3.0, 20, 400, 10};  // the planner's
    // -1.7 +/- 1.6 after 20 pairs (the planner's half-size reflection, quiet): the upper end
    // -0.1 is 1.4 from the margin, beyond the reach of 1.5 standard errors (1.22), yet the
    // estimate says more pairs would clear it.
    EXPECT_TRUE(NearVerdictBoundary(EstimateWithInterval(20, -3.3, -0.1), coarse));
    EXPECT_EQ(DecideStop(EstimateWithInterval(20, -3.3, -0.1), coarse), StopDecision::kContinue);
    EXPECT_EQ(DecideStop(EstimateWithInterval(20, +0.1, +3.3), coarse), StopDecision::kContinue);
    // The centre inside the margins: no direction however many pairs, so it stops.
    EXPECT_FALSE(NearVerdictBoundary(EstimateWithInterval(20, -2.9, +0.1), coarse));
    EXPECT_EQ(DecideStop(EstimateWithInterval(20, -2.9, +0.1), coarse), StopDecision::kResolved);
    // At the finest half-width it stops wherever it lies.
    EXPECT_EQ(DecideStop(EstimateWithInterval(300, -2.2, -0.8), coarse), StopDecision::kResolved);

    // The estimate decides, not the interval's midpoint. The half-size reflection beside two
    // `yes` (2026-11-27): +2.8% [-0.8, +3.7] in performance after 20 pairs, the as-run and
    // contended intervals spanned, midpoint +1.45, inside the margin; it stopped unclaimed.
    PairedEstimate lopsided = EstimateWithInterval(20, -0.8, +3.7);
    lopsided.change_percent = +2.8;
    EXPECT_TRUE(NearVerdictBoundary(lopsided, coarse));
    EXPECT_EQ(DecideStop(lopsided, coarse), StopDecision::kContinue);
    // And the other way: the midpoint beyond the margin, the estimate inside it.
    lopsided = EstimateWithInterval(20, -0.4, +4.2);
    lopsided.change_percent = +0.6;
    EXPECT_FALSE(NearVerdictBoundary(lopsided, coarse));
    EXPECT_EQ(DecideStop(lopsided, coarse), StopDecision::kResolved);

    // Effects a little beyond the margin at the measured noise: with the clause, many more runs
    // claim the direction; without it, most stop early and do not. (80 runs each: the sequential
    // runs are slow under the sanitizers.)
    constexpr int kRuns = 80;
    auto claimed_share = [&](double change, double boundary_standard_errors) {
        StoppingRule rule = coarse;
        rule.boundary_standard_errors = boundary_standard_errors;
        int claimed = 0;
        for (int run = 0; run < kRuns; ++run) {
            StopDecision decision = StopDecision::kContinue;
            const PairedEstimate e =
                    RunSequential(1.0 / (1.0 + change / 100.0), rule,
                                  static_cast<std::uint64_t>(5000 + run), &decision, 0.08);
            claimed += e.change_high < -kDirectionMarginPoints ? 1 : 0;
        }
        return static_cast<double>(claimed) / kRuns;
    };
    // (Closer to the margin, at -2.2 and -2.4%, it was 0.28 and 0.38 against 0.07 and 0.08: the
    // band where runs disagree narrows but stays, about the margin plus the finest half-width.)
    for (double change : {-2.6, -2.8}) {
        const double with = claimed_share(change, 1.5);
        const double without = claimed_share(change, 0.0);
        std::printf("%.1f%%: claimed in %.2f of runs with the clause, %.2f without\n", change, with,
                    without);
        EXPECT_GE(with, without + 0.3) << change;
    }
}

TEST(PairedEstimateTest, AnIntervalHoldingAnotherBoundaryKeepsGoingUntilItClearsIt) {
    StoppingRule rule;
    rule.boundaries_points = {-6.0};
    // Half-width 1.2, far from the margins: without the boundary it would stop.
    EXPECT_EQ(DecideStop(EstimateWithInterval(50, -7.0, -4.6), StoppingRule{}),
              StopDecision::kResolved);
    // Holding -6.0, or ending 0.6 from it (within 1.5 standard errors of 0.61): it goes on.
    EXPECT_TRUE(NearVerdictBoundary(EstimateWithInterval(50, -7.0, -4.6), rule));
    EXPECT_EQ(DecideStop(EstimateWithInterval(50, -7.0, -4.6), rule), StopDecision::kContinue);
    EXPECT_EQ(DecideStop(EstimateWithInterval(50, -5.4, -3.0), rule), StopDecision::kContinue);
    // Ending 1.1 from it: clear.
    EXPECT_EQ(DecideStop(EstimateWithInterval(50, -4.9, -2.5), rule), StopDecision::kResolved);

    // Row 2's case: an effect of -3.3% against the band that starts at -4.8%, with the pairs'
    // noise of a loaded machine. No run states a firm magnitude on the wrong side of the band's
    // start (wholly within the band), which another run's "outside the band" would contradict;
    // a run that stops holding it states the band's edge, which contradicts neither.
    StoppingRule row;
    row.boundaries_points = {-4.8, -19.2};
    constexpr int kRuns = 80;  // slow under the sanitizers
    int outside = 0;
    int within = 0;
    for (int run = 0; run < kRuns; ++run) {
        StopDecision decision = StopDecision::kContinue;
        const PairedEstimate e = RunSequential(
                1.0 / (1.0 - 0.033), row, static_cast<std::uint64_t>(7000 + run), &decision, 0.08);
        outside += e.change_low > -4.8 ? 1 : 0;
        within += e.change_high < -4.8 ? 1 : 0;
    }
    std::printf("outside the band in %d of %d runs, within it in %d\n", outside, kRuns, within);
    EXPECT_EQ(within, 0);
    EXPECT_GE(outside, kRuns / 2);
}

TEST(PairedEstimateTest, AnIntervalHoldingABandEdgeGoesOnPastTheFinestHalfWidth) {
    StoppingRule row;                     // resolution 1.5: the finest half-width is 0.75
    row.boundaries_points = {1.75, 7.0};  // row 4: half to twice the whitepaper's +3.5%
    // Row 4 loaded: +7.3% [+6.9, +7.7] after 20 pairs, a half-width of 0.4, holding the edge.
    EXPECT_TRUE(HoldsVerdictBoundary(EstimateWithInterval(20, 6.9, 7.7), row));
    EXPECT_EQ(DecideStop(EstimateWithInterval(20, 6.9, 7.7), row), StopDecision::kContinue);
    // Without the edge in its rule the same interval stops at the finest half-width.
    EXPECT_EQ(DecideStop(EstimateWithInterval(20, 6.9, 7.7), StoppingRule{}),
              StopDecision::kResolved);
    // Clear of the edge, even with an end close to it, it stops below the finest half-width.
    EXPECT_FALSE(HoldsVerdictBoundary(EstimateWithInterval(80, 7.1, 7.5), row));
    EXPECT_EQ(DecideStop(EstimateWithInterval(80, 7.1, 7.5), row), StopDecision::kResolved);
    // The direction margin is no such boundary: holding +1.5 gives no verdict to contradict.
    EXPECT_EQ(DecideStop(EstimateWithInterval(300, 1.3, 1.7), row), StopDecision::kResolved);
    // The progress guess follows it past the finest half-width.
    EXPECT_GT(PairsExpectedAtStop(EstimateWithInterval(20, 6.9, 7.7), row, 60), 20);

    // Still holding it at boundary_pairs, it stops: its magnitude is the band's edge. Without
    // the bound it went on to the cap.
    EXPECT_EQ(row.boundary_pairs, 80);
    EXPECT_EQ(DecideStop(EstimateWithInterval(77, 6.9, 7.1), row), StopDecision::kContinue);
    EXPECT_EQ(DecideStop(EstimateWithInterval(96, 6.9, 7.1), row), StopDecision::kResolved);
    StoppingRule unbounded = row;
    unbounded.boundary_pairs = 0;
    EXPECT_EQ(DecideStop(EstimateWithInterval(96, 6.9, 7.1), unbounded), StopDecision::kContinue);
    EXPECT_EQ(DecideStop(EstimateWithInterval(400, 6.9, 7.1), unbounded), StopDecision::kCapped);
    // Past it, an end near the edge that the interval does not hold still goes on: that
    // magnitude is firm, and the other side of the edge would be another firm one.
    // (A half-width of 1, between the finest and the resolution; at the finest it stops.)
    EXPECT_TRUE(NearUnheldBoundary(EstimateWithInterval(96, 7.05, 9.05), row));
    EXPECT_EQ(DecideStop(EstimateWithInterval(96, 7.05, 9.05), row), StopDecision::kContinue);
    EXPECT_FALSE(NearUnheldBoundary(EstimateWithInterval(96, 6.9, 7.1), row));
    // So does one near the direction margin, however many pairs: a direction is firm.
    EXPECT_EQ(DecideStop(EstimateWithInterval(200, 1.55, 2.6), row), StopDecision::kContinue);

    // An effect of +7.4%, 0.4 points beyond the edge, at a noise where 20 pairs give a
    // half-width of about half a point (the development machine's in 2026-11). With the edge in
    // the rule, more runs decide that the magnitude lies outside the band than without it, where
    // a run stops at 20 pairs holding the edge about as often as not; no run states it within
    // the band, which would contradict those that state it outside.
    constexpr int kRuns = 80;  // slow under the sanitizers
    auto shares = [&](const StoppingRule& rule) {
        int outside = 0;
        int within = 0;
        for (int run = 0; run < kRuns; ++run) {
            StopDecision decision = StopDecision::kContinue;
            const PairedEstimate e = RunSequential(
                    1.0 / 1.074, rule, static_cast<std::uint64_t>(9000 + run), &decision, 0.012);
            outside += e.change_low > 7.0 ? 1 : 0;
            within += e.change_high < 7.0 ? 1 : 0;
        }
        return std::pair<double, double>{static_cast<double>(outside) / kRuns,
                                         static_cast<double>(within) / kRuns};
    };
    const auto [with_outside, with_within] = shares(row);
    const auto [without_outside, without_within] = shares(StoppingRule{});
    std::printf(
            "outside the band in %.2f of runs with the edge in the rule (within %.2f), %.2f "
            "without (within %.2f)\n",
            with_outside, with_within, without_outside, without_within);
    EXPECT_GE(with_outside, without_outside + 0.2);
    EXPECT_EQ(with_within, 0.0);
}

// A load that slows the candidate's frames by 3% more than the baseline's: the contended pairs
// see it, and the stated interval reaches it while keeping the as-run estimate.
TEST(PairedEstimateTest, TheStatedIntervalSpansTheAsRunAndTheContendedIntervals) {
    FrameNoise quiet(7, 0.01);
    FrameNoise busy(8, 0.01);
    std::vector<double> a, b, ca, cb;
    for (int i = 0; i < 40; ++i) {
        const auto [x, y] = quiet.NextPair(1.10, i);
        a.push_back(x);
        b.push_back(y);
    }
    for (int i = 0; i < 20; ++i) {
        const auto [x, y] = busy.NextPair(1.10 * 1.03, i);
        ca.push_back(x);
        cb.push_back(y);
    }
    const PairedEstimate as_run = EstimatePaired(a, b);
    const PairedEstimate contended = EstimatePaired(ca, cb);
    ASSERT_TRUE(as_run.Valid() && contended.Valid());
    const PairedEstimate stated = AcrossHostStates(as_run, contended);
    ASSERT_TRUE(stated.Valid()) << stated.error;
    EXPECT_EQ(stated.pairs, 40);
    EXPECT_EQ(stated.ratio, as_run.ratio);
    EXPECT_EQ(stated.change_percent, as_run.change_percent);
    EXPECT_EQ(stated.ratio_low, std::min(as_run.ratio_low, contended.ratio_low));
    EXPECT_EQ(stated.ratio_high, std::max(as_run.ratio_high, contended.ratio_high));
    EXPECT_LE(stated.change_low, std::min(as_run.change_low, contended.change_low));
    EXPECT_GE(stated.change_high, std::max(as_run.change_high, contended.change_high));
    // The two states' estimates both lie inside what is stated; the as-run interval alone
    // misses the contended estimate here.
    EXPECT_GT(contended.ratio, as_run.ratio_high);
    EXPECT_LE(stated.ratio_low, as_run.ratio);
    EXPECT_GE(stated.ratio_high, contended.ratio);
}

TEST(PairedEstimateTest, WithoutContendedPairsTheStatedIntervalIsTheAsRunOne) {
    const PairedEstimate as_run = EstimateWithInterval(20, 1.0, 2.0);
    const PairedEstimate stated = AcrossHostStates(as_run, PairedEstimate{});
    EXPECT_EQ(stated.change_low, 1.0);
    EXPECT_EQ(stated.change_high, 2.0);
    EXPECT_EQ(stated.pairs, 20);
    // Too few contended pairs for an interval: no stated interval yet, and why.
    const PairedEstimate few = EstimatePaired({10, 10, 10}, {11, 11, 11});
    const PairedEstimate none = AcrossHostStates(
            EstimatePaired(std::vector<double>(20, 10.0), std::vector<double>(20, 11.0)), few);
    EXPECT_FALSE(none.Valid());
    EXPECT_NE(none.error.find("core shared"), std::string::npos) << none.error;
    EXPECT_TRUE(std::isnan(none.change_low));
    EXPECT_EQ(DecideStop(none, StoppingRule{}), StopDecision::kContinue);
}

TEST(PairedEstimateTest, ContendedPairsFollowTheShareWithAnIntervalsMinimum) {
    StoppingRule rule;
    EXPECT_EQ(ContendedPairsBeforeNextLook(20, 0, rule), 0);  // share 0: none
    rule.contended_share = 0.5;
    EXPECT_EQ(ContendedPairsBeforeNextLook(20, 0, rule), kMinimumPairs);
    EXPECT_EQ(ContendedPairsBeforeNextLook(30, 10, rule), 5);
    EXPECT_EQ(ContendedPairsBeforeNextLook(31, 15, rule), 1);  // ceil(15.5) - 15
    EXPECT_EQ(ContendedPairsBeforeNextLook(100, 50, rule), 0);
    rule.contended_share = 0.1;
    EXPECT_EQ(ContendedPairsBeforeNextLook(40, 0, rule), kMinimumPairs);  // an interval needs 10
    EXPECT_EQ(ContendedPairsBeforeNextLook(200, 10, rule), 10);
}

TEST(PairedEstimateTest, ContendedPairsNarrowMoreWhereTheirIntervalSetsTheEndThatNarrowsFaster) {
    const PairedEstimate as_run = EstimateWithInterval(40, -2.6, -2.4);
    // Row 2 after 363 pairs: both ends of the stated interval are the contended interval's.
    EXPECT_TRUE(ContendedPairsNarrowMore(as_run, EstimateWithInterval(182, -3.34, -1.77)));
    // One end each, the contended one the wider per pair (0.75 / 20 against 0.1 / 40).
    EXPECT_TRUE(ContendedPairsNarrowMore(as_run, EstimateWithInterval(20, -2.5, -1.0)));
    EXPECT_TRUE(ContendedPairsNarrowMore(as_run, EstimateWithInterval(20, -4.0, -2.5)));
    EXPECT_TRUE(ContendedPairsNarrowMore(as_run, EstimateWithInterval(20, -2.6, -1.0)));
    // open_sea's half-size reflection beside two `yes` (2026-11-28): the contended interval sets
    // the upper end, the one the planner's margin decides on, at 0.0038 points per pair against
    // the as-run lower end's 0.0009.
    EXPECT_TRUE(ContendedPairsNarrowMore(EstimateWithInterval(400, -3.17, -2.48),
                                         EstimateWithInterval(200, -2.97, -1.44)));
    // One end each, the as-run one the wider per pair (1.5 / 20 against 1.1 / 200).
    EXPECT_FALSE(ContendedPairsNarrowMore(EstimateWithInterval(20, -4.0, -1.0),
                                          EstimateWithInterval(200, -3.0, -0.8)));
    // The contended interval inside the as-run one, or equal to it: it sets no end.
    EXPECT_FALSE(ContendedPairsNarrowMore(as_run, EstimateWithInterval(20, -2.55, -2.45)));
    EXPECT_FALSE(ContendedPairsNarrowMore(as_run, as_run));
    // No interval on either side: as-run pairs.
    EXPECT_FALSE(ContendedPairsNarrowMore(as_run, PairedEstimate{}));
    EXPECT_FALSE(ContendedPairsNarrowMore(PairedEstimate{}, EstimateWithInterval(182, -3.3, -1.8)));
}

TEST(PairedEstimateTest, ALookOfContendedPairsAloneTakesWhatAnAsRunLookWouldUpToTheCap) {
    const StoppingRule rule;  // batch 10, cap 400
    EXPECT_EQ(ContendedPairsForLook(10, rule), 10);
    EXPECT_EQ(ContendedPairsForLook(100, rule), 25);
    EXPECT_EQ(ContendedPairsForLook(380, rule), 20);
    EXPECT_EQ(ContendedPairsForLook(400, rule), 0);
    EXPECT_EQ(ContendedPairsForLook(0, rule), 10);
}

TEST(PairedEstimateTest, TheRulesPairCountsCountTheLargerStatesPairs) {
    StoppingRule row;
    row.boundaries_points = {1.75, 7.0};  // row 4's band
    // 40 as-run pairs holding the band's edge: it goes on as before with 20 contended pairs, and
    // stops at the bound once the contended pairs it took alone reach boundary_pairs.
    const PairedEstimate holding = EstimateWithInterval(40, 6.9, 7.1);
    EXPECT_EQ(DecideStopAcrossStates(holding, 20, row), StopDecision::kContinue);
    EXPECT_EQ(DecideStopAcrossStates(holding, 96, row), StopDecision::kResolved);
    // The cap counts them too, where the as-run pairs alone never reach it.
    const PairedEstimate wide = EstimateWithInterval(40, -4.0, 1.0);
    EXPECT_EQ(DecideStopAcrossStates(wide, 399, StoppingRule{}), StopDecision::kContinue);
    EXPECT_EQ(DecideStopAcrossStates(wide, 400, StoppingRule{}), StopDecision::kCapped);
    // With fewer contended pairs than as-run ones it is DecideStop.
    EXPECT_EQ(DecideStopAcrossStates(holding, 20, row), DecideStop(holding, row));
    EXPECT_EQ(DecideStopAcrossStates(EstimateWithInterval(96, 6.9, 7.1), 48, row),
              DecideStop(EstimateWithInterval(96, 6.9, 7.1), row));
}

// Pairs whose frame-time ratio is `ratio` give or take up to `spread` (a fixed pattern of five
// steps), the baseline at 10 ms.
struct Samples {
    std::vector<double> baseline;
    std::vector<double> candidate;
};
Samples PairsOf(int pairs, double ratio, double spread) {
    Samples out;
    for (int i = 0; i < pairs; ++i) {
        out.baseline.push_back(10.0);
        out.candidate.push_back(10.0 * ratio * (1.0 + spread * ((i % 5) - 2) / 2.0));
    }
    return out;
}

// A comparison's pairs in both states, 3% slower, and what the progress guess makes of them.
struct TwoStates {
    Samples as_run;
    Samples contended;
    PairedEstimate as_run_estimate;
    PairedEstimate contended_estimate;
    PairedEstimate stated;
    bool binds = false;  // ContendedPairsNarrowMore

    TwoStates(int as_run_pairs, double as_run_spread, int contended_pairs, double contended_spread)
        : as_run(PairsOf(as_run_pairs, 1.03, as_run_spread)),
          contended(PairsOf(contended_pairs, 1.03, contended_spread)),
          as_run_estimate(EstimatePaired(as_run.baseline, as_run.candidate)),
          contended_estimate(EstimatePaired(contended.baseline, contended.candidate)),
          stated(AcrossHostStates(as_run_estimate, contended_estimate)),
          binds(ContendedPairsNarrowMore(as_run_estimate, contended_estimate)) {}
    ExpectedPairs Guess(const StoppingRule& rule) const {
        return PairsExpectedAcrossStates(as_run.baseline, as_run.candidate, contended.baseline,
                                         contended.candidate, as_run_estimate, contended_estimate,
                                         rule, 60);
    }
};

TEST(PairedEstimateTest, TheProgressGuessCountsTheStatesPairsTheRuleWillTake) {
    StoppingRule rule;
    rule.contended_share = 0.5;
    StoppingRule alone = rule;
    alone.contended_share = 0;
    // A steady candidate as run, give or take 4% with its core shared: the contended interval
    // holds the as-run one, and the looks to come take contended pairs alone.
    const TwoStates binding(20, 0.004, 10, 0.04);
    ASSERT_TRUE(binding.binds);
    ASSERT_EQ(DecideStopAcrossStates(binding.stated, 10, rule), StopDecision::kContinue);
    EXPECT_EQ(binding.Guess(rule).as_run, 20);
    PairedEstimate by_contended = binding.stated;
    by_contended.pairs = 10;
    const int contended_guess = PairsExpectedFromPairs(
            binding.contended.baseline, binding.contended.candidate, by_contended, alone, 60);
    EXPECT_EQ(binding.Guess(rule).contended, contended_guess);
    EXPECT_GT(contended_guess, 10);
    // A probe's 10 as-run pairs count as the 20 its first look will have.
    const TwoStates probe(10, 0.004, 10, 0.04);
    ASSERT_TRUE(probe.binds);
    EXPECT_EQ(probe.Guess(rule).as_run, 20);

    // The other way round, the as-run interval sets an end: the as-run guess, with the
    // contended share beside it.
    const TwoStates as_run_bound(20, 0.04, 10, 0.004);
    ASSERT_FALSE(as_run_bound.binds);
    const int guess =
            PairsExpectedFromPairs(as_run_bound.as_run.baseline, as_run_bound.as_run.candidate,
                                   as_run_bound.stated, rule, 60);
    EXPECT_EQ(as_run_bound.Guess(rule).as_run, guess);
    EXPECT_EQ(as_run_bound.Guess(rule).contended,
              10 + ContendedPairsBeforeNextLook(guess, 10, rule));

    // When the rule stops now, the pairs so far.
    const TwoStates settled(120, 0.004, 60, 0.004);
    ASSERT_NE(DecideStopAcrossStates(settled.stated, 60, rule), StopDecision::kContinue);
    EXPECT_EQ(settled.Guess(rule).as_run, 120);
    EXPECT_EQ(settled.Guess(rule).contended, 60);
}

TEST(PairedEstimateTest, PullingTheOuterRatiosInMovesTheLowestAndHighestPairToTheNext) {
    const std::vector<double> baseline = {10, 10, 20, 10, 10};
    // Log ratios: ln 1.02, ln 1.5 (highest), ln 1.01, ln 0.9 (lowest), ln 1.03.
    const std::vector<double> candidate = {10.2, 15.0, 20.2, 9.0, 10.3};
    const std::vector<double> pulled = WithOuterRatiosPulledIn(baseline, candidate);
    ASSERT_EQ(pulled.size(), candidate.size());
    EXPECT_DOUBLE_EQ(pulled[0], 10.2);
    EXPECT_NEAR(pulled[1], 10.3, 1e-9);  // to the next highest ratio, 1.03
    EXPECT_DOUBLE_EQ(pulled[2], 20.2);
    EXPECT_NEAR(pulled[3], 10.1, 1e-9);  // to the next lowest ratio, 1.01
    EXPECT_DOUBLE_EQ(pulled[4], 10.3);
    // Nothing to pull in, or nothing to read: as given.
    EXPECT_EQ(WithOuterRatiosPulledIn({10, 10}, {11, 12}), (std::vector<double>{11, 12}));
    EXPECT_EQ(WithOuterRatiosPulledIn({10, 10, 10}, {11, 12}), (std::vector<double>{11, 12}));
    EXPECT_EQ(WithOuterRatiosPulledIn({10, 0, 10}, {11, 12, 13}),
              (std::vector<double>{11, 12, 13}));
}

// A probe: ten pairs each way, 3% slower give or take a little, one as-run pair 25% slower; and
// its steadied twin, whose disturbed pair reads like the next slowest one.
struct DisturbedProbe {
    StoppingRule rule;
    Samples as_run = PairsOf(10, 1.03, 0.004);
    Samples contended = PairsOf(10, 1.03, 0.01);
    PairedEstimate as_run_estimate;
    PairedEstimate contended_estimate;
    Samples steadied;
    PairedEstimate steadied_estimate;

    DisturbedProbe() {
        rule.contended_share = 0.5;
        as_run.candidate[3] = 12.5;
        as_run_estimate = EstimatePaired(as_run.baseline, as_run.candidate);
        contended_estimate = EstimatePaired(contended.baseline, contended.candidate);
        steadied = as_run;
        steadied.candidate = WithOuterRatiosPulledIn(as_run.baseline, as_run.candidate);
        steadied_estimate = EstimatePaired(steadied.baseline, steadied.candidate);
    }
};

TEST(PairedEstimateTest, OneDisturbedPairInAProbeDoesNotSetItsGuess) {
    const DisturbedProbe p;
    const ExpectedPairs guess = PairsExpectedAcrossStates(
            p.as_run.baseline, p.as_run.candidate, p.contended.baseline, p.contended.candidate,
            p.as_run_estimate, p.contended_estimate, p.rule, 60);
    // From the interval the ten pairs state as they are, the guess would be over 200 pairs.
    EXPECT_GT(PairsExpectedAtStop(AcrossHostStates(p.as_run_estimate, p.contended_estimate), p.rule,
                                  60),
              200);
    EXPECT_LT(guess.as_run + guess.contended, 100);
    // It is the guess of the probe whose disturbed pair reads like the next slowest one.
    EXPECT_LT(p.steadied.candidate[3], 10.5);
    const ExpectedPairs steady = PairsExpectedAcrossStates(
            p.steadied.baseline, p.steadied.candidate, p.contended.baseline, p.contended.candidate,
            p.steadied_estimate, p.contended_estimate, p.rule, 60);
    EXPECT_EQ(guess.as_run, steady.as_run);
    EXPECT_EQ(guess.contended, steady.contended);
}

TEST(PairedEstimateTest, ExpectedPairsFollowTheSquareRootLawAndTheLooks) {
    StoppingRule rule;  // resolution 1.5, looks at 20, then every quarter
    // Half-width 3.0 at 20 pairs, centre 8, clear of the margins wherever the change lies within
    // the interval's reach: (3.0 / 1.5)^2 x 20 = 80, and the first look at or after 80 is 20,
    // 30, 40, 50, 62, 77, 96.
    EXPECT_EQ(PairsExpectedAtStop(EstimateWithInterval(20, 5.0, 11.0), rule, 60), 96);
    // Already narrow enough and far from the margins: the pairs so far.
    EXPECT_EQ(PairsExpectedAtStop(EstimateWithInterval(62, 4.0, 5.0), rule, 60), 62);
    // The same width with the interval holding the margin (centre -2.65, upper end -1.4, 0.1
    // beyond it) needs more: the end must clear the margin by 1.5 standard errors, and a change
    // nearer the margin than the centre needs more still, up to the cap. Far from it, it stops
    // now. Mirrored, the same.
    const int near = PairsExpectedAtStop(EstimateWithInterval(150, -3.9, -1.4), rule, 60);
    const int far = PairsExpectedAtStop(EstimateWithInterval(150, -11.15, -8.65), rule, 60);
    EXPECT_EQ(far, 150);
    EXPECT_GT(near, far);
    EXPECT_EQ(PairsExpectedAtStop(EstimateWithInterval(150, -4.65, -2.15), rule, 60),
              PairsExpectedAtStop(EstimateWithInterval(150, +2.15, +4.65), rule, 60));
    // The closer the centre to the margin, the more pairs (centre -3.4, upper end 0.65 beyond
    // the margin).
    EXPECT_GT(near, PairsExpectedAtStop(EstimateWithInterval(150, -4.65, -2.15), rule, 60));
    // An estimate that does not stop now expects at least the next look.
    EXPECT_EQ(DecideStop(EstimateWithInterval(150, -3.9, -1.4), rule), StopDecision::kContinue);
    EXPECT_GE(near, 150 + PairsBeforeNextLook(150, rule));
    // No interval yet: the fallback, rounded to a look.
    EXPECT_EQ(PairsExpectedAtStop(PairedEstimate{}, rule, 60), 62);
    // At the cap: the cap.
    EXPECT_EQ(PairsExpectedAtStop(EstimateWithInterval(400, 6.9, 7.1), rule, 60), 400);
}

// `pairs` pairs (an even number) whose candidate is `slower` times slower, and whose log
// frame-time ratios lie by turns above and below that by an amount the spread estimate (1.4826
// median absolute deviations) reads as `sigma_points` points of frame rate.
std::pair<std::vector<double>, std::vector<double>> PairsWithSpread(int pairs, double slower,
                                                                    double sigma_points) {
    const double mu = std::log(slower);
    const double deviation = sigma_points / (1.4826 * 100.0 * std::exp(-mu));
    std::vector<double> baseline;
    std::vector<double> candidate;
    for (int i = 0; i < pairs; ++i) {
        baseline.push_back(10.0);
        candidate.push_back(10.0 * std::exp(mu + (i % 2 == 0 ? deviation : -deviation)));
    }
    return {baseline, candidate};
}

TEST(PairedEstimateTest, ExpectedPairsFromTheSpreadFollowTheNoiseAndTheContendedShare) {
    // 10% slower (-9.1%, far from every margin) with a spread of 5.05 points a pair: the
    // resolution of 1.5 needs (1.96 x 5.05 / 1.5)^2 = 43.5 pairs, the first look after that is
    // 50 (looks at 20, 30, 40, 50, 62, 77, 96).
    const auto [baseline, candidate] = PairsWithSpread(20, 1.10, 5.05);
    StoppingRule as_run_only;
    EXPECT_EQ(PairsExpectedFromSpread(baseline, candidate, as_run_only), 50);
    // With contended pairs at half the as-run ones, the stated interval is the contended one's,
    // of half the pairs: 87 as-run pairs, so the look at 96.
    StoppingRule contended = as_run_only;
    contended.contended_share = 0.5;
    EXPECT_EQ(PairsExpectedFromSpread(baseline, candidate, contended), 96);
    // No noise: the next look (the one at the pairs so far is the caller's, already decided),
    // after a probe's 10 pairs the first at 20.
    const auto [quiet_baseline, quiet_candidate] = PairsWithSpread(10, 1.10, 0.0);
    EXPECT_EQ(PairsExpectedFromSpread(quiet_baseline, quiet_candidate, contended), 20);
}

TEST(PairedEstimateTest, TooFewOrUnusablePairsGiveNoGuessFromTheSpread) {
    const StoppingRule rule;
    const auto [baseline, candidate] = PairsWithSpread(20, 1.10, 5.0);
    EXPECT_EQ(PairsExpectedFromSpread({baseline.begin(), baseline.begin() + 9},
                                      {candidate.begin(), candidate.begin() + 9}, rule),
              0);
    EXPECT_EQ(PairsExpectedFromSpread(baseline, {candidate.begin(), candidate.end() - 1}, rule), 0);
    std::vector<double> broken = candidate;
    broken[3] = 0.0;
    EXPECT_EQ(PairsExpectedFromSpread(baseline, broken, rule), 0);
    broken[3] = std::nan("");
    EXPECT_EQ(PairsExpectedFromSpread(baseline, broken, rule), 0);
}

TEST(PairedEstimateTest, TheProgressGuessIsTheGeometricMeanOfTheIntervalsAndTheSpreads) {
    StoppingRule rule;
    rule.contended_share = 0.5;
    // A stated interval far wider than the pairs' own spread (as when ten contended pairs hold a
    // disturbed one): the interval alone guesses long, the spread short, and the guess lies
    // between, at their geometric mean.
    const auto [baseline, candidate] = PairsWithSpread(20, 1.10, 2.0);
    const PairedEstimate wide = EstimateWithInterval(20, -15.0, -3.0);
    const int from_interval = PairsExpectedAtStop(wide, rule, 60);
    const int from_spread = PairsExpectedFromSpread(baseline, candidate, rule);
    ASSERT_GT(from_interval, from_spread);
    const int guess = PairsExpectedFromPairs(baseline, candidate, wide, rule, 60);
    EXPECT_EQ(guess, std::lround(std::sqrt(static_cast<double>(from_interval) * from_spread)));
    EXPECT_GT(guess, from_spread);
    EXPECT_LT(guess, from_interval);
    // A comparison the rule stops now: its pairs, whatever the spread says.
    const PairedEstimate done = EstimateWithInterval(20, -9.8, -8.4);
    ASSERT_NE(DecideStop(done, rule), StopDecision::kContinue);
    EXPECT_EQ(PairsExpectedFromPairs(baseline, candidate, done, rule, 60), 20);
    // Too few pairs for a spread: the interval's guess alone.
    EXPECT_EQ(PairsExpectedFromPairs({baseline.begin(), baseline.begin() + 5},
                                     {candidate.begin(), candidate.begin() + 5}, wide, rule, 60),
              from_interval);
    // A probe's ten pairs, fewer than the rule's first look takes: the spread's guess alone
    // (AProbesGuessFollowsTheRulesStopsOnHeavyTailedNoise says why).
    const std::vector<double> probe_baseline(baseline.begin(), baseline.begin() + 10);
    const std::vector<double> probe_candidate(candidate.begin(), candidate.begin() + 10);
    const int probe_spread = PairsExpectedFromSpread(probe_baseline, probe_candidate, rule);
    ASSERT_GT(probe_spread, 0);
    const PairedEstimate probe_wide = EstimateWithInterval(10, -15.0, -3.0);
    ASSERT_NE(PairsExpectedAtStop(probe_wide, rule, 60), probe_spread);
    EXPECT_EQ(PairsExpectedFromPairs(probe_baseline, probe_candidate, probe_wide, rule, 60),
              probe_spread);
}

// The guess at a comparison's first look against where the rule then stops, over simulated runs
// with a known effect near row 4's band edge (+7%), at a noise where 20 pairs give a half-width
// of about a point: the progress line's ETA adds these guesses, so their mean must follow the
// mean stop, although a single comparison's stop may lie anywhere from 20 pairs to the cap.
TEST(PairedEstimateTest, ExpectedPairsAtTheFirstLookFollowTheRulesStops) {
    StoppingRule row;
    row.boundaries_points = {1.75, 7.0};
    constexpr int kRuns = 60;  // slow under the sanitizers
    double guessed = 0;
    double stopped = 0;
    for (int run = 0; run < kRuns; ++run) {
        // The effect: +6.0% to +9.0% across the runs, the edge inside that range.
        const double change = 6.0 + 3.0 * run / (kRuns - 1);
        FrameNoise noise(static_cast<std::uint64_t>(11000 + run), 0.016);
        std::vector<double> a;
        std::vector<double> b;
        int first_guess = 0;
        for (;;) {
            const int batch = PairsBeforeNextLook(static_cast<int>(a.size()), row);
            for (int k = 0; k < batch; ++k) {
                const auto [x, y] =
                        noise.NextPair(1.0 / (1.0 + change / 100.0), static_cast<int>(a.size()));
                a.push_back(x);
                b.push_back(y);
            }
            const PairedEstimate e = EstimatePaired(a, b);
            if (first_guess == 0) {
                first_guess = PairsExpectedAtStop(e, row, 60);
            }
            if (DecideStop(e, row) != StopDecision::kContinue) {
                stopped += e.pairs;
                break;
            }
        }
        guessed += first_guess;
    }
    std::printf("first looks guessed %.0f pairs on average; the rule stopped at %.0f\n",
                guessed / kRuns, stopped / kRuns);
    EXPECT_GT(stopped / kRuns, 2.0 * row.min_pairs) << "the edge should cost pairs here";
    EXPECT_NEAR(guessed / stopped, 1.0, 0.3);
}

// Frame times whose noise has heavy tails, as on the 2-core host of 2026-12-07: a core (log
// standard deviation 2.5% a frame) and, in one frame of 8, a slowdown of 12% on average and up
// to a half (an interrupt, another guest on the core). The pairs' standard deviation is then
// about twice their normal-equivalent median absolute deviation; that host's main-job pairs
// measured 1.5 to 4 times.
class HeavyTailedNoise {
public:
    explicit HeavyTailedNoise(std::uint64_t seed) : random_(seed) {}

    std::pair<double, double> NextPair(double ratio) {
        const double a = 20.0 * std::exp(Next());
        const double b = 20.0 * ratio * std::exp(Next());
        return {a, b};
    }

private:
    double Next() {
        double value = 0.025 * normal_(random_);
        if (uniform_(random_) < 1.0 / 8) {
            value += std::abs(0.15 * normal_(random_));
        }
        return value;
    }

    std::mt19937_64 random_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

// A probe's guess against where the rule then stops, over simulated comparisons with effects
// from -5% to +1% (the direction margin at -1.5 inside) on heavy-tailed noise. The progress line
// adds these guesses, so their mean must follow the mean stop. A rank interval from ten such
// pairs reaches into the tails, where from more pairs it reaches into the core only: guessed
// from it by the square-root law, the probe's guess is about a third too long here (over eight
// main-job halves of 2026-12-07, the probes' guesses summed missed the comparisons' work by a
// median 59%, at most 101%); from the pairs' spread it follows them.
TEST(PairedEstimateTest, AProbesGuessFollowsTheRulesStopsOnHeavyTailedNoise) {
    const StoppingRule rule;  // resolution 1.5, 20 to 400 pairs, as run only
    constexpr int kRuns = 60;
    double guessed = 0;
    double from_interval = 0;
    double stopped = 0;
    for (int run = 0; run < kRuns; ++run) {
        const double change = -5.0 + 6.0 * run / (kRuns - 1);
        HeavyTailedNoise noise(static_cast<std::uint64_t>(27000 + run));
        std::vector<double> a;
        std::vector<double> b;
        for (;;) {
            const int batch = a.size() < static_cast<std::size_t>(kMinimumPairs)
                                      ? kMinimumPairs
                                      : PairsBeforeNextLook(static_cast<int>(a.size()), rule);
            for (int k = 0; k < batch; ++k) {
                const auto [x, y] = noise.NextPair(1.0 / (1.0 + change / 100.0));
                a.push_back(x);
                b.push_back(y);
            }
            const PairedEstimate e = EstimatePaired(a, b);
            if (a.size() == static_cast<std::size_t>(kMinimumPairs)) {  // the probe
                const ExpectedPairs guess =
                        PairsExpectedAcrossStates(a, b, {}, {}, e, PairedEstimate{}, rule, 60);
                guessed += guess.as_run + guess.contended;
                const std::vector<double> steadied = WithOuterRatiosPulledIn(a, b);
                from_interval += PairsExpectedAtStop(EstimatePaired(a, steadied), rule, 60);
                continue;
            }
            if (DecideStop(e, rule) != StopDecision::kContinue) {
                stopped += e.pairs;
                break;
            }
        }
    }
    std::printf(
            "probes guessed %.0f pairs on average (%.0f from their intervals); the rule "
            "stopped at %.0f\n",
            guessed / kRuns, from_interval / kRuns, stopped / kRuns);
    EXPECT_GT(stopped / kRuns, 2.0 * rule.min_pairs) << "the noise should cost pairs here";
    EXPECT_NEAR(guessed / stopped, 1.0, 0.2);
    EXPECT_GT(from_interval / stopped, 1.2) << "the noise should have tails that mislead a probe";
}

// Ten pairs whose log ratios are `centre` plus `offsets` (in log units), baselines 20 ms.
std::pair<std::vector<double>, std::vector<double>> PairsWithOffsets(
        double centre, const std::vector<double>& offsets) {
    std::vector<double> baseline(offsets.size(), 20.0);
    std::vector<double> candidate;
    for (double o : offsets) {
        candidate.push_back(20.0 * std::exp(centre + o));
    }
    return {baseline, candidate};
}

TEST(PairedEstimateTest, ASpreadIsPulledInAboutItsMedian) {
    const std::vector<double> offsets = {-0.03, -0.02, -0.01, -0.005, 0.0,
                                         0.0,   0.005, 0.01,  0.02,   0.04};
    const auto [baseline, candidate] = PairsWithOffsets(0.1, offsets);
    const double spread = LogRatioSpread(baseline, candidate);
    EXPECT_NEAR(spread, 1.4826 * 0.01, 1e-9);  // deviations' median: 0.01
    const std::vector<double> pulled = WithSpreadAtMost(baseline, candidate, spread / 4);
    EXPECT_NEAR(LogRatioSpread(baseline, pulled), spread / 4, 1e-9);
    EXPECT_NEAR(EstimatePaired(baseline, pulled).ratio, std::exp(0.1), 1e-6);
    for (std::size_t i = 0; i < pulled.size(); ++i) {
        EXPECT_NEAR(std::log(pulled[i] / baseline[i]), 0.1 + offsets[i] / 4, 1e-9) << i;
    }
    // At most what it is already, or no bound: as given.
    EXPECT_EQ(WithSpreadAtMost(baseline, candidate, spread * 2), candidate);
    EXPECT_EQ(WithSpreadAtMost(baseline, candidate, std::nan("")), candidate);
    // Too few pairs for a spread.
    EXPECT_TRUE(std::isnan(LogRatioSpread({20, 20}, {21, 22})));
    EXPECT_EQ(WithSpreadAtMost({20, 20}, {21, 22}, 0.0), (std::vector<double>{21, 22}));
}

// A probe whose ten pairs are disturbed, among calm ones, is guessed from pairs pulled in to
// three times the calm ones' spread: row 11's probe in a traced main job of 2026-12-07 had log
// ratios from -33% to +40%, where the median probe's spread was 1.3%, and guessed 1,214 frames for
// a comparison that took 174.
TEST(PairedEstimateTest, ADisturbedProbesGuessIsPulledInTowardsTheCalmOnes) {
    StoppingRule rule;
    rule.contended_share = 0.5;
    const std::vector<double> calm = {-0.015, -0.01, -0.006, -0.003, 0.0,
                                      0.0,    0.003, 0.006,  0.01,   0.015};
    const std::vector<double> disturbed = {-0.33, -0.21, -0.17, -0.06, -0.04,
                                           0.04,  0.06,  0.11,  0.26,  0.40};
    ProbeSpreads spreads;
    auto probe = [&](const std::vector<double>& as_run, const std::vector<double>& contended) {
        const auto [b, c] = PairsWithOffsets(-0.04, as_run);
        const auto [cb, cc] = PairsWithOffsets(-0.04, contended);
        return std::make_pair(UndisturbedProbe(b, c, cb, cc, spreads), std::array{b, c, cb, cc});
    };
    // The first probes set no bound, however they read.
    const auto first = probe(disturbed, calm);
    EXPECT_EQ(first.first.as_run, first.second[1]);
    spreads = ProbeSpreads{};
    probe(calm, calm);
    probe(calm, calm);
    // The third, calm, is its own.
    const auto third = probe(calm, calm);
    EXPECT_EQ(third.first.as_run, third.second[1]);
    EXPECT_EQ(third.first.contended, third.second[3]);
    // Now a disturbed as-run state is pulled in to three times the median spread, and its guess
    // falls from the cap towards a calm probe's; its contended state, calm, stays.
    const auto pulled = probe(disturbed, calm);
    const ProbeCandidates& candidates = pulled.first;
    const auto& pairs = pulled.second;
    const double median = Median(spreads.as_run);
    EXPECT_NEAR(LogRatioSpread(pairs[0], candidates.as_run), kDisturbedProbeSpread * median, 1e-9);
    EXPECT_EQ(candidates.contended, pairs[3]);
    auto guess = [&](const std::vector<double>& as_run_candidate) {
        const ExpectedPairs e =
                PairsExpectedAcrossStates(pairs[0], as_run_candidate, pairs[2], pairs[3],
                                          EstimatePaired(pairs[0], as_run_candidate),
                                          EstimatePaired(pairs[2], pairs[3]), rule, 60);
        return e.as_run + e.contended;
    };
    const int raw = guess(pairs[1]);
    const int undisturbed = guess(candidates.as_run);
    const int calm_guess = guess(third.second[1]);
    std::printf("disturbed probe guessed %d pairs as it read, %d pulled in; a calm one %d\n", raw,
                undisturbed, calm_guess);
    EXPECT_EQ(raw, rule.max_pairs + ContendedPairsBeforeNextLook(rule.max_pairs, 0, rule));
    EXPECT_GT(raw, 4 * undisturbed);
    EXPECT_GE(undisturbed, calm_guess);
}

TEST(PairedEstimateTest, ProbesGoFromBothEndsOfTheListInTurn) {
    EXPECT_EQ(ProbeOrder(5), (std::vector<std::size_t>{0, 4, 1, 3, 2}));
    EXPECT_EQ(ProbeOrder(4), (std::vector<std::size_t>{0, 3, 1, 2}));
    EXPECT_EQ(ProbeOrder(1), (std::vector<std::size_t>{0}));
    EXPECT_TRUE(ProbeOrder(0).empty());
}

}  // namespace
}  // namespace tidepool::base
