#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <memory>
#include <set>
#include <vector>

#include "RenderProgress.h"

namespace tidepool::runner {
namespace {

using Clock = ProgressMeter::Clock;

TEST(RenderProgressTest, EachComparisonIsFollowedByItsShareOfTheConfigurations) {
    const std::vector<WorkUnit> units = RenderWorkOrder(16, 147);
    ASSERT_EQ(units.size(), 16U + 147U);
    std::set<std::size_t> comparisons;
    std::set<std::size_t> configurations;
    std::vector<std::size_t> run_lengths;  // configurations after each comparison
    for (const WorkUnit& unit : units) {
        if (unit.comparison) {
            comparisons.insert(unit.index);
            run_lengths.push_back(0);
        } else {
            configurations.insert(unit.index);
            ASSERT_FALSE(run_lengths.empty()) << "a comparison goes first";
            ++run_lengths.back();
        }
    }
    EXPECT_EQ(comparisons.size(), 16U);
    EXPECT_EQ(configurations.size(), 147U);
    for (std::size_t length : run_lengths) {
        EXPECT_TRUE(length == 9 || length == 10) << length;  // 147 / 16 = 9.2
    }
    EXPECT_FALSE(units.back().comparison);  // the queue ends on short units
}

TEST(RenderProgressTest, TheReferenceConfigurationRendersFirstAndOnce) {
    const std::vector<WorkUnit> units = RenderWorkOrder(16, 147, 42);
    ASSERT_EQ(units.size(), 16U + 147U);
    EXPECT_FALSE(units.front().comparison);
    EXPECT_EQ(units.front().index, 42U);
    std::set<std::size_t> configurations;
    std::size_t comparisons = 0;
    for (const WorkUnit& unit : units) {
        if (unit.comparison) {
            ++comparisons;
        } else {
            EXPECT_TRUE(configurations.insert(unit.index).second) << unit.index;
        }
    }
    EXPECT_EQ(comparisons, 16U);
    EXPECT_EQ(configurations.size(), 147U);
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

// Comparisons not started expect the median of what the finished ones took (the first guess
// counting as one): one that needed 300 pairs near a verdict's boundary does not make every
// later one expect a hundred.
TEST(RenderProgressTest, WaitingComparisonsExpectTheMedianOfTheFinishedOnes) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    meter.AddComparisons(6, 120);  // 6 comparisons, 120 frames each until they say otherwise
    meter.ComparisonExpects(0, 40, true);
    meter.ComparisonExpects(1, 600, true);
    meter.ComparisonExpects(2, 40, true);
    meter.Step(ProgressMeter::kComparison, "row", 680, start + std::chrono::seconds(34));
    // Finished: 40 + 600 + 40 frames; the three waiting expect median{120, 40, 600, 40} = 120
    // (the upper middle), not the mean 200.
    EXPECT_EQ(meter.Last().total, 40 + 600 + 40 + 3 * 120);
    meter.ComparisonExpects(3, 40, true);
    meter.Step(ProgressMeter::kComparison, "row", 40, start + std::chrono::seconds(36));
    EXPECT_EQ(meter.Last().total, 40 + 600 + 40 + 40 + 2 * 40);
}

// A second process that takes images at full speed while this one also goes through its
// comparisons: with no comparisons left they split the images in half; with no images left this
// process has none; in between it renders its share rho = I / (C + I) of the time until they meet.
TEST(RenderProgressTest, ImagesLeftHereFollowTheMeetingPointOfTheTwoProcesses) {
    EXPECT_DOUBLE_EQ(ImagesLeftHere(0, 30), 15);
    EXPECT_DOUBLE_EQ(ImagesLeftHere(60, 0), 0);
    // C = 60 s, I = 30 s: rho = 1/3; they meet after 30 / (4/3) = 22.5 s, a third of it here.
    EXPECT_DOUBLE_EQ(ImagesLeftHere(60, 30), 7.5);
    // Never more than the images left, never less than none.
    for (double c : {0.0, 1.0, 100.0}) {
        for (double i : {0.0, 1.0, 100.0}) {
            EXPECT_GE(ImagesLeftHere(c, i), 0.0);
            EXPECT_LE(ImagesLeftHere(c, i), i);
        }
    }
}

// The units a second process claims leave the meter's totals, and while it is taking units, the
// ETA counts on it for half of the images when no comparison is left.
TEST(RenderProgressTest, ImagesASecondProcessTakesLeaveTheTotalsAndShortenTheEta) {
    const ProgressCallback none;
    const Clock::time_point start = Clock::now();
    ProgressMeter meter(none, start);
    const std::unique_ptr<base::SharedClaims> claims = base::SharedClaims::Create(10);
    ASSERT_TRUE(claims);
    constexpr long kFramesPerUnit = 7;
    meter.AddExpected(ProgressMeter::kImage, 10 * kFramesPerUnit);
    meter.ShareImages(claims.get(), kFramesPerUnit);
    Clock::time_point now = start;
    ASSERT_TRUE(claims->ClaimForOwner(0));
    for (int f = 0; f < kFramesPerUnit; ++f) {
        now += std::chrono::milliseconds(100);
        meter.Step(ProgressMeter::kImage, "0", 1, now);
    }
    // Alone: 9 units of 7 frames at 100 ms.
    EXPECT_EQ(meter.Last().total, 10 * kFramesPerUnit);
    EXPECT_NEAR(meter.Last().eta_seconds, 6.3, 1e-6);
    ASSERT_TRUE(claims->ClaimForHelper(9));
    ASSERT_TRUE(claims->ClaimForHelper(8));
    claims->SetHelperTaking(true);
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    // The helper's 2 units are gone; of the 7 left, this process renders half.
    EXPECT_EQ(meter.Last().total, 8 * kFramesPerUnit);
    EXPECT_NEAR(meter.Last().eta_seconds, 0.5 * 4.9, 1e-6);
    claims->SetHelperTaking(false);  // it stopped taking: the rest is this process's
    meter.Step(ProgressMeter::kImage, "0", 0, now);
    EXPECT_NEAR(meter.Last().eta_seconds, 4.9, 1e-6);
}

}  // namespace
}  // namespace tidepool::runner
