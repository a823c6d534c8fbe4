// Comparing render configurations the way the whitepaper does: paired frame-time ratios over
// pairs of frames with a signed-rank confidence interval, conversion to the whitepaper's
// "performance increased/reduced by p%", a split-half reliability check and the time/error
// Pareto frontier. The statistics they rest on are base's (PairedEstimate, SampleStatistics).
//
// Units and sign conventions:
//  * A frame-time ratio is candidate frame time / baseline frame time: 2.5 means the candidate
//    takes 2.5 times as long per frame.
//  * A performance change is in percent of frame rate, positive = faster, as the whitepaper
//    words it: "performance reduced by 60%" is -60 and equals a frame-time ratio of
//    1 / (1 - 0.60) = 2.5; "increased by 25%" is +25 and equals a ratio of 1 / 1.25 = 0.8.
//
// Failures are values: a function that cannot answer returns NaN (or an empty result) as its
// comment says, never throws and never prints.
#pragma once

#include "tidepool/base/PairedEstimate.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::report {

/// Coverage of every interval the report shows (two-sided).
inline constexpr double kConfidenceLevel = base::kConfidenceLevel;

/// A closed interval [low, high]; NaN bounds mean "not computed".
struct Interval {
    double low = std::numeric_limits<double>::quiet_NaN();
    double high = std::numeric_limits<double>::quiet_NaN();
};

/// A paired frame-time ratio (candidate / baseline) with its interval, as the report shows it.
struct PairedRatio {
    double ratio = std::numeric_limits<double>::quiet_NaN();  // NaN when the comparison failed
    // The interval stated: the kConfidenceLevel Wilcoxon signed-rank interval of `ratio`, or,
    // when the comparison was also timed with its core shared, the span of that interval and
    // the contended one (base::AcrossHostStates).
    Interval ci;
    int pairs = 0;       // pairs of frames compared as the machine ran; 0 when it failed
    std::string error;   // "" on success, otherwise why ratio is NaN
    Interval as_run_ci;  // the as-run pairs' own interval
    // The pairs timed with the core shared: their estimate, interval and count (NaN and 0 when
    // none).
    double contended_ratio = std::numeric_limits<double>::quiet_NaN();
    Interval contended_ci;
    int contended_pairs = 0;
};

/// Compares paired frame times (base::EstimatePaired: the Hodges-Lehmann estimate of the
/// per-pair log ratios and its signed-rank interval), and with the pairs timed with the core
/// shared when there are any (base::AcrossHostStates). Fails (ratio NaN, pairs 0, `error`
/// set) when EstimatePaired gives no interval for either set.
PairedRatio ComparePairs(const std::vector<double>& baseline_ms,
                         const std::vector<double>& candidate_ms,
                         const std::vector<double>& contended_baseline_ms = {},
                         const std::vector<double>& contended_candidate_ms = {});

/// One pair per timing round from the medians of round r of each side: how results written
/// before the runner recorded pairs are compared. Returns "" or why not (the round counts
/// differ, or a round is empty).
std::string PairsFromRounds(const std::vector<std::vector<double>>& baseline_rounds,
                            const std::vector<std::vector<double>>& candidate_rounds,
                            std::vector<double>* baseline_ms, std::vector<double>* candidate_ms);

/// Converts a frame-time ratio to the whitepaper's performance change in percent of frame rate,
/// (1 / ratio - 1) * 100, positive = faster (ratio 2.5 gives -60, "reduced by 60%"). Fails
/// (returns NaN) when the ratio is not finite and positive.
double PerformanceChangePercent(double frame_time_ratio);

/// Converts the whitepaper's performance change in percent of frame rate to a frame-time ratio,
/// 1 / (1 + percent / 100) (-60, "reduced by 60%", gives 2.5), the inverse of
/// PerformanceChangePercent. Fails (returns NaN) when percent is not finite or is <= -100
/// (a frame rate cannot drop by 100% or more).
double FrameTimeRatioFromPerformanceChange(double percent);

/// The same comparison made on the even pairs (indices 0, 2, ...: the baseline rendered
/// first) and on the odd pairs (the candidate first) separately: it shows whether the estimate
/// is stable, and whether going first favours a side.
struct SplitHalf {
    PairedRatio odd;   // pairs 1, 3, ... (the candidate first)
    PairedRatio even;  // pairs 0, 2, ... (the baseline first)
    // |change(odd) - change(even)| in percent points of PerformanceChangePercent; NaN when
    // either half failed.
    double disagreement_percent_points = std::numeric_limits<double>::quiet_NaN();
};

/// Runs ComparePairs on the even and on the odd pairs. Fails (disagreement NaN, the failing
/// half's `error` set) when either half has too few pairs for an interval.
SplitHalf CompareSplitPairs(const std::vector<double>& baseline_ms,
                            const std::vector<double>& candidate_ms);

/// Returns the indices of the points not dominated in (time, error), lower being better in
/// both: a point is dominated when another is <= in both and < in at least one, so identical
/// points are all kept. Sorted by time, then error, then index. Points with a NaN coordinate
/// are never on the frontier and dominate nothing. Fails (returns empty) when the sizes differ.
std::vector<std::size_t> ParetoFrontier(const std::vector<double>& time,
                                        const std::vector<double>& error);

}  // namespace tidepool::report
