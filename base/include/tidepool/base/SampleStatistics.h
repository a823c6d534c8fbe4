// Order statistics of samples: one Median and one Quantile for the whole project.
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

}  // namespace tidepool::base
