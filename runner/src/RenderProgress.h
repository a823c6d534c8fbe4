// The render's order of work and its progress line: which unit a rendering thread takes next,
// and how much of the run is done and how long the rest will take. Private to the runner
// library; tested on its own (tests/unit/RenderProgressTest.cpp).
#pragma once

#include "tidepool/base/SharedClaims.h"
#include "tidepool/runner/Results.h"

#include <array>
#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace tidepool::runner {

/// A unit of work: one configuration's images and coarse time, or one comparison.
struct WorkUnit {
    bool comparison = false;
    std::size_t index = 0;
};

/// Seconds until this process finishes `work` seconds of units (seconds of one thread) on
/// `threads` threads, while a second process of one thread takes units from the other end of the
/// same work order at the same speed once it joins in `helper_joins_in` seconds (0: it is taking
/// units now; nothing: it will take none). Until it joins, this process works alone; after, the
/// two share what is left in proportion to their threads.
double SecondsToFinish(double work, double threads, std::optional<double> helper_joins_in);

/// The order the rendering threads take units in: `first` (the reference configuration, whose
/// images the others are compared with), then each comparison followed by its share of the
/// other configurations, in a fixed shuffled order (the matrix runs from heavy variants to light
/// ones). Both kinds of frame are then measured from the first seconds on, so the ETA knows
/// what an image frame costs long before the comparisons are done, and the queue still ends on
/// short units, which keeps several threads busy to the end.
std::vector<WorkUnit> RenderWorkOrder(std::size_t comparisons, std::size_t configurations,
                                      std::optional<std::size_t> first = std::nullopt);

/// Progress shared by the rendering threads, in frames of two kinds: timed frames of the
/// comparisons, and the images and coarse frames of the configurations. A comparison's expected
/// frames follow its interval (pairs needed ~ pairs so far x (half-width / resolution)^2, the
/// square-root law of an interval's width). Frames of the two kinds cost very differently (an
/// image frame compiles on first use and encodes a PNG), so the share done and the ETA weigh
/// each kind by its measured seconds per frame (SecondsPerFrame), which follows the recent rate:
/// a process that shares the machine (`run`'s stability and plan stages, another user's job)
/// may end or start halfway, and the rate before it says little about the rate after.
class ProgressMeter {
public:
    using Clock = std::chrono::steady_clock;
    enum Kind : std::size_t { kComparison = 0, kImage = 1 };

    /// How long ago a frame may have been measured and still count for half of a new one.
    static constexpr double kRateHalfLifeSeconds = 15.0;

    ProgressMeter(const ProgressCallback& callback, Clock::time_point start)
        : callback_(callback), start_(start) {}

    void AddExpected(Kind kind, long frames);

    /// `count` comparisons, each expected to take `guess` frames until it says otherwise.
    void AddComparisons(std::size_t count, long guess);

    /// Comparison `k` now expects `frames` in all (a running comparison's guess, from its
    /// interval), or took `frames` when `finished` (0: it failed before timing). The comparisons
    /// still waiting then expect the mean of what the finished ones took, with a guess counting
    /// as three of them: few finished comparisons say little, and one slow comparison near a
    /// verdict's boundary should move the rest only by its share. `resolution_frames`, when
    /// given (> 0), is what `k`'s noise at this look needs for the resolution alone
    /// (base::PairsForResolution, in frames); once any comparison has said it, the guess is
    /// kBoundaryAllowance times their mean instead of the first guess.
    void ComparisonExpects(std::size_t k, long frames, bool finished, long resolution_frames = 0);

    /// What the boundary clauses of the stopping rule add to the pairs a comparison needs for
    /// the resolution alone, on average: main-job runs took 1.4 to 2.8 times the median such
    /// pairs on the 2-core host of 2026-11-25 (32 to 88 pairs a comparison) and about 1.1 on the
    /// faster one of 2026-11-26, where nearly every comparison stopped at the minimum 20.
    static constexpr double kBoundaryAllowance = 1.5;

    /// `frames` of `kind` finished on the calling thread since its last step, at `now`.
    void Step(Kind kind, const std::string& what, long frames, Clock::time_point now);
    void Step(Kind kind, const std::string& what, long frames) {
        Step(kind, what, frames, Clock::now());
    }

    /// A second process takes units off the same work order from its end (`claims`: one unit per
    /// configuration, `configurations` of them with `frames_per_configuration` image frames
    /// each, then one per comparison). The units it claims leave this meter's work; the ETA
    /// counts on it for its share of the units nobody has claimed yet from the time it said it
    /// would start taking them (SecondsToFinish), as long as it renews that forecast within
    /// `forecast_silence` (a second process that goes silent may have died).
    void ShareUnits(const base::SharedClaims* claims, long frames_per_configuration,
                    std::size_t configurations,
                    std::chrono::milliseconds forecast_silence = kForecastSilence);

    /// How long the second process may go without renewing its forecast (it does at every
    /// stability case and scene plan: under a minute with the machine loaded).
    static constexpr std::chrono::milliseconds kForecastSilence{120'000};

    /// The last state passed to the callback.
    RunProgress Last() const;

private:
    struct KindState {
        long done = 0;
        long total = 0;
        // Seconds and frames measured, each weighed by 2^(-age / kRateHalfLifeSeconds).
        double recent_seconds = 0;
        double recent_frames = 0;
    };

    enum class ComparisonState { kWaiting, kRunning, kFinished };

    double SecondsPerFrame(std::size_t kind) const;
    void SumComparisons();
    // Sets what every waiting comparison expects: the shrunk mean of the finished ones.
    void ExpectWaiting();

    const ProgressCallback& callback_;
    std::optional<double> HelperJoinsIn(Clock::time_point now) const;
    std::array<long, 2> HelperClaimedFrames() const;

    const base::SharedClaims* shared_ = nullptr;
    long shared_frames_per_configuration_ = 0;
    std::size_t shared_configurations_ = 0;
    std::chrono::milliseconds forecast_silence_ = kForecastSilence;
    Clock::time_point start_;
    Clock::time_point decayed_to_;  // when the recent sums were last aged
    mutable std::mutex mutex_;
    std::array<KindState, 2> kinds_;
    long comparison_guess_ = 0;
    std::vector<long> comparison_frames_;
    std::vector<long> resolution_frames_;  // per comparison, its latest look's; 0: none yet
    std::vector<ComparisonState> comparison_state_;
    std::map<std::thread::id, Clock::time_point> last_step_;
    RunProgress state_;
};

}  // namespace tidepool::runner
