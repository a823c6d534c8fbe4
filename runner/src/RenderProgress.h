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

/// A unit of work: one configuration's images and coarse time, or one comparison. A comparison
/// may come twice: first its probe (`probe`: its first pairs, ProbeComparison), then the rest of
/// it, which goes on from the probe's pairs.
struct WorkUnit {
    bool comparison = false;
    std::size_t index = 0;
    bool probe = false;
};

/// Seconds until this process finishes `work` seconds of units (seconds of one thread) on
/// `threads` threads, while a second process of one thread takes units from the other end of the
/// same work order at the same speed once it joins in `helper_joins_in` seconds (0: it is taking
/// units now; nothing: it will take none). Until it joins, this process works alone; after, the
/// two share what is left in proportion to their threads, except `own` seconds of it, units this
/// process has claimed (the comparisons it has begun; a probe claims nothing), which only it can
/// do: when the second process runs out of the rest first, `own` sets the end.
double SecondsToFinish(double work, double threads, std::optional<double> helper_joins_in,
                       double own = 0);

/// The core share ContendedFramesCost takes before a probe has measured one: halfway between
/// a quiet machine and one loaded twice over.
inline constexpr double kDefaultCoreShare = 0.75;

/// How many seconds of its configurations' median as-run frame a comparison frame is expected
/// to take before any has been measured (ProgressMeter::ComparisonCostPrior), over its pairs'
/// frames. Contended pairs, `contended_share` of the as-run pairs, share their core with a
/// CoreCompetitor. `core_share` is the share of its core the render thread gets, an as-run
/// frame's CPU time over its wall time (1 on a quiet machine, about 0.5 beside one other busy
/// process per core; out of (0, 1], kDefaultCoreShare): one more process on the core leaves it
/// core_share / (1 + core_share), so a contended frame takes 1 + core_share as-run frames of
/// wall time. Warm-up and per-pass frames are left out: they cost about an as-run frame (an
/// instrumented frame's CPU time was within 2% of it, 2026-11-27), which lowers the ratio over
/// all of a comparison's frames a little. In two traced main-job runs of 2026-11-27, with the
/// overhead frames counted, the calibration settled at 1.37 quiet and 1.19 beside two `yes`;
/// this gives 1.33 and 1.17.
double ContendedFramesCost(double contended_share, double core_share = kDefaultCoreShare);

/// The order the rendering threads take units in: `first` (the reference configuration, whose
/// images the others are compared with), then with `probes` every comparison's probe (in
/// base::ProbeOrder, from both ends of the list in turn), then
/// `early` (the configurations the comparisons time), then every comparison (the rest of it,
/// after a probe), then the other configurations in a fixed shuffled order (the matrix runs from
/// heavy variants to light ones).
///
/// Why the probes come first: how many pairs a comparison takes is the run's one large unknown.
/// Most stop at the minimum, but one whose effect lies near a verdict's boundary takes many more
/// (before base::StoppingRule::boundary_pairs, row 4 of the default matrix took 14 s quiet and
/// 48 to 85 s beside two `yes` on 2026-11-27, a fifth of the run, and the ETA before its turn
/// was 45 to 50% short). Each comparison's first pairs, as-run and contended (ProbeComparison,
/// two or three seconds each), tell the progress line which ones those are
/// (base::PairsExpectedAtStop) within the first seconds of the run. Why the comparisons before
/// the other configurations: a second process takes units from the end, and a comparison left to
/// the end would keep this one busy long after that process ran out of units; images are short.
/// `early`'s images measure what an image frame costs before the comparisons start.
std::vector<WorkUnit> RenderWorkOrder(std::size_t comparisons, std::size_t configurations,
                                      std::optional<std::size_t> first = std::nullopt,
                                      const std::vector<std::size_t>& early = {},
                                      bool probes = false);

/// Progress shared by the rendering threads, in frames of two kinds: timed frames of the
/// comparisons, and the images and coarse frames of the configurations. A comparison's expected
/// frames follow its pairs and interval (base::PairsExpectedAcrossStates). Frames of the two kinds
/// cost very differently (an image frame compiles on first use and encodes a PNG), so the share
/// done and the ETA weigh each kind by its measured seconds per frame (SecondsPerFrame), and the
/// comparisons' frames left by their own configurations' cost once known (PriceOf). Both
/// follow the recent rate:
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
    /// as kPriorComparisons of them. The guess is the mean of the first guesses the comparisons
    /// that have looked gave (a probe's, where the run probes), or AddComparisons' guess before
    /// any has looked. Why their own guesses, not the pairs the noise they measured needs for the
    /// resolution with an allowance for the boundary clauses, as before: replayed over the
    /// main-job halves of 2026-12-07 (`bench/replay_comparisons`), the comparisons not yet probed
    /// after eight probes were guessed at 0.41 to 1.73 times the frames they took (median 0.98)
    /// this way, against 0.55 to 2.62 (median 1.29) with the fixed allowance of 1.5 (over twelve
    /// halves recorded after the choice, 0.63 to 1.68, median 0.94): where the boundary clauses
    /// take pairs depends on each comparison's effect, which its own guess weighs and a fixed
    /// allowance cannot.
    void ComparisonExpects(std::size_t k, long frames, bool finished);

    /// How many comparisons the guess (the first guesses' mean, above) counts for in the
    /// expectation of the comparisons still waiting, against the mean of the finished ones. A whole
    /// default matrix's worth: the extra pairs a comparison takes near a verdict's boundary are its
    /// own (its effect lies near the edge of its own band), so the finished ones say little about
    /// the rest. Replayed over the comparisons' frames in 15 main-job runs with contended pairs
    /// (2026-11-26; rows 2 to 4 and 8, near their bands' edges, took up to 874 frames where most
    /// took the minimum 60), the predicted frames of the waiting comparisons missed by at most 19%
    /// of the run's work (the comparisons taken as half of it) in the worst run and 14% in the
    /// median one with this weight, against 42% and 20% with the weight of 3 used before: the heavy
    /// rows come first in the default order, and a mean over few finished ones then charges every
    /// later row for them.
    static constexpr double kPriorComparisons = 16.0;

    /// What an image frame costs over a timed frame of the same configurations, for the image
    /// rate's prior until images have been measured (an image frame renders one of the
    /// configuration's views and reads it back; the images come from every configuration, the
    /// timed frames from the compared ones). Four traced main jobs of 2026-12-07 (not committed:
    /// the meter's state at every line) measured images at 1.32 to 1.40 times the mean cost of
    /// the configurations the probes had timed quiet and 1.28 to 1.40 beside two `yes`. The prior
    /// before, the comparisons' recent rate (contended frames included), was 53 to 54 ms a frame
    /// early in a quiet run whose images then took 44 to 46 ms.
    static constexpr double kImageFrameCost = 1.3;

    /// `frames` of `kind` finished on the calling thread since its last step, at `now`.
    void Step(Kind kind, const std::string& what, long frames, Clock::time_point now);
    void Step(Kind kind, const std::string& what, long frames) {
        Step(kind, what, frames, Clock::now());
    }

    /// Comparison k (of those AddComparisons made; nothing before it) times configurations
    /// `baseline` and `candidate`. Once any comparison has been given its configurations, the
    /// comparisons' frames must all be counted through StepComparison, which counts each one's
    /// frames done: frames counted by Step(kComparison, ...) would still count as left. Once both
    /// have a cost (ConfigurationCost), the frames k has left are priced at the mean of the two
    /// costs times the calibration, instead of at the comparisons' recent rate. The calibration is
    /// the ratio of the seconds recent comparison frames took (contended frames share a core) to
    /// their price, aged like the rates, ComparisonCostPrior before any.
    void ComparisonConfigurations(std::size_t k, std::size_t baseline, std::size_t candidate);

    /// What the calibration (above) is taken to be until comparison frames have been priced:
    /// ContendedFramesCost. 1 when never given. Until the first comparison after the probes
    /// runs (a fifth of the render), the calibration is this prior alone; at 1, the comparisons'
    /// contended frames went unpriced and the ETA of those lines was up to 27% short.
    void ComparisonCostPrior(double ratio);

    /// Configuration i's timed frame takes `seconds` (the median of its coarse frames).
    void ConfigurationCost(std::size_t i, double seconds);

    /// As Step(kComparison, ...), for frames of comparison k: they also count as k's frames done
    /// and calibrate the prices.
    void StepComparison(std::size_t k, const std::string& what, long frames, Clock::time_point now);
    void StepComparison(std::size_t k, const std::string& what, long frames) {
        StepComparison(k, what, frames, Clock::now());
    }

    /// Publishes the progress line again at `now` without a step, while this process waits for
    /// the second process to finish `what` (the units it claimed): the ETA is then what those
    /// units have left. The rates and totals stay as they are.
    void Waiting(const std::string& what, Clock::time_point now);

    /// A second process takes units off the same work order from its end (`claims`: one unit per
    /// configuration, `configurations` of them with `frames_per_configuration` image frames
    /// each, then one per comparison). The units it claims leave this meter's work; the ETA
    /// counts on it for its share of the units nobody has claimed yet from the time it said it
    /// would start taking them (SecondsToFinish), as long as it renews that forecast within
    /// `forecast_silence` (a second process that goes silent may have died). The units it is
    /// working on count as its own until their expected seconds have passed: it takes no other
    /// before they end, and the run ends no sooner than they do.
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

    void StepLocked(Kind kind, const std::string& what, long frames, Clock::time_point now,
                    std::optional<std::size_t> comparison);
    // Works out the line's state at `now` and passes it to the callback.
    void PublishLocked(const char* stage, const std::string& what, Clock::time_point now);
    double HelperSecondsLeft(Clock::time_point now);
    double SecondsPerFrame(std::size_t kind) const;
    // Seconds of the comparison frames left in this process (those the second process has not
    // claimed), each comparison priced by PriceOf; `owned` of them in comparisons this process
    // has claimed, which the second process cannot take.
    struct ComparisonSeconds {
        double left = 0;
        double owned = 0;
    };
    ComparisonSeconds ComparisonSecondsLeft() const;
    // Seconds a frame of comparison k is expected to take: its configurations' cost times the
    // calibration, or the comparisons' recent rate while a cost is missing.
    double PriceOf(std::size_t k) const;
    std::optional<double> CostOf(std::size_t k) const;
    double Calibration() const;
    // The mean of the configurations' costs so far (ConfigurationCost); none before any.
    std::optional<double> MeanConfigurationCost() const;
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
    // By unit: when this meter first saw the second process working on it.
    std::vector<std::optional<Clock::time_point>> helper_seen_;
    Clock::time_point start_;
    Clock::time_point decayed_to_;  // when the recent sums were last aged
    mutable std::mutex mutex_;
    std::array<KindState, 2> kinds_;
    long comparison_guess_ = 0;
    std::vector<long> comparison_frames_;
    std::vector<long> first_guess_frames_;  // per comparison, its first look's; 0: none yet
    std::vector<ComparisonState> comparison_state_;
    std::vector<long> comparison_done_;  // frames stepped through StepComparison
    std::vector<std::array<std::size_t, 2>> comparison_configurations_;  // empty: not priced
    std::map<std::size_t, double> configuration_cost_;                   // seconds a frame
    // Comparison frames' seconds and their price, aged like the kinds' recent sums.
    double priced_seconds_ = 0;
    double priced_estimate_ = 0;
    double cost_prior_ = 1.0;  // ComparisonCostPrior
    std::map<std::thread::id, Clock::time_point> last_step_;
    RunProgress state_;
};

}  // namespace tidepool::runner
