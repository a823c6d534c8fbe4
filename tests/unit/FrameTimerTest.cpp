// The timing engine's parts that need no GL: the clock chosen from a renderer string, the
// pairing order of a comparison, its stopping and its per-pass frames
// (runner/include/tidepool/runner/FrameTimer.h).
#include "tidepool/runner/FrameTimer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace tidepool::runner {
namespace {

struct ClockCase {
    const char* renderer;
    const char* lp_num_threads;
    bool timer_query;
    FrameClock expected;
};

TEST(FrameTimerTest, ClockFollowsTheRendererString) {
    const std::vector<ClockCase> cases = {
            {"llvmpipe (LLVM 15.0.6, 256 bits)", "0", true, FrameClock::kThreadCpu},
            {"llvmpipe (LLVM 15.0.6, 256 bits)", "2", true, FrameClock::kProcessCpu},
            {"softpipe", "0", false, FrameClock::kThreadCpu},
            {"Mesa OffScreen", "", false, FrameClock::kProcessCpu},
            {"Software Rasterizer", "", false, FrameClock::kProcessCpu},
            {"AMD Radeon RX 6600 (navi23, LLVM 15.0.6, DRM 3.49, 6.1.0)", "0", true,
             FrameClock::kGpuTimer},
            {"Mali-G78", "", true, FrameClock::kGpuTimer},
            {"Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "", false, FrameClock::kWall},
            {"PowerVR Rogue GE8320", "", false, FrameClock::kWall},
    };
    for (const ClockCase& c : cases) {
        const FrameClockChoice choice =
                ChooseFrameClock(c.renderer, c.lp_num_threads, c.timer_query);
        EXPECT_EQ(choice.clock, c.expected) << c.renderer << " LP_NUM_THREADS=" << c.lp_num_threads;
        EXPECT_FALSE(choice.reason.empty());
    }
    EXPECT_EQ(FrameClockName(FrameClock::kThreadCpu), "thread_cpu");
    EXPECT_EQ(FrameClockName(FrameClock::kGpuTimer), "gpu_timer_query");
}

TEST(FrameTimerTest, SidesAlternateWhoGoesFirstAndStopAtTheResolution) {
    std::vector<bool> order;
    const TimeSide side = [&](bool candidate) {
        order.push_back(candidate);
        // 10% longer candidate frames, with a little deterministic jitter.
        const double jitter = 1.0 + 0.003 * static_cast<double>(order.size() % 7);
        return FrameTime{(candidate ? 11.0 : 10.0) * jitter, 0.0};
    };
    base::StoppingRule rule;
    rule.resolution_points = 1.5;
    const ComparisonTiming t = TimeComparison(side, rule);
    ASSERT_GE(order.size(), 4U);
    EXPECT_EQ(order[0], false);  // pair 0: baseline first
    EXPECT_EQ(order[1], true);
    EXPECT_EQ(order[2], true);  // pair 1: candidate first
    EXPECT_EQ(order[3], false);
    EXPECT_EQ(t.decision, base::StopDecision::kResolved);
    EXPECT_EQ(t.estimate.pairs, rule.min_pairs);  // this little noise needs no more
    EXPECT_NEAR(t.estimate.ratio, 1.1, 0.01);
}

// Threads of this process now, from /proc: one more while a CoreCompetitor runs.
long ThreadsNow() {
    return std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                         std::filesystem::directory_iterator{});
}

// Frames rendered, and of them those with the core shared (a base::CoreCompetitor running).
struct FrameCounts {
    long alone = ThreadsNow();  // this process's threads without a competitor
    int frames = 0;
    int as_run = 0;
    int contended = 0;
};

TEST(FrameTimerTest, ContendedPairsAreTimedWithTheCoreSharedAndTheIntervalSpansBoth) {
    const long alone = ThreadsNow();
    int contended_frames = 0;
    int frames = 0;
    const TimeSide side = [&](bool candidate) {
        // The candidate is 10% slower as the machine runs and 12% slower with its core shared
        // (the competitor is a thread of this process).
        const bool busy = ThreadsNow() > alone;
        contended_frames += busy ? 1 : 0;
        ++frames;
        const double jitter = 1.0 + 0.002 * static_cast<double>(frames % 5);
        return FrameTime{(candidate ? (busy ? 11.2 : 11.0) : 10.0) * jitter, 0.0};
    };
    base::StoppingRule rule;
    rule.contended_share = 0.5;
    const ComparisonTiming t = TimeComparison(side, rule);
    EXPECT_EQ(t.decision, base::StopDecision::kResolved);
    EXPECT_EQ(t.samples.baseline_ms.size(), 20U);
    EXPECT_EQ(t.contended.baseline_ms.size(), 10U);
    EXPECT_EQ(contended_frames, 20);  // every contended frame, and only those, saw the competitor
    EXPECT_NEAR(t.estimate.ratio, 1.10, 0.01);
    EXPECT_NEAR(t.contended_estimate.ratio, 1.12, 0.01);
    EXPECT_EQ(t.stated.ratio, t.estimate.ratio);
    EXPECT_LT(t.stated.ratio_low, 1.10);
    EXPECT_GT(t.stated.ratio_high, 1.12);
    EXPECT_EQ(ThreadsNow(), alone);  // the competitor is gone
}

// Times a comparison with the default contended share whose candidate takes `ratio(busy, k)`
// times the baseline's 10 ms in its k-th frame of that state (busy: a competitor running), and
// checks what a comparison whose looks after the first take contended pairs alone shows: at
// every look the as-run pairs are the first look's `rule.min_pairs` (and `at_look` holds), it
// resolves after more than one look, and only the contended pairs' frames saw the competitor.
void ExpectLooksAfterTheFirstTakeContendedPairsAlone(
        const std::function<double(bool busy, int k)>& ratio,
        const std::function<void(const ComparisonTiming&)>& at_look) {
    FrameCounts counts;
    int looks = 0;
    base::StoppingRule rule;
    rule.contended_share = 0.5;
    const TimeSide side = [&](bool candidate) {
        counts.frames += 1;
        const bool busy = ThreadsNow() > counts.alone;
        const int k = busy ? ++counts.contended : ++counts.as_run;
        return FrameTime{candidate ? 10.0 * ratio(busy, k) : 10.0, 0.0};
    };
    const ComparisonTiming t = TimeComparison(side, rule, [&](const ComparisonTiming& so_far) {
        ++looks;
        EXPECT_EQ(so_far.estimate.pairs, rule.min_pairs);
        at_look(so_far);
    });
    EXPECT_EQ(t.decision, base::StopDecision::kResolved);
    EXPECT_GT(looks, 1);
    EXPECT_EQ(t.samples.baseline_ms.size(), static_cast<std::size_t>(rule.min_pairs));
    EXPECT_GT(t.contended.baseline_ms.size(), static_cast<std::size_t>(rule.min_pairs));
    EXPECT_EQ(counts.contended, 2 * static_cast<int>(t.contended.baseline_ms.size()));
    EXPECT_LE(t.stated.HalfWidthPoints(), rule.resolution_points);
}

TEST(FrameTimerTest, WhileTheContendedIntervalHoldsTheAsRunOneALookTakesContendedPairsAlone) {
    // As run the candidate is a steady 10% slower; with the core shared it is 10% slower give or
    // take 6%, so the contended interval holds the as-run one until it has many more pairs.
    ExpectLooksAfterTheFirstTakeContendedPairsAlone(
            [](bool busy, int k) {
                return 1.10 * (1.0 + (busy ? 0.03 * (((k / 2) % 5) - 2.0) : 0.001 * ((k / 2) % 3)));
            },
            [](const ComparisonTiming&) {});
}

TEST(FrameTimerTest, WhereContentionMovesTheChangeALookTakesContendedPairsWhileTheyNarrowMore) {
    // As run the candidate is a steady 10% slower; with the core shared 7% slower give or take
    // 2%: the contended interval lies below the as-run one and sets the stated interval's upper
    // end only (+ = faster), and it is the wider per pair, so the looks after the first take
    // contended pairs alone.
    ExpectLooksAfterTheFirstTakeContendedPairsAlone(
            [](bool busy, int k) {
                return busy ? 1.07 * (1.0 + 0.01 * (((k / 2) % 5) - 2.0))
                            : 1.10 * (1.0 + 0.0005 * ((k / 2) % 3));
            },
            [](const ComparisonTiming& so_far) {
                EXPECT_GT(so_far.contended_estimate.change_high, so_far.estimate.change_high);
                EXPECT_GT(so_far.contended_estimate.change_low, so_far.estimate.change_low);
            });
}

TEST(FrameTimerTest, ACapStopsAComparisonThatCannotResolve) {
    std::uint64_t state = 12345;
    const TimeSide side = [&](bool) {
        // Frame times spread uniformly over 10..20 ms: noise far above the asked resolution.
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return FrameTime{10.0 + 10.0 * static_cast<double>(state >> 11) * 0x1.0p-53, 0.0};
    };
    base::StoppingRule rule{0.5, 10, 30, 10};
    const ComparisonTiming t = TimeComparison(side, rule);
    EXPECT_EQ(t.decision, base::StopDecision::kCapped);
    EXPECT_EQ(t.estimate.pairs, 30);
}

// Frames of a pseudo-random time (±8%, enough that the rule needs more than its minimum of
// pairs), the candidate 5% slower; the contended frames twice as noisy. The k-th as-run frame,
// and the k-th contended one, take the same time whatever came between them, so that a
// comparison split into a probe and the rest sees the same samples as one call, and looks at the
// same estimates.
TimeSide NumberedFrames(FrameCounts* counts) {
    return [counts](bool candidate) {
        counts->frames += 1;
        const bool busy = ThreadsNow() > counts->alone;
        const int k = busy ? ++counts->contended : ++counts->as_run;
        std::uint64_t state = static_cast<std::uint64_t>(k) + (busy ? 1000000U : 0U);
        state *= 0x9E3779B97F4A7C15U;
        state ^= state >> 29;
        state *= 0xBF58476D1CE4E5B9U;
        state ^= state >> 32;
        const double unit = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
        const double noise = 1.0 + (busy ? 0.32 : 0.16) * unit;
        return FrameTime{(candidate ? 10.5 : 10.0) * noise, 0.0};
    };
}

// A probe, then the rest of the comparison from it, renders what one call from the start does.
TEST(FrameTimerTest, AProbeAndTheRestTakeThePairsAndLooksOfOneCall) {
    base::StoppingRule rule;
    rule.contended_share = 0.5;
    FrameCounts frames_whole;
    int looks_whole = 0;
    const ComparisonTiming whole = TimeComparison(NumberedFrames(&frames_whole), rule,
                                                  [&](const ComparisonTiming&) { ++looks_whole; });
    ASSERT_GT(whole.samples.baseline_ms.size(), static_cast<std::size_t>(rule.min_pairs));
    // Some looks took contended pairs alone (their interval held the as-run one): more than the
    // contended share of the as-run pairs.
    ASSERT_GT(whole.contended.baseline_ms.size(), (whole.samples.baseline_ms.size() + 1) / 2);

    FrameCounts frames_split;
    const ComparisonTiming probe = ProbeComparison(NumberedFrames(&frames_split), 10, rule);
    EXPECT_EQ(probe.samples.baseline_ms.size(), 10U);
    // The contended pairs the first look takes come with the probe, and state its interval.
    EXPECT_EQ(probe.contended.baseline_ms.size(), static_cast<std::size_t>(base::kMinimumPairs));
    EXPECT_EQ(probe.decision, base::StopDecision::kContinue);
    EXPECT_EQ(probe.estimate.pairs, 10);
    EXPECT_TRUE(probe.contended_estimate.Valid());
    const base::PairedEstimate across =
            base::AcrossHostStates(probe.estimate, probe.contended_estimate);
    EXPECT_EQ(probe.stated.ratio_low, across.ratio_low);
    EXPECT_EQ(probe.stated.ratio_high, across.ratio_high);
    int looks_split = 0;
    const ComparisonTiming rest = TimeComparison(
            NumberedFrames(&frames_split), rule, [&](const ComparisonTiming&) { ++looks_split; },
            probe);

    // The same frames, looks and pairs of each kind as one call; only the order of the first
    // look's as-run and contended pairs differs.
    EXPECT_EQ(frames_split.frames, frames_whole.frames);
    EXPECT_EQ(frames_split.contended, frames_whole.contended);
    EXPECT_EQ(looks_split, looks_whole);
    EXPECT_EQ(rest.samples.baseline_ms.size(), whole.samples.baseline_ms.size());
    EXPECT_EQ(rest.contended.baseline_ms.size(), whole.contended.baseline_ms.size());
    EXPECT_EQ(rest.decision, whole.decision);
    EXPECT_TRUE(rest.stated.Valid());

    // Without contended pairs in the rule, a probe takes none.
    rule.contended_share = 0;
    FrameCounts frames_plain;
    EXPECT_TRUE(
            ProbeComparison(NumberedFrames(&frames_plain), 10, rule).contended.baseline_ms.empty());
    EXPECT_EQ(frames_plain.frames, 20);
}

TEST(FrameTimerTest, PassFramesAlternateLikeThePairsAndKeepEachSidesMedians) {
    std::vector<bool> order;
    const TimeSidePasses side = [&](bool candidate) {
        order.push_back(candidate);
        // The k-th frame of a side: main 10 + k ms (baseline) or 20 + k ms (candidate); only the
        // candidate has a low_res_water pass.
        const double k = static_cast<double>(std::count(order.begin(), order.end(), candidate) - 1);
        std::map<std::string, double> passes = {{"main", (candidate ? 20.0 : 10.0) + k}};
        if (candidate) {
            passes["low_res_water"] = 3.0;
        }
        passes["frame"] = passes["main"] + (candidate ? 3.0 : 0.0);
        return passes;
    };
    ComparisonTiming t;
    t.baseline_passes.pass_ms = {{"stale", 1.0}};  // replaced, not merged
    TimePassesInPairs(side, 5, t);
    EXPECT_EQ(order,
              (std::vector<bool>{false, true, true, false, false, true, true, false, false, true}));
    EXPECT_EQ(t.baseline_passes.pass_ms, (std::map<std::string, double>{{"main", 12.0}}));
    EXPECT_DOUBLE_EQ(t.baseline_passes.frame_ms, 12.0);
    EXPECT_EQ(t.candidate_passes.pass_ms,
              (std::map<std::string, double>{{"low_res_water", 3.0}, {"main", 22.0}}));
    EXPECT_DOUBLE_EQ(t.candidate_passes.frame_ms, 25.0);
}

}  // namespace
}  // namespace tidepool::runner
