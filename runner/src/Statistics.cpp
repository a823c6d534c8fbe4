// Order statistics for frame-time samples.
#include "tidepool/runner/Statistics.h"

#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tidepool::runner {
namespace {

// P(B <= k) for B ~ binomial(n, 1/2), summed in log space so large n cannot overflow.
double BinomialHalfCdf(int n, int k) {
    double total = 0;
    for (int i = 0; i <= k; ++i) {
        const double log_term = std::lgamma(n + 1.0) - std::lgamma(i + 1.0) -
                                std::lgamma(n - i + 1.0) + n * std::log(0.5);
        total += std::exp(log_term);
    }
    return total;
}

}  // namespace

SampleStatistics ComputeSampleStatistics(std::vector<double> samples, double confidence) {
    SampleStatistics stats;
    if (samples.empty()) {
        return stats;
    }
    std::sort(samples.begin(), samples.end());
    const int n = static_cast<int>(samples.size());
    stats.count = n;
    stats.min = samples.front();
    stats.max = samples.back();
    stats.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / n;
    stats.median = base::Quantile(samples, 0.5);
    stats.q1 = base::Quantile(samples, 0.25);
    stats.q3 = base::Quantile(samples, 0.75);
    stats.iqr = stats.q3 - stats.q1;
    // j is 1-based; j = 1 gives [min, max]. Take the largest j that still covers enough.
    int best_j = 1;
    for (int j = 1; j <= n / 2; ++j) {
        const double coverage = 1.0 - 2.0 * BinomialHalfCdf(n, j - 1);
        if (coverage + 1e-12 < confidence) {  // 1e-12: rounding of the summed probabilities
            break;
        }
        best_j = j;
    }
    stats.ci_low = samples[static_cast<std::size_t>(best_j - 1)];
    stats.ci_high = samples[static_cast<std::size_t>(n - best_j)];
    stats.ci_coverage = 1.0 - 2.0 * BinomialHalfCdf(n, best_j - 1);
    return stats;
}

}  // namespace tidepool::runner
