// The statistics of samples, one home for the whole project: Median, Quantile, the standard
// deviation, the summary of a configuration's frame times (SampleStatistics) and Spearman's rank
// correlation. The paired comparison of two configurations is PairedEstimate.h's.
//
// Failures are values: a function that cannot answer says so as its comment tells (NaN, or a
// count of 0), never throws and never prints. Empty input is such a failure everywhere: Median,
// Quantile, StandardDeviation and SpearmanRho return NaN, ComputeSampleStatistics a count of 0.
#pragma once

#include <vector>

namespace tidepool::base {

/// The median of `samples` (the mean of the middle two for an even count). Fails (returns NaN)
/// when `samples` is empty or holds a NaN.
double Median(std::vector<double> samples);

/// The q-th quantile (0 <= q <= 1) of ascending `sorted` samples by linear interpolation
/// between order statistics (Hyndman and Fan type 7, as R and NumPy default). Fails (returns
/// NaN) when `sorted` is empty or q is outside [0, 1] or NaN.
double Quantile(const std::vector<double>& sorted, double q);

/// The sample standard deviation of `samples` (divided by n - 1). Fails (returns NaN) when
/// there are fewer than two samples.
double StandardDeviation(const std::vector<double>& samples);

/// What a configuration's frame times summarise to (all in the samples' unit).
struct SampleStatistics {
    int count = 0;
    double min = 0;
    double max = 0;
    double mean = 0;
    double median = 0;
    double q1 = 0;   // 25th percentile, Quantile's interpolation
    double q3 = 0;   // 75th percentile, likewise
    double iqr = 0;  // q3 - q1
    // Confidence interval of the median from order statistics: [x(j), x(n-j+1)] with the
    // largest j whose binomial(n, 1/2) coverage 1 - 2 P(B <= j-1) is still at least the level
    // asked for. Distribution-free; needs n >= 6 for 95% (below that it is [min, max] and
    // ci_coverage says how much it really covers).
    double ci_low = 0;
    double ci_high = 0;
    double ci_coverage = 0;  // the exact coverage the chosen order statistics achieve
};

/// Computes the statistics of `samples` with a median interval of at least `confidence`
/// coverage where the sample count allows. Fails (all zero, count 0) when samples is empty.
SampleStatistics ComputeSampleStatistics(std::vector<double> samples, double confidence = 0.95);

/// The 1-based ranks of `values` in ascending order, tied values sharing the average of their
/// ranks (so [10, 20, 20] ranks [1, 2.5, 2.5]). Never fails; NaN values get arbitrary ranks.
std::vector<double> AverageRanks(const std::vector<double>& values);

/// Spearman's rank correlation of paired samples, tied values getting the average of their
/// ranks (the Pearson correlation of the ranks). Fails (returns NaN) when the sizes differ,
/// there are fewer than two pairs, a value is NaN, or either side is constant.
double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tidepool::base
