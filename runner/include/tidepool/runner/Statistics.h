// Summary statistics of timing samples: median, quartiles and a distribution-free confidence
// interval of the median.
#pragma once

#include <vector>

namespace tidepool::runner {

/// What a configuration's frame times summarise to (all in the samples' unit).
struct SampleStatistics {
    int count = 0;
    double min = 0;
    double max = 0;
    double mean = 0;
    double median = 0;
    double q1 = 0;   // 25th percentile, linear interpolation between order statistics
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

}  // namespace tidepool::runner
