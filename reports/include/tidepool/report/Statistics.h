// Statistics for comparing render configurations the way the whitepaper does: paired frame-time
// ratios over interleaved rounds with a bootstrap confidence interval, conversion to the
// whitepaper's "performance increased/reduced by p%", a split-half reliability check, a verdict
// against a quoted figure, rank correlation and the time/error Pareto frontier.
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

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::report {

/// Bootstrap resamples per interval: 2000 keeps the Monte Carlo error of a 2.5% / 97.5%
/// percentile endpoint small (Efron and Tibshirani advise at least 1000 for percentile
/// intervals) and costs well under a millisecond for the round counts we run.
inline constexpr int kBootstrapResamples = 2000;

/// Coverage of the intervals ComparePaired reports (two-sided, percentile bootstrap).
inline constexpr double kConfidenceLevel = 0.95;

/// A suggested `magnitude_tolerance_percent_points` for CompareWithWhitepaper. The whitepaper's
/// figures were measured on a mobile GPU and are quoted to whole percent; we render on Mesa
/// (llvmpipe), whose relative costs of arithmetic, texture fetches and bandwidth differ from a
/// GPU's. Measurement noise is covered by the confidence interval, so this tolerance only has to
/// absorb that platform difference: 10 points says "same size of effect" for a 60% claim
/// measured as 52%, yet still separates a 60% claim from a 30% measurement.
inline constexpr double kWhitepaperMagnitudeTolerancePercentPoints = 10.0;

/// Returns the median of `samples` (the mean of the middle two for an even count). Fails
/// (returns NaN) when `samples` is empty or holds a NaN.
double Median(std::vector<double> samples);

/// Returns the q-th quantile (0 <= q <= 1) of ascending `sorted` samples by linear
/// interpolation between order statistics (Hyndman and Fan type 7, as R and NumPy default).
/// Fails (returns NaN) when `sorted` is empty or q is outside [0, 1] or NaN.
double Quantile(const std::vector<double>& sorted, double q);

/// A closed interval [low, high]; NaN bounds mean "not computed".
struct Interval {
    double low = std::numeric_limits<double>::quiet_NaN();
    double high = std::numeric_limits<double>::quiet_NaN();
};

/// A paired frame-time ratio (candidate / baseline) over timing rounds, with its interval.
struct PairedRatio {
    double ratio = std::numeric_limits<double>::quiet_NaN();  // NaN when the comparison failed
    Interval ci;        // kConfidenceLevel percentile-bootstrap interval of `ratio`
    int rounds = 0;     // rounds compared; 0 when the comparison failed
    std::string error;  // "" on success, otherwise why ratio is NaN
};

/// Compares two configurations timed in the same interleaved rounds: round r's ratio is
/// median(candidate_rounds[r]) / median(baseline_rounds[r]), so drift between rounds (thermal
/// state, other load) cancels; the estimate is the median of the per-round ratios, taken on
/// their logarithms (for an even count, the geometric mean of the middle two) so that swapping
/// baseline and candidate gives exactly the reciprocal. The median rather than the geometric
/// mean of all rounds because one disturbed round (a background job, a page-cache miss) must
/// not move the estimate. The interval is a percentile bootstrap over whole rounds (resampling
/// rounds keeps each round's pairing), kBootstrapResamples resamples drawn from
/// std::mt19937_64(seed) with an unbiased index draw of our own, so the result is identical on
/// every standard library. Percentile intervals of a median under-cover with few rounds: use
/// at least 10. With a single round the interval is [0, +infinity) (one round says nothing
/// about spread), which CompareWithWhitepaper treats as inconclusive. Fails (ratio NaN, rounds
/// 0, `error` set) when there are no rounds, the round counts differ, a round is empty, or a
/// sample is not a finite positive time.
PairedRatio ComparePaired(const std::vector<std::vector<double>>& baseline_rounds,
                          const std::vector<std::vector<double>>& candidate_rounds,
                          std::uint64_t seed = 1);

/// Converts a frame-time ratio to the whitepaper's performance change in percent of frame rate,
/// (1 / ratio - 1) * 100, positive = faster (ratio 2.5 gives -60, "reduced by 60%"). Fails
/// (returns NaN) when the ratio is not finite and positive.
double PerformanceChangePercent(double frame_time_ratio);

/// Converts the whitepaper's performance change in percent of frame rate to a frame-time ratio,
/// 1 / (1 + percent / 100) (-60, "reduced by 60%", gives 2.5), the inverse of
/// PerformanceChangePercent. Fails (returns NaN) when percent is not finite or is <= -100
/// (a frame rate cannot drop by 100% or more).
double FrameTimeRatioFromPerformanceChange(double percent);

/// The same comparison made on the odd rounds (1st, 3rd, ...: indices 0, 2, ...) and on the even
/// rounds (indices 1, 3, ...) separately, to see whether the estimate is stable.
struct SplitHalf {
    PairedRatio odd;
    PairedRatio even;
    // |change(odd) - change(even)| in percent points of PerformanceChangePercent; NaN when
    // either half failed.
    double disagreement_percent_points = std::numeric_limits<double>::quiet_NaN();
};

/// Runs ComparePaired on the odd and on the even rounds with the same seed. Fails
/// (disagreement NaN, the failing half's `error` set) when ComparePaired would fail on all
/// rounds or there are fewer than two rounds.
SplitHalf CompareSplitHalves(const std::vector<std::vector<double>>& baseline_rounds,
                             const std::vector<std::vector<double>>& candidate_rounds,
                             std::uint64_t seed = 1);

/// How a measurement agrees with a figure the whitepaper quotes.
enum class Agreement {
    kSameDirectionAndMagnitude,  // same sign, and the figure is within tolerance or the CI
    kSameDirectionOnly,          // same sign, but the size of the effect differs
    kOpposite,                   // the measurement shows a definite change the other way
    kInconclusive,               // the CI straddles 0% change (or the measurement failed)
};

/// Returns a stable lower-case name for `agreement` ("same-direction-and-magnitude",
/// "same-direction-only", "opposite", "inconclusive") for reports and JSON; never fails.
std::string_view AgreementName(Agreement agreement);

/// Grades `measured` against the whitepaper's `whitepaper_percent` (performance change, positive
/// = faster). Inconclusive when the measurement failed or its interval is unbounded (a single
/// round). For a nonzero figure it is also inconclusive when the interval contains a ratio of 1
/// (0% change), since then not even the direction is established; otherwise the direction is
/// the side of 0% the interval lies on, and when it matches the figure's, the magnitude agrees if
/// the measured change is within `magnitude_tolerance_percent_points` of the figure or the
/// figure lies inside the measured interval (the interval covers our noise, the tolerance the
/// difference between the whitepaper's GPU and our renderer; see
/// kWhitepaperMagnitudeTolerancePercentPoints). A figure of exactly 0 ("no change") has no
/// direction: it is kSameDirectionAndMagnitude when the interval contains 0 or the change is
/// within tolerance, and kOpposite otherwise. Never fails: a figure that is not finite is
/// kInconclusive, and a NaN or negative tolerance counts as 0.
Agreement CompareWithWhitepaper(double whitepaper_percent, const PairedRatio& measured,
                                double magnitude_tolerance_percent_points);

/// Spearman's rank correlation of paired samples, tied values getting the average of their
/// ranks (the Pearson correlation of the ranks). Fails (returns NaN) when the sizes differ,
/// there are fewer than two pairs, a value is NaN, or either side is constant.
double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y);

/// Returns the indices of the points not dominated in (time, error), lower being better in
/// both: a point is dominated when another is <= in both and < in at least one, so identical
/// points are all kept. Sorted by time, then error, then index. Points with a NaN coordinate
/// are never on the frontier and dominate nothing. Fails (returns empty) when the sizes differ.
std::vector<std::size_t> ParetoFrontier(const std::vector<double>& time,
                                        const std::vector<double>& error);

}  // namespace tidepool::report
