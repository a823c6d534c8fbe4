// The one timing engine: which clock a frame is timed on, how one frame (and each of its passes)
// is timed, and how two configurations are compared pair by pair until the interval is as
// narrow as asked. `render`, `bench`, `run` and the scene planner all time through here.
#pragma once

#include "tidepool/base/PairedEstimate.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::runner {

/// A clock a frame can be timed on.
enum class FrameClock {
    kThreadCpu,   // CPU time of the rendering thread (software renderer on the calling thread)
    kProcessCpu,  // CPU time of the whole process (software renderer with worker threads)
    kGpuTimer,    // GL_EXT_disjoint_timer_query around the frame (a GPU's own clock)
    kWall,        // steady clock around submission + glFinish
};

/// "thread_cpu", "process_cpu", "gpu_timer_query" or "wall"; never fails.
std::string_view FrameClockName(FrameClock clock);

/// A clock and why it was chosen, recorded in results.json.
struct FrameClockChoice {
    FrameClock clock = FrameClock::kWall;
    std::string reason;
};

/// Picks the clock for a renderer from its GL_RENDERER string. A software rasteriser (llvmpipe,
/// softpipe, swrast, Mesa's offscreen renderer) does its work on the CPU: thread CPU time when
/// it renders on the calling thread (`lp_num_threads` "0"), process CPU time otherwise, because
/// CPU time is the work a frame costs whatever else the machine runs, and GL timer queries on
/// llvmpipe do not measure whole draws. A GPU's work is not CPU time: timer queries when the
/// driver offers them (`has_timer_query`), otherwise the wall clock around glFinish. Never fails.
FrameClockChoice ChooseFrameClock(std::string_view gl_renderer, std::string_view lp_num_threads,
                                  bool has_timer_query);

/// One timed frame.
struct FrameTime {
    double ms = 0;       // on the timer's clock
    double wall_ms = 0;  // steady clock around the same frame, always recorded beside it
};

/// Times frames of one renderer on one clock. Not thread-safe: one timer per rendering thread.
class FrameTimer {
public:
    /// Times through `renderer` (whose context must be current on this thread) on `clock`.
    FrameTimer(WaterRenderer& renderer, FrameClock clock);

    /// Renders one frame of `configuration` at `view`, waits for it (glFinish) and returns its
    /// time; `report` receives the frame's description when not null. Fails softly: a frame
    /// whose GPU query was disjoint is timed on the wall clock instead (rare, and only on GPUs).
    FrameTime Time(const RenderConfiguration& configuration, const CameraView& view,
                   FrameReport* report = nullptr);

    /// Renders one frame with a glFinish after every pass and returns each pass's time in
    /// milliseconds by pass name (on the CPU clocks as asked; on the wall clock when the timer
    /// uses GPU queries, which cannot nest), plus the whole instrumented frame under "frame".
    std::map<std::string, double> TimePasses(const RenderConfiguration& configuration,
                                             const CameraView& view);

    /// The renderer timed.
    WaterRenderer& Renderer() { return renderer_; }
    /// The clock frames are timed on.
    FrameClock Clock() const { return clock_; }

private:
    double ReadMs() const;  // the clock now (CPU and wall clocks)

    WaterRenderer& renderer_;
    FrameClock clock_;
};

/// Every frame of a paired comparison, in the order they were taken.
struct PairSamples {
    std::vector<double> baseline_ms;  // on the timer's clock
    std::vector<double> candidate_ms;
    std::vector<double> baseline_wall_ms;
    std::vector<double> candidate_wall_ms;
};

/// One configuration's instrumented frames (a glFinish after every pass): each pass's median
/// time and the median of the frames as a whole, on the timer's clock.
struct PassMedians {
    std::map<std::string, double> pass_ms;  // by pass name
    double frame_ms = 0;                    // 0 when no instrumented frame was timed
};

/// The outcome of comparing two configurations.
struct ComparisonTiming {
    PairSamples samples;            // as the machine runs
    base::PairedEstimate estimate;  // over those pairs, on the timer's clock
    // Pairs timed with a base::CoreCompetitor on the rendering thread's core
    // (rule.contended_share), their estimate, and the interval the comparison states across
    // both (base::AcrossHostStates), which the stopping rule watches; `stated` is `estimate`
    // when there are none.
    PairSamples contended;
    base::PairedEstimate contended_estimate;
    base::PairedEstimate stated;
    base::StopDecision decision = base::StopDecision::kContinue;
    // Each side's per-pass times, from instrumented frames taken in pairs like the samples, so
    // that the two sides' passes are timed under the same load (TimePassesInPairs).
    PassMedians baseline_passes;
    PassMedians candidate_passes;
};

/// Times one side of a pair: false for the baseline, true for the candidate.
using TimeSide = std::function<FrameTime(bool candidate)>;

/// Times one side's instrumented frame: each pass's time by name plus "frame" for the whole, as
/// FrameTimer::TimePasses returns them; false for the baseline, true for the candidate.
using TimeSidePasses = std::function<std::map<std::string, double>(bool candidate)>;

/// Times `pairs` instrumented frames of each side, in pairs ordered as TimeComparison orders
/// them (baseline first in even pairs, candidate first in odd ones), and writes each side's
/// medians into `out`'s baseline_passes and candidate_passes. Why pairs: instrumented frames
/// timed seconds apart, or in another comparison, differ by the load of their moment (a pass
/// of an identical configuration read 26.5 ms in one and 35.6 ms in another on a shared
/// machine), and the report compares the two sides pass by pass.
void TimePassesInPairs(const TimeSidePasses& time_side, int pairs, ComparisonTiming& out);

/// Compares two configurations pair by pair: pair i renders the baseline then the candidate
/// when i is even, the other way round when odd, so neither side always goes first and the two
/// frames of a pair lie milliseconds apart (drift on a shared machine cancels in their ratio).
/// After each look's PairsBeforeNextLook pairs it takes ContendedPairsBeforeNextLook pairs,
/// ordered the same way, with a base::CoreCompetitor sharing the calling thread's core, then
/// looks at the stated interval (AcrossHostStates) and stops as `rule` says
/// (DecideStopAcrossStates). Once it has `rule.min_pairs` as-run pairs, a look at which
/// contended pairs narrow the stated interval more (ContendedPairsNarrowMore) takes
/// ContendedPairsForLook contended pairs instead, and no as-run pair.
/// `after_look` (may be empty) sees the timing so far (samples, estimates, decision) after every
/// look. Never fails: a side whose frames cannot be timed makes the estimate's error say so.
///
/// `so_far` is where to go on from: a ProbeComparison's pairs (or nothing). The pairs, looks and
/// decisions are then those one call from the start would take; only the time between the
/// probe's pairs and the rest differs, and each pair's two frames stay milliseconds apart.
ComparisonTiming TimeComparison(
        const TimeSide& time_side, const base::StoppingRule& rule,
        const std::function<void(const ComparisonTiming& so_far)>& after_look = {},
        ComparisonTiming so_far = {});

/// The first `pairs` as-run pairs of a comparison, taken as TimeComparison takes them, then the
/// contended pairs TimeComparison would take after them (base::ContendedPairsBeforeNextLook:
/// none when `rule.contended_share` is 0), with their estimates and the interval they state
/// (AcrossHostStates); no look of the rule: the decision stays kContinue. Why: a run takes
/// every comparison's first pairs early, so that its progress line knows from them which
/// comparisons will need many pairs (those near a verdict's boundary,
/// base::PairsExpectedAtStop) long before their turn, and goes on with TimeComparison later.
/// Why the contended pairs too: they are noisier than the as-run ones, so they widen the
/// interval a comparison states and set how long it runs. From the as-run pairs alone, the
/// guessed work of 11 main-job halves of 2026-11-27, replayed, fell short of the comparisons'
/// by 36 to 70% at its worst moment (median 61%).
/// `pairs` should stay below the rule's min_pairs, so that no look is skipped.
ComparisonTiming ProbeComparison(const TimeSide& time_side, int pairs,
                                 const base::StoppingRule& rule);

}  // namespace tidepool::runner
