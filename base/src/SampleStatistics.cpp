#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tidepool::base {

double Median(std::vector<double> samples) {
    if (samples.empty() ||
        std::any_of(samples.begin(), samples.end(), [](double v) { return std::isnan(v); })) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    std::sort(samples.begin(), samples.end());
    return Quantile(samples, 0.5);
}

double Quantile(const std::vector<double>& sorted, double q) {
    if (sorted.empty() || !(q >= 0.0 && q <= 1.0)) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const double position = q * static_cast<double>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double fraction = position - static_cast<double>(below);
    return sorted[below] + (sorted[above] - sorted[below]) * fraction;
}

}  // namespace tidepool::base
