#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "RenderProgress.h"

namespace tidepool::runner {
namespace {

using Clock = ProgressMeter::Clock;

// Where each kind of unit lies in an order: the positions of probes, of whole or rest
// comparisons, and of configurations.
struct UnitPositions {
    std::vector<std::size_t> probes;
    std::vector<std::size_t> comparisons;
    std::vector<std::size_t> configurations;
    std::set<std::size_t> probed;    // comparison indices with a probe
    std::set<std::size_t> compared;  // comparison indices with a rest unit
    std::set<std::size_t> configured;
};

UnitPositions PositionsOf(const std::vector<WorkUnit>& units) {
    UnitPositions p;
    for (std::size_t u = 0; u < units.size(); ++u) {
        if (units[u].comparison && units[u].probe) {
            p.probes.push_back(u);
            EXPECT_TRUE(p.probed.insert(units[u].index).second) << "probe twice: " << u;
        } else if (units[u].comparison) {
            p.comparisons.push_back(u);
            EXPECT_TRUE(p.compared.insert(units[u].index).second) << "comparison twice: " << u;
        } else {
            p.configurations.push_back(u);
            EXPECT_TRUE(p.configured.insert(units[u].index).second) << "configuration twice: " << u;
        }
    }
    return p;
}

// Every comparison's probe comes before every comparison's rest, and every comparison before the
// configurations that no comparison times: the progress line learns which comparisons will be long
// within seconds, and the queue a second process takes from the end holds short units only.
TEST(RenderProgressTest, ProbesComeFirstAndTheQueueEndsOnConfigurations) {
    const std::vector<std::size_t> early = {7, 3, 9, 11};
    const std::vector<WorkUnit> units = RenderWorkOrder(16, 147, 42, early, true);
    ASSERT_EQ(units.size(), 2 * 16U + 147U);
    const UnitPositions p = PositionsOf(units);
    EXPECT_EQ(p.probed.size(), 16U);
    EXPECT_EQ(p.compared.size(), 16U);
    EXPECT_EQ(p.configured.size(), 147U);
    // The reference, then the probes from both ends of the list in turn, then the early
    // configurations, then the rest of every comparison in order.
    ASSERT_FALSE(units[0].comparison);
    EXPECT_EQ(units[0].index, 42U);
    const std::array<std::size_t, 16> probe_order = {0, 15, 1, 14, 2, 13, 3, 12,
                                                     4, 11, 5, 10, 6, 9,  7, 8};
    for (std::size_t k = 0; k < 16; ++k) {
        EXPECT_EQ(p.probes[k], 1 + k);
        EXPECT_EQ(units[p.probes[k]].index, probe_order[k]);
        EXPECT_EQ(units[p.comparisons[k]].index, k);
    }
    for (std::size_t e = 0; e < early.size(); ++e) {
        EXPECT_FALSE(units[17 + e].comparison);
        EXPECT_EQ(units[17 + e].index, early[e]);
    }
    EXPECT_EQ(p.comparisons.front(), 17 + early.size());
    EXPECT_EQ(p.comparisons.back(), 16 + early.size() + 16);
    for (std::size_t u = p.comparisons.back() + 1; u < units.size(); ++u) {
        EXPECT_FALSE(units[u].comparison) << u;
    }
}

TEST(RenderProgressTest, WithoutProbesEachComparisonComesOnceBeforeTheOtherConfigurations) {
    const std::vector<WorkUnit> units = RenderWorkOrder(16, 147, 42, {7, 3});
    ASSERT_EQ(units.size(), 16U + 147U);
    const UnitPositions p = PositionsOf(units);
    EXPECT_TRUE(p.probes.empty());
    EXPECT_EQ(p.compared.size(), 16U);
    EXPECT_EQ(p.configured.size(), 147U);
    EXPECT_EQ(units[0].index, 42U);
    EXPECT_EQ(units[1].index, 7U);
    EXPECT_EQ(units[2].index, 3U);
    EXPECT_EQ(p.comparisons.front(), 3U);
    EXPECT_EQ(p.comparisons.back(), 18U);
    EXPECT_FALSE(units.back().comparison);
}

// An early configuration named twice, the reference among them, or one past the matrix, is
// rendered once or not at all.
TEST(RenderProgressTest, EachConfigurationRendersOnceWhateverTheEarlyListSays) {
    const std::vector<std::size_t> early = {7, 3, 42, 7, 200};  // 42 is the reference, 200 none
    const std::vector<WorkUnit> units = RenderWorkOrder(16, 147, 42, early, true);
    ASSERT_EQ(units.size(), 2 * 16U + 147U);
    const UnitPositions p = PositionsOf(units);
    EXPECT_EQ(p.configured.size(), 147U);
    EXPECT_EQ(p.configured.count(200), 0U);
    EXPECT_EQ(units[0].index, 42U);
    EXPECT_EQ(units[17].index, 7U);
    EXPECT_EQ(units[18].index, 3U);
    EXPECT_TRUE(units[19].comparison);
}

TEST(RenderProgressTest, WithoutComparisonsEveryConfigurationIsStillThere) {
    const std::vector<WorkUnit> units = RenderWorkOrder(0, 5);
    ASSERT_EQ(units.size(), 5U);
    std::set<std::size_t> seen;
    for (const WorkUnit& unit : units) {
        EXPECT_FALSE(unit.comparison);
        seen.insert(unit.index);
    }
    EXPECT_EQ(seen.size(), 5U);
    EXPECT_EQ(RenderWorkOrder(3, 1).size(), 4U);
}

// One thread renders 100 ms frames for a minute, then the machine frees up and frames take
// 50 ms. Half a minute later the ETA must reflect the new rate: the average over the whole run
// (75 ms) would put it 50% late.
TEST(RenderProgressTest, EtaFollowsTheRecentRateAfterTheMachineFreesUp) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    constexpr long kTotal = 3000;
    meter.AddExpected(ProgressMeter::kImage, kTotal);
    Clock::time_point now = start;
    long done = 0;
    for (int i = 0; i < 600; ++i, ++done) {
        now += std::chrono::milliseconds(100);
        meter.Step(ProgressMeter::kImage, "slow", 1, now);
    }
    for (int i = 0; i < 600; ++i, ++done) {
        now += std::chrono::milliseconds(50);
        meter.Step(ProgressMeter::kImage, "fast", 1, now);
    }
    const double truth = 0.050 * static_cast<double>(kTotal - done);
    const RunProgress progress = meter.Last();
    EXPECT_NEAR(progress.eta_seconds, truth, 0.2 * truth);
    EXPECT_EQ(progress.done, done);
    EXPECT_NEAR(progress.elapsed_seconds, 90.0, 1e-6);
}

// Before any image is measured, images cost what a timed frame costs; once images are measured,
// their own rate takes over.
TEST(RenderProgressTest, ImagesBorrowTheComparisonRateUntilTheirOwnIsMeasured) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    meter.AddExpected(ProgressMeter::kImage, 1000);
    meter.AddComparisons(1, 100);
    Clock::time_point now = start;
    for (int i = 0; i < 50; ++i) {
        now += std::chrono::milliseconds(40);
        meter.Step(ProgressMeter::kComparison, "row", 1, now);
    }
    // 50 comparison frames and 1000 image frames left, all at 40 ms.
    EXPECT_NEAR(meter.Last().eta_seconds, 0.040 * 1050, 0.01 * 0.040 * 1050);
    for (int i = 0; i < 400; ++i) {
        now += std::chrono::milliseconds(120);
        meter.Step(ProgressMeter::kImage, "image", 1, now);
    }
    // 600 image frames left at about 120 ms, 50 comparison frames at about 40 ms (both shrunk a
    // little towards each other).
    const double truth = 0.120 * 600 + 0.040 * 50;
    EXPECT_NEAR(meter.Last().eta_seconds, truth, 0.1 * truth);
}

// Once configurations have a cost, images not yet measured are priced at kImageFrameCost times
// their mean, not at the comparisons' rate (whose contended frames cost more than a frame); the
// images' own frames then take over.
TEST(RenderProgressTest, ImagesArePricedFromTheConfigurationsCostsUntilTheirOwnIsMeasured) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    meter.AddExpected(ProgressMeter::kImage, 1000);
    meter.AddComparisons(1, 100);
    meter.ConfigurationCost(0, 0.030);
    meter.ConfigurationCost(1, 0.050);
    Clock::time_point now = start;
    for (int i = 0; i < 100; ++i) {
        now += std::chrono::milliseconds(60);  // comparison frames at 60 ms, contended ones too
        meter.Step(ProgressMeter::kComparison, "row", 1, now);
    }
    // 1000 image frames at 1.3 x 40 ms (the mean cost), no comparison frames left.
    const double priced = ProgressMeter::kImageFrameCost * 0.040 * 1000;
    EXPECT_NEAR(meter.Last().eta_seconds, priced, 0.01 * priced);
    for (int i = 0; i < 400; ++i) {
        now += std::chrono::milliseconds(120);
        meter.Step(ProgressMeter::kImage, "image", 1, now);
    }
    // 600 image frames left at about 120 ms (shrunk a little towards the prior).
    const double truth = 0.120 * 600;
    EXPECT_NEAR(meter.Last().eta_seconds, truth, 0.1 * truth);
}

// Comparisons not started expect the mean of what the finished ones took, the first guess
// counting as kPriorComparisons of them: one that needed 300 pairs near a verdict's boundary
// moves every later one by its share only.
TEST(RenderProgressTest, WaitingComparisonsExpectTheShrunkMeanOfTheFinishedOnes) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    constexpr double kPrior = ProgressMeter::kPriorComparisons;
    meter.AddComparisons(6, 120);  // 6 comparisons, 120 frames each until they say otherwise
    meter.ComparisonExpects(0, 40, true);
    meter.ComparisonExpects(1, 600, true);
    meter.ComparisonExpects(2, 40, true);
    meter.Step(ProgressMeter::kComparison, "row", 680, start + std::chrono::seconds(34));
    // Finished: 40 + 600 + 40 frames; the three waiting expect (k x 120 + 680) / (k + 3),
    // between the guess and the plain mean 227.
    const long first = std::lround((kPrior * 120 + 680) / (kPrior + 3));
    EXPECT_GT(first, 120);
    EXPECT_LT(first, 227);
    EXPECT_EQ(meter.Last().total, 40 + 600 + 40 + 3 * first);
    // A first guess (comparison 3's, 400 frames) is the guess the waiting ones shrink towards.
    meter.ComparisonExpects(3, 400, false);
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(35));
    const long second = std::lround((kPrior * 400 + 680) / (kPrior + 3));
    EXPECT_EQ(meter.Last().total, 40 + 600 + 40 + 400 + 2 * second);
    // It finishes at 40: one more finished comparison in the mean.
    meter.ComparisonExpects(3, 40, true);
    meter.Step(ProgressMeter::kComparison, "row", 40, start + std::chrono::seconds(36));
    const long third = std::lround((kPrior * 400 + 720) / (kPrior + 4));
    EXPECT_LT(third, second);
    EXPECT_EQ(meter.Last().total, 40 + 600 + 40 + 40 + 2 * third);
}

// Once comparisons have looked, the waiting ones start from the mean of their first guesses, not
// from AddComparisons' guess: a host where 20 pairs suffice is not charged 60.
TEST(RenderProgressTest, WaitingComparisonsStartFromTheMeanOfTheFirstGuesses) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    meter.AddComparisons(4, 120);  // 60 pairs each until a look says otherwise
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(1));
    EXPECT_EQ(meter.Last().total, 4 * 120);
    // Comparison 0's probe guesses 54 frames.
    meter.ComparisonExpects(0, 54, false);
    meter.Step(ProgressMeter::kComparison, "row", 20, start + std::chrono::seconds(2));
    EXPECT_EQ(meter.Last().total, 54 + 3 * 54);
    // Comparison 1's probe guesses 300 (an effect near a verdict's boundary): the waiting ones
    // expect the mean of the two.
    meter.ComparisonExpects(1, 300, false);
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(3));
    EXPECT_EQ(meter.Last().total, 54 + 300 + 2 * 177);
    // A later look's guess is that comparison's own: the waiting ones keep the first guesses'
    // mean.
    meter.ComparisonExpects(1, 600, false);
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(4));
    EXPECT_EQ(meter.Last().total, 54 + 600 + 2 * 177);
    // Comparison 0 finishes at 60: the waiting ones shrink towards it from the guess.
    meter.ComparisonExpects(0, 60, true);
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(5));
    constexpr double kPrior = ProgressMeter::kPriorComparisons;
    const long expected = std::lround((kPrior * 177 + 60) / (kPrior + 1));
    EXPECT_EQ(meter.Last().total, 60 + 600 + 2 * expected);
    // A comparison that failed before it timed says nothing about the others.
    meter.ComparisonExpects(2, 0, true);
    meter.Step(ProgressMeter::kComparison, "row", 0, start + std::chrono::seconds(6));
    EXPECT_EQ(meter.Last().total, 60 + 600 + 0 + expected);
}

// Gives `meter` one comparison per pair of configurations, 100 frames each until they say
// otherwise, and configurations 0, 1, ... the costs in `seconds`.
void PriceComparisons(ProgressMeter& meter,
                      const std::vector<std::array<std::size_t, 2>>& comparisons,
                      const std::vector<double>& seconds) {
    meter.AddComparisons(comparisons.size(), 100);
    for (std::size_t k = 0; k < comparisons.size(); ++k) {
        meter.ComparisonConfigurations(k, comparisons[k][0], comparisons[k][1]);
    }
    for (std::size_t i = 0; i < seconds.size(); ++i) {
        meter.ConfigurationCost(i, seconds[i]);
    }
}

// Comparisons whose configurations have a cost are priced by it: a comparison of 80 ms frames
// waiting behind one of 40 ms frames is not charged the 40 ms the first one measured.
TEST(RenderProgressTest, ComparisonsArePricedByTheirConfigurationsCosts) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    PriceComparisons(meter, {{0, 1}, {2, 3}}, {0.040, 0.040, 0.060, 0.100});
    Clock::time_point now = start;
    for (int f = 0; f < 50; ++f) {
        now += std::chrono::milliseconds(40);
        meter.StepComparison(0, "cheap", 1, now);
    }
    // 50 frames of comparison 0 left at 40 ms, 100 of comparison 1 at (60 + 100) / 2 = 80 ms;
    // the calibration is 1 (frames took their price).
    EXPECT_NEAR(meter.Last().eta_seconds, 50 * 0.040 + 100 * 0.080, 1e-6);
    // The recent rate alone would have said 150 x 40 ms.
    EXPECT_GT(meter.Last().eta_seconds, 1.5 * 150 * 0.040);
}

// Comparison frames that take longer than their configurations' coarse frames (contended
// frames share a core) raise every price by the same ratio; a comparison whose configurations have
// no cost yet takes the recent rate.
TEST(RenderProgressTest, ThePriceFollowsWhatComparisonFramesTookAgainstTheirCost) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    PriceComparisons(meter, {{0, 1}, {2, 3}, {4, 5}}, {0.040, 0.040, 0.080, 0.080});  // 4, 5: none
    Clock::time_point now = start;
    for (int f = 0; f < 100; ++f) {
        now += std::chrono::milliseconds(60);  // 1.5 times the price
        meter.StepComparison(0, "row", 1, now);
    }
    meter.ComparisonExpects(0, 100, true);
    meter.StepComparison(0, "row", 0, now);
    // The calibration: about (6 s + 2 s of prior) / (4 s + 2 s) = 1.33 (less a little, as
    // the sums age); comparison 1 is priced at 80 ms x 1.33, comparison 2 at the recent rate,
    // 60 ms.
    const double calibration = (6.0 + 2.0) / (4.0 + 2.0);
    const double eta = 100 * 0.080 * calibration + 100 * 0.060;
    EXPECT_NEAR(meter.Last().eta_seconds, eta, 0.02 * eta);
    // Ignored: costs that are not a positive time. With 5's cost known, any accepted cost of 4
    // would price comparison 2.
    meter.ConfigurationCost(5, 0.080);
    for (double bad : {0.0, -0.040, std::nan(""), std::numeric_limits<double>::infinity()}) {
        meter.ConfigurationCost(4, bad);
        meter.StepComparison(0, "row", 0, now);
        EXPECT_NEAR(meter.Last().eta_seconds, eta, 0.02 * eta) << bad;
    }
    // A real one does.
    meter.ConfigurationCost(4, 0.080);
    meter.StepComparison(0, "row", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 200 * 0.080 * calibration, 0.02 * eta);
}

// Before a comparison frame has been priced, comparisons are priced at their configurations'
// cost times the prior (their contended frames cost more than a frame); measured frames then
// take over from it.
TEST(RenderProgressTest, UntilComparisonFramesAreMeasuredTheirPriceCarriesThePrior) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    PriceComparisons(meter, {{0, 1}}, {0.040, 0.040});
    meter.ComparisonCostPrior(ContendedFramesCost(0.5));
    // Ignored: priors that are not a positive ratio.
    for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        meter.ComparisonCostPrior(bad);
    }
    meter.Step(ProgressMeter::kImage, "image", 1, start + std::chrono::milliseconds(40));
    const double prior = (1 + 0.5 * (1 + kDefaultCoreShare)) / 1.5;
    EXPECT_NEAR(meter.Last().eta_seconds, 100 * 0.040 * prior, 1e-6);
    // 50 s of frames that took exactly their price outweigh the prior's 2 s.
    Clock::time_point now = start;
    for (int f = 0; f < 50; ++f) {
        now += std::chrono::milliseconds(40);
        meter.StepComparison(0, "row", 1, now);
    }
    const double calibration = (50 * 0.040 + 2 * prior) / (50 * 0.040 + 2);
    EXPECT_NEAR(meter.Last().eta_seconds, 50 * 0.040 * calibration, 0.02);
    EXPECT_LT(meter.Last().eta_seconds, 50 * 0.040 * prior - 0.1);
}

// After its last look a comparison still renders its per-pass frames: they stay in the ETA
// and the total until they are done, and the comparison ends with none left.
TEST(RenderProgressTest, AComparisonPastItsLastLookStillExpectsItsPerPassFrames) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    PriceComparisons(meter, {{0, 1}}, {0.040, 0.040});
    Clock::time_point now = start;
    for (int f = 0; f < 60; ++f) {
        now += std::chrono::milliseconds(40);
        meter.StepComparison(0, "row", 1, now);
    }
    meter.ComparisonExpects(0, 60 + 10, false);  // the last look: 10 per-pass frames to come
    meter.StepComparison(0, "row", 0, now);
    EXPECT_EQ(meter.Last().total, 70);
    EXPECT_NEAR(meter.Last().eta_seconds, 10 * 0.040, 0.01);
    now += std::chrono::milliseconds(400);
    meter.StepComparison(0, "row", 10, now);
    meter.ComparisonExpects(0, 70, true);
    meter.StepComparison(0, "row", 0, now);
    EXPECT_EQ(meter.Last().done, 70);
    EXPECT_EQ(meter.Last().total, 70);
    EXPECT_DOUBLE_EQ(meter.Last().eta_seconds, 0.0);
}

// A contended frame adds a process to its core: with the render thread getting all of its core
// it takes twice an as-run frame's wall time, with half of it 1.5 times. No contended pairs cost
// what the as-run ones do; a core share outside (0, 1] gives way to the default.
TEST(RenderProgressTest, ContendedFramesCostMoreTheMoreOfItsCoreTheRenderHad) {
    EXPECT_DOUBLE_EQ(ContendedFramesCost(0, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(ContendedFramesCost(-1, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(ContendedFramesCost(1, 1.0), 1.5);
    EXPECT_DOUBLE_EQ(ContendedFramesCost(1, 0.5), 1.25);
    EXPECT_DOUBLE_EQ(ContendedFramesCost(0.5, 1.0), 2.0 / 1.5);
    EXPECT_DOUBLE_EQ(ContendedFramesCost(0.5), ContendedFramesCost(0.5, kDefaultCoreShare));
    for (double bad : {0.0, -0.5, 1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
        EXPECT_DOUBLE_EQ(ContendedFramesCost(0.5, bad), ContendedFramesCost(0.5)) << bad;
    }
}

// Alone until the second process joins, then the rest split by threads: one thread here and
// one there halve what is left at the join.
TEST(RenderProgressTest, SecondsToFinishShareWhatIsLeftOnceTheSecondProcessJoins) {
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, std::nullopt), 60);
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 2, std::nullopt), 30);
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, 0.0), 30);
    // 20 s alone, then the 40 s left shared: 20 s more.
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, 20.0), 40);
    // Two threads here: 40 s of work in the first 20 s, the 20 s left shared three ways.
    EXPECT_NEAR(SecondsToFinish(60, 2, 20.0), 20 + 20.0 / 3, 1e-9);
    // Done before it joins.
    EXPECT_DOUBLE_EQ(SecondsToFinish(10, 1, 20.0), 10);
    // A join forecast in the past counts as now; no work is no time.
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, -5.0), 30);
    EXPECT_DOUBLE_EQ(SecondsToFinish(0, 1, 0.0), 0);
    // 60 s left 20 s before the join, 50 s of it this process's own: shared, the end would be
    // 40 s, but the second process has only 10 s it may take, so this process's 50 s set it.
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, 20.0, 50.0), 50);
    // With 20 s of its own, sharing the 40 s left at the join still ends first at 40 s.
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 1, 20.0, 20.0), 40);
    // Without a second process, what is its own changes nothing.
    EXPECT_DOUBLE_EQ(SecondsToFinish(60, 2, std::nullopt, 60.0), 30);
    // Never more than working alone, never less than half of it with one thread each.
    for (double work : {0.0, 1.0, 100.0}) {
        for (double join : {0.0, 1.0, 50.0, 500.0}) {
            EXPECT_LE(SecondsToFinish(work, 1, join), work);
            EXPECT_GE(SecondsToFinish(work, 1, join), work / 2);
        }
    }
}

// A claim table of `configurations` configurations and two comparisons, shared with `meter`,
// which expects `frames_per_unit` image frames per configuration.
std::unique_ptr<base::SharedClaims> ShareWithSecondProcess(ProgressMeter& meter,
                                                           std::size_t configurations,
                                                           long frames_per_unit) {
    std::unique_ptr<base::SharedClaims> claims = base::SharedClaims::Create(configurations + 2);
    if (claims) {
        meter.AddExpected(ProgressMeter::kImage,
                          static_cast<long>(configurations) * frames_per_unit);
        meter.ShareUnits(claims.get(), frames_per_unit, configurations);
    }
    return claims;
}

// This process claims configuration 0 and renders its `frames` image frames at 100 ms each from
// `start`; returns the time after the last.
Clock::time_point RenderConfigurationZero(ProgressMeter& meter, base::SharedClaims& claims,
                                          Clock::time_point start, long frames) {
    EXPECT_TRUE(claims.ClaimForOwner(0));
    Clock::time_point now = start;
    for (long f = 0; f < frames; ++f) {
        now += std::chrono::milliseconds(100);
        meter.Step(ProgressMeter::kImage, "0", 1, now);
    }
    return now;
}

// A meter that shares ten configurations of 7 image frames and two comparisons of 70 frames with
// a second process, after this process rendered configuration 0 at 100 ms a frame.
struct TenConfigurationsAndTwoComparisons {
    static constexpr std::size_t kConfigurations = 10;
    static constexpr long kFramesPerUnit = 7;
    TenConfigurationsAndTwoComparisons() {
        meter.AddComparisons(2, 70);
        claims = ShareWithSecondProcess(meter, kConfigurations, kFramesPerUnit);
        if (claims) {
            now = RenderConfigurationZero(meter, *claims, start, kFramesPerUnit);
        }
    }
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter{none, start};
    std::unique_ptr<base::SharedClaims> claims;
    Clock::time_point now;
};

// The units a second process claims, configurations' and comparisons' alike, leave the meter's
// totals; before it joins the ETA counts on it from the time it said, while it takes units from
// now, and once it has stopped not at all.
TEST(RenderProgressTest, UnitsASecondProcessTakesLeaveTheTotalsAndShortenTheEta) {
    TenConfigurationsAndTwoComparisons run;
    ASSERT_TRUE(run.claims);
    ProgressMeter& meter = run.meter;
    base::SharedClaims* const claims = run.claims.get();
    const Clock::time_point now = run.now;
    constexpr std::size_t kConfigurations = TenConfigurationsAndTwoComparisons::kConfigurations;
    constexpr long kFramesPerUnit = TenConfigurationsAndTwoComparisons::kFramesPerUnit;
    // Alone: 9 units of 7 frames and 2 comparisons of 70 frames, all at 100 ms a frame.
    EXPECT_EQ(meter.Last().total, 10 * kFramesPerUnit + 140);
    EXPECT_NEAR(meter.Last().eta_seconds, 6.3 + 14, 1e-6);
    // The helper says it joins in 4.3 s: 4.3 s alone, then the 16 s left are halved.
    claims->ExpectHelperAt(now + std::chrono::milliseconds(4300));
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 4.3 + 8, 1e-3);
    ASSERT_TRUE(claims->ClaimForHelper(9));
    ASSERT_TRUE(claims->ClaimForHelper(kConfigurations + 1));  // the second comparison
    ASSERT_TRUE(claims->FinishForHelper(9));
    ASSERT_TRUE(claims->FinishForHelper(kConfigurations + 1));
    claims->SetHelperTaking(true);
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    // Its unit and its comparison are gone; of the 8 units and 1 comparison left, this process
    // does half.
    EXPECT_EQ(meter.Last().total, 9 * kFramesPerUnit + 70);
    EXPECT_NEAR(meter.Last().eta_seconds, 0.5 * (5.6 + 7), 1e-6);
    claims->SetHelperTaking(false);  // it stopped taking: the rest is this process's
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 5.6 + 7, 1e-6);
}

// The figure of a line's parts named `name`; NaN when the line has none of that name.
double PartOf(const RunProgress& line, const std::string& name) {
    for (const auto& [part, value] : line.parts) {
        if (part == name) {
            return value;
        }
    }
    return std::numeric_limits<double>::quiet_NaN();
}

// A progress log (`--progress-log`) has, beside each line, the figures its ETA was worked out
// from: what is left of each kind and at what price, the threads, and the second process's
// forecast, which join to the line's ETA.
TEST(RenderProgressTest, ALinesPartsAreTheFiguresItsEtaIsWorkedOutFrom) {
    TenConfigurationsAndTwoComparisons run;
    ASSERT_TRUE(run.claims);
    ProgressMeter& meter = run.meter;
    EXPECT_TRUE(std::isnan(PartOf(meter.Last(), "second_process_joins_in_seconds")));
    run.claims->ExpectHelperAt(run.now + std::chrono::milliseconds(4300));
    meter.Step(ProgressMeter::kImage, "0", 0, run.now);
    const RunProgress line = meter.Last();
    // 9 units of 7 frames and 2 comparisons of 70 frames left, at 100 ms a frame.
    EXPECT_EQ(PartOf(line, "image_frames_done"), 7);
    EXPECT_EQ(PartOf(line, "image_frames_left"), 63);
    EXPECT_EQ(PartOf(line, "comparison_frames_left"), 140);
    EXPECT_NEAR(PartOf(line, "image_seconds_per_frame"), 0.1, 1e-9);
    EXPECT_NEAR(PartOf(line, "seconds_left"), 6.3 + 14, 1e-6);
    EXPECT_EQ(PartOf(line, "threads"), 1);
    EXPECT_NEAR(PartOf(line, "second_process_joins_in_seconds"), 4.3, 1e-3);
    // 4.3 s alone, then the 16 s left halved: the ETA.
    EXPECT_NEAR(PartOf(line, "own_end_seconds"), line.eta_seconds, 1e-9);
    EXPECT_NEAR(line.eta_seconds,
                SecondsToFinish(PartOf(line, "seconds_left"), PartOf(line, "threads"),
                                PartOf(line, "second_process_joins_in_seconds"),
                                PartOf(line, "owned_seconds_left")),
                1e-9);
}

// A unit the second process is working on keeps it from the rest until the unit's expected
// seconds have passed (it takes no other unit before), counted from when the meter first saw it.
TEST(RenderProgressTest, AUnitTheSecondProcessIsWorkingOnDelaysItsShareOfTheRest) {
    using namespace std::chrono_literals;
    TenConfigurationsAndTwoComparisons run;
    ASSERT_TRUE(run.claims);
    ProgressMeter& meter = run.meter;
    base::SharedClaims* const claims = run.claims.get();
    Clock::time_point now = run.now;
    constexpr std::size_t kConfigurations = TenConfigurationsAndTwoComparisons::kConfigurations;
    claims->SetHelperTaking(true);
    ASSERT_TRUE(claims->ClaimForHelper(kConfigurations + 1));  // 70 frames at 100 ms: 7 s
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    // 9 units (6.3 s) and the first comparison (7 s) are left here; the second process takes
    // its half of what is left then only after its comparison's 7 s.
    EXPECT_NEAR(meter.Last().eta_seconds, 7.0 + (13.3 - 7.0) / 2, 1e-6);
    now += 3s;  // no frame here meanwhile: published without a step, so the rates stay
    meter.Waiting("the second process's units", now);
    EXPECT_NEAR(meter.Last().eta_seconds, 4.0 + (13.3 - 4.0) / 2, 1e-6);
    ASSERT_TRUE(claims->FinishForHelper(kConfigurations + 1));
    meter.Waiting("the second process's units", now);
    EXPECT_NEAR(meter.Last().eta_seconds, 13.3 / 2, 1e-6);
}

// With its own units done, the render waits for the second process's last ones and collects
// their results: the line says so and counts down their expected seconds, never below none, at
// 100% of this process's own work.
TEST(RenderProgressTest, WaitingForTheSecondProcessCountsDownItsUnitsExpectedSeconds) {
    using namespace std::chrono_literals;
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    meter.AddComparisons(1, 50);
    const std::unique_ptr<base::SharedClaims> claims = ShareWithSecondProcess(meter, 1, 7);
    ASSERT_TRUE(claims);
    Clock::time_point now = RenderConfigurationZero(meter, *claims, start, 7);
    claims->SetHelperTaking(true);
    ASSERT_TRUE(claims->ClaimForHelper(1));  // the comparison: 50 frames at 100 ms
    meter.Waiting("the second process's units", now);
    EXPECT_EQ(meter.Last().stage, "waiting for");
    EXPECT_NEAR(meter.Last().eta_seconds, 5.0, 1e-6);
    // Its own work is done: waiting is none of it (counted as work, 0.7 s of 5.7 would read 12%).
    EXPECT_NEAR(meter.Last().percent, 100.0, 1e-9);
    now += 2s;
    meter.Waiting("the second process's units", now);
    EXPECT_NEAR(meter.Last().eta_seconds, 3.0, 1e-6);
    now += 4s;  // past its expected end
    meter.Waiting("the second process's units", now);
    EXPECT_NEAR(meter.Last().eta_seconds, 0.0, 1e-9);
    ASSERT_TRUE(claims->FinishForHelper(1));
    meter.Waiting("the second process's units", now);
    EXPECT_NEAR(meter.Last().percent, 100.0, 1e-9);
}

// The comparisons this process has claimed (begun after their probes) are its own: a second
// process that takes every image cannot shorten them, and once it would run out of images the
// ETA is theirs.
TEST(RenderProgressTest, ComparisonsThisProcessClaimedAreNotSharedInTheEta) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    constexpr std::size_t kConfigurations = 4;
    // Two comparisons of 100 frames each (PriceComparisons' guess) at 100 ms a frame: 20 s.
    PriceComparisons(meter, {{0, 1}, {2, 3}}, {0.1, 0.1, 0.1, 0.1});
    const std::unique_ptr<base::SharedClaims> claims =
            ShareWithSecondProcess(meter, kConfigurations, 10);
    ASSERT_TRUE(claims);
    claims->SetHelperTaking(true);  // the second process takes units from now
    // Image frames at what the configurations' cost prices them (kImageFrameCost x 100 ms).
    const double image_seconds = ProgressMeter::kImageFrameCost * 0.1;
    Clock::time_point now = start;
    for (int f = 0; f < 10; ++f) {
        now += std::chrono::duration_cast<Clock::duration>(
                std::chrono::duration<double>(image_seconds));
        meter.Step(ProgressMeter::kImage, "images", 1, now);
    }
    // 3 configurations' images and 20 s of comparisons left, nothing claimed: shared.
    EXPECT_NEAR(meter.Last().eta_seconds, (30 * image_seconds + 20.0) / 2, 1e-6);
    // This process claims both comparisons: their 20 s are its own, and the second process has
    // only the images to take.
    ASSERT_TRUE(claims->ClaimForOwner(kConfigurations));
    ASSERT_TRUE(claims->ClaimForOwner(kConfigurations + 1));
    meter.Step(ProgressMeter::kImage, "images", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 20.0, 1e-6);
}

// A second process that stops renewing its join forecast may have died before taking a unit: the
// ETA stops counting on it rather than wait for a join that will not come.
TEST(RenderProgressTest, AForecastNotRenewedIsNotCountedOn) {
    using namespace std::chrono_literals;
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    const std::unique_ptr<base::SharedClaims> claims = base::SharedClaims::Create(4);
    ASSERT_TRUE(claims);
    meter.AddExpected(ProgressMeter::kImage, 40);
    meter.ShareUnits(claims.get(), 10, 4, 50ms);
    Clock::time_point now = start;
    for (int f = 0; f < 10; ++f) {
        now += 100ms;
        meter.Step(ProgressMeter::kImage, "0", 1, now);
    }
    // 30 frames left at 100 ms: 3 s alone; with the second process joining in 1 s, 1 + 2 / 2.
    claims->Beat();
    claims->ExpectHelperAt(now + 1s);
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 2.0, 0.05);
    std::this_thread::sleep_for(80ms);  // silent for longer than the meter allows
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 3.0, 1e-6);
    claims->Beat();  // it renews its forecast: counted on again
    claims->ExpectHelperAt(now + 1s);
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 2.0, 0.05);
}

}  // namespace
}  // namespace tidepool::runner
