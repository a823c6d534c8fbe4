#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace tidepool::base {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool HasNaN(const std::vector<double>& values) {
    return std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); });
}

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

double Median(std::vector<double> samples) {
    if (samples.empty() || HasNaN(samples)) {
        return kNaN;
    }
    std::sort(samples.begin(), samples.end());
    return Quantile(samples, 0.5);
}

double Quantile(const std::vector<double>& sorted, double q) {
    if (sorted.empty() || !(q >= 0.0 && q <= 1.0)) {
        return kNaN;
    }
    const double position = q * static_cast<double>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double fraction = position - static_cast<double>(below);
    return sorted[below] + (sorted[above] - sorted[below]) * fraction;
}

double StandardDeviation(const std::vector<double>& samples) {
    if (samples.size() < 2) {
        return kNaN;
    }
    const double mean = std::accumulate(samples.begin(), samples.end(), 0.0) /
                        static_cast<double>(samples.size());
    double sum = 0;
    for (double v : samples) {
        sum += (v - mean) * (v - mean);
    }
    return std::sqrt(sum / static_cast<double>(samples.size() - 1));
}

std::vector<double> AverageRanks(const std::vector<double>& values) {
    std::vector<std::size_t> order(values.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    std::vector<double> ranks(values.size());
    std::size_t start = 0;
    while (start < order.size()) {
        std::size_t end = start + 1;
        while (end < order.size() && values[order[end]] == values[order[start]]) {
            ++end;
        }
        // Positions start+1 .. end (1-based) share their mean.
        const double rank = (static_cast<double>(start + 1) + static_cast<double>(end)) / 2;
        for (std::size_t k = start; k < end; ++k) {
            ranks[order[k]] = rank;
        }
        start = end;
    }
    return ranks;
}

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
    stats.median = Quantile(samples, 0.5);
    stats.q1 = Quantile(samples, 0.25);
    stats.q3 = Quantile(samples, 0.75);
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

double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y) {
    if (x.size() != y.size() || x.size() < 2 || HasNaN(x) || HasNaN(y)) {
        return kNaN;
    }
    const std::vector<double> rank_x = AverageRanks(x);
    const std::vector<double> rank_y = AverageRanks(y);
    // Both rank vectors have the same mean, (n + 1) / 2.
    const double mean = (static_cast<double>(x.size()) + 1) / 2;
    double sum_xy = 0;
    double sum_xx = 0;
    double sum_yy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double dx = rank_x[i] - mean;
        const double dy = rank_y[i] - mean;
        sum_xy += dx * dy;
        sum_xx += dx * dx;
        sum_yy += dy * dy;
    }
    if (sum_xx == 0 || sum_yy == 0) {
        return kNaN;  // a constant side has no order to correlate
    }
    return sum_xy / std::sqrt(sum_xx * sum_yy);
}

}  // namespace tidepool::base
