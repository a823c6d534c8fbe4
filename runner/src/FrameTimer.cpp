#include "tidepool/runner/FrameTimer.h"

#include "tidepool/base/CoreCompetitor.h"
#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <utility>
#include <vector>

namespace tidepool::runner {
namespace {

double ClockMs(clockid_t id) {
    timespec now{};
    ::clock_gettime(id, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

double WallMs() {
    return std::chrono::duration<double, std::milli>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
}

bool Contains(std::string_view text, std::string_view word) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return lower.find(word) != std::string::npos;
}

}  // namespace

std::string_view FrameClockName(FrameClock clock) {
    switch (clock) {
        case FrameClock::kThreadCpu:
            return "thread_cpu";
        case FrameClock::kProcessCpu:
            return "process_cpu";
        case FrameClock::kGpuTimer:
            return "gpu_timer_query";
        case FrameClock::kWall:
            return "wall";
    }
    return "wall";
}

FrameClockChoice ChooseFrameClock(std::string_view gl_renderer, std::string_view lp_num_threads,
                                  bool has_timer_query) {
    const bool software = Contains(gl_renderer, "llvmpipe") || Contains(gl_renderer, "softpipe") ||
                          Contains(gl_renderer, "swrast") || Contains(gl_renderer, "offscreen") ||
                          Contains(gl_renderer, "software rasterizer");
    if (software) {
        if (lp_num_threads == "0") {
            return {FrameClock::kThreadCpu,
                    "a software renderer rendering on the calling thread (LP_NUM_THREADS=0): "
                    "the thread's CPU time is the frame's whole work, and other processes on "
                    "the machine barely move it"};
        }
        return {FrameClock::kProcessCpu,
                "a software renderer with worker threads: the process's CPU time sums every "
                "rasteriser thread's work"};
    }
    if (has_timer_query) {
        return {FrameClock::kGpuTimer,
                "a GPU: its own clock through GL_EXT_disjoint_timer_query, since CPU time does "
                "not measure GPU work"};
    }
    return {FrameClock::kWall,
            "a GPU without timer queries: the wall clock around submission and glFinish"};
}

FrameTimer::FrameTimer(WaterRenderer& renderer, FrameClock clock)
    : renderer_(renderer), clock_(clock) {}

double FrameTimer::ReadMs() const {
    switch (clock_) {
        case FrameClock::kThreadCpu:
            return ClockMs(CLOCK_THREAD_CPUTIME_ID);
        case FrameClock::kProcessCpu:
            return ClockMs(CLOCK_PROCESS_CPUTIME_ID);
        case FrameClock::kGpuTimer:
        case FrameClock::kWall:
            return WallMs();
    }
    return WallMs();
}

FrameTime FrameTimer::Time(const RenderConfiguration& configuration, const CameraView& view,
                           FrameReport* report) {
    FrameTime time;
    const bool gpu = clock_ == FrameClock::kGpuTimer && renderer_.BeginGpuTimer();
    const double wall_start = WallMs();
    const double start = ReadMs();
    FrameReport frame = renderer_.RenderFrame(configuration, view);
    const double gpu_ms = gpu ? renderer_.EndGpuTimerMs() : std::nan("");
    renderer_.Finish();
    time.ms = ReadMs() - start;
    time.wall_ms = WallMs() - wall_start;
    if (gpu && std::isfinite(gpu_ms)) {
        time.ms = gpu_ms;
    }
    if (report != nullptr) {
        *report = std::move(frame);
    }
    return time;
}

std::map<std::string, double> FrameTimer::TimePasses(const RenderConfiguration& configuration,
                                                     const CameraView& view) {
    std::map<std::string, double> out;
    renderer_.Finish();
    const double start = ReadMs();
    double last = start;
    renderer_.RenderFrame(configuration, view, [&](const std::string& pass) {
        renderer_.Finish();
        const double now = ReadMs();
        out[pass] += now - last;
        last = now;
    });
    renderer_.Finish();
    out["frame"] = ReadMs() - start;
    return out;
}

void TimePassesInPairs(const TimeSidePasses& time_side, int pairs, ComparisonTiming& out) {
    std::map<std::string, std::vector<double>> samples[2];  // [0] baseline, [1] candidate
    for (int k = 0; k < pairs; ++k) {
        const bool candidate_first = k % 2 == 1;
        for (const bool candidate : {candidate_first, !candidate_first}) {
            for (const auto& [pass, ms] : time_side(candidate)) {
                samples[candidate ? 1 : 0][pass].push_back(ms);
            }
        }
    }
    PassMedians* sides[2] = {&out.baseline_passes, &out.candidate_passes};
    for (int side = 0; side < 2; ++side) {
        *sides[side] = PassMedians{};
        for (const auto& [pass, times] : samples[side]) {
            if (pass == "frame") {
                sides[side]->frame_ms = base::Median(times);
            } else {
                sides[side]->pass_ms[pass] = base::Median(times);
            }
        }
    }
}

namespace {

// One pair into `s`: the baseline first in its even pairs, the candidate first in odd ones.
void TakePair(const TimeSide& time_side, PairSamples& s) {
    const bool baseline_first = s.baseline_ms.size() % 2 == 0;
    const FrameTime first = time_side(!baseline_first);
    const FrameTime second = time_side(baseline_first);
    const FrameTime& baseline = baseline_first ? first : second;
    const FrameTime& candidate = baseline_first ? second : first;
    s.baseline_ms.push_back(baseline.ms);
    s.candidate_ms.push_back(candidate.ms);
    s.baseline_wall_ms.push_back(baseline.wall_ms);
    s.candidate_wall_ms.push_back(candidate.wall_ms);
}

// The contended pairs `rule` asks for after the as-run pairs `out` holds
// (base::ContendedPairsBeforeNextLook), with a base::CoreCompetitor on the calling thread's core.
void TakeContendedPairs(const TimeSide& time_side, const base::StoppingRule& rule,
                        ComparisonTiming& out) {
    const int contended = base::ContendedPairsBeforeNextLook(
            static_cast<int>(out.samples.baseline_ms.size()),
            static_cast<int>(out.contended.baseline_ms.size()), rule);
    if (contended > 0) {
        const base::CoreCompetitor competitor;
        for (int k = 0; k < contended; ++k) {
            TakePair(time_side, out.contended);
        }
    }
}

}  // namespace

ComparisonTiming ProbeComparison(const TimeSide& time_side, int pairs,
                                 const base::StoppingRule& rule) {
    ComparisonTiming out;
    for (int k = 0; k < pairs; ++k) {
        TakePair(time_side, out.samples);
    }
    TakeContendedPairs(time_side, rule, out);
    out.estimate = base::EstimatePaired(out.samples.baseline_ms, out.samples.candidate_ms);
    out.contended_estimate =
            base::EstimatePaired(out.contended.baseline_ms, out.contended.candidate_ms);
    out.stated = base::AcrossHostStates(out.estimate, out.contended_estimate);
    return out;
}

ComparisonTiming TimeComparison(
        const TimeSide& time_side, const base::StoppingRule& rule,
        const std::function<void(const ComparisonTiming& so_far)>& after_look,
        ComparisonTiming so_far) {
    ComparisonTiming out = std::move(so_far);
    out.decision = base::StopDecision::kContinue;
    for (;;) {
        const int as_run = static_cast<int>(out.samples.baseline_ms.size());
        const int contended = static_cast<int>(out.contended.baseline_ms.size());
        // Each look's pairs go where they narrow the stated interval more: to the contended
        // state alone while its pairs do (base::ContendedPairsNarrowMore), otherwise to the
        // as-run state with the contended share beside them.
        int taken = 0;
        if (as_run >= rule.min_pairs &&
            base::ContendedPairsNarrowMore(out.estimate, out.contended_estimate)) {
            const base::CoreCompetitor competitor;
            taken = base::ContendedPairsForLook(contended, rule);
            for (int k = 0; k < taken; ++k) {
                TakePair(time_side, out.contended);
            }
        } else {
            taken = base::PairsBeforeNextLook(as_run, rule);
            for (int k = 0; k < taken; ++k) {
                TakePair(time_side, out.samples);
            }
            TakeContendedPairs(time_side, rule, out);
        }
        out.estimate = base::EstimatePaired(out.samples.baseline_ms, out.samples.candidate_ms);
        out.contended_estimate =
                base::EstimatePaired(out.contended.baseline_ms, out.contended.candidate_ms);
        out.stated = base::AcrossHostStates(out.estimate, out.contended_estimate);
        out.decision = taken == 0
                               ? base::StopDecision::kCapped
                               : base::DecideStopAcrossStates(
                                         out.stated,
                                         static_cast<int>(out.contended.baseline_ms.size()), rule);
        if (after_look) {
            after_look(out);
        }
        if (out.decision != base::StopDecision::kContinue) {
            return out;
        }
    }
}

}  // namespace tidepool::runner
