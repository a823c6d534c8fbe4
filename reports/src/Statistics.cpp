// Paired bootstrap comparison, whitepaper conversions and verdicts, ranks and Pareto frontier.
#include "tidepool/report/Statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <tuple>
#include <utility>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

PairedRatio Failure(std::string error) {
    PairedRatio result;
    result.error = std::move(error);
    return result;
}

// Median of a non-empty vector without NaN, reordering it. The even-count midpoint is
// (lower + upper) / 2 rather than lower + (upper - lower) / 2 so that negating every value
// negates the result exactly, which keeps ComparePaired's swap symmetry exact in log space.
double MedianInPlace(std::vector<double>& values) {
    const std::size_t middle = values.size() / 2;
    const auto middle_it = values.begin() + static_cast<std::ptrdiff_t>(middle);
    std::nth_element(values.begin(), middle_it, values.end());
    const double upper = *middle_it;
    if (values.size() % 2 == 1) {
        return upper;
    }
    const double lower = *std::max_element(values.begin(), middle_it);
    return (lower + upper) / 2;
}

// An index in [0, n) from the engine's raw 64-bit output, unbiased by rejection. Not
// std::uniform_int_distribution: its algorithm is implementation-defined, so the same seed would
// give different intervals with libstdc++ and libc++. mt19937_64's output sequence is fixed by
// the standard.
std::size_t DrawIndex(std::mt19937_64& engine, std::size_t n) {
    const std::uint64_t range = n;
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    // Draws at or above the largest multiple of `range` would favour the small indices.
    const std::uint64_t limit = kMax - kMax % range;
    std::uint64_t draw = engine();
    while (draw >= limit) {
        draw = engine();
    }
    return static_cast<std::size_t>(draw % range);
}

// Checks that both sides have the same, nonzero number of rounds; returns "" or why not.
std::string CheckRoundCounts(const std::vector<std::vector<double>>& baseline_rounds,
                             const std::vector<std::vector<double>>& candidate_rounds) {
    if (baseline_rounds.empty() || candidate_rounds.empty()) {
        return "no timing rounds to compare";
    }
    if (baseline_rounds.size() != candidate_rounds.size()) {
        return fmt::format("the baseline has {} timing rounds but the candidate has {}",
                           baseline_rounds.size(), candidate_rounds.size());
    }
    return "";
}

// The median frame time of one round, or NaN with `error` set when the round cannot be used.
double RoundMedian(const std::vector<double>& samples, std::string_view side, std::size_t round,
                   std::string* error) {
    if (samples.empty()) {
        *error = fmt::format("{} round {} has no frame samples", side, round + 1);
        return kNaN;
    }
    for (const double sample : samples) {
        if (!std::isfinite(sample) || sample <= 0) {
            *error = fmt::format("{} round {} has a frame time of {}, not a finite positive time",
                                 side, round + 1, sample);
            return kNaN;
        }
    }
    std::vector<double> copy = samples;
    return MedianInPlace(copy);
}

// Pearson-ready ranks: 1-based positions in ascending order, ties sharing their average rank.
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

}  // namespace

double Median(std::vector<double> samples) {
    if (samples.empty() ||
        std::any_of(samples.begin(), samples.end(), [](double v) { return std::isnan(v); })) {
        return kNaN;  // NaN would also break nth_element's ordering
    }
    return MedianInPlace(samples);
}

double Quantile(const std::vector<double>& sorted, double q) {
    if (sorted.empty() || !(q >= 0 && q <= 1)) {
        return kNaN;
    }
    const double position = q * static_cast<double>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double fraction = position - static_cast<double>(below);
    return sorted[below] + (sorted[above] - sorted[below]) * fraction;
}

PairedRatio ComparePaired(const std::vector<std::vector<double>>& baseline_rounds,
                          const std::vector<std::vector<double>>& candidate_rounds,
                          std::uint64_t seed) {
    if (std::string error = CheckRoundCounts(baseline_rounds, candidate_rounds); !error.empty()) {
        return Failure(std::move(error));
    }
    const std::size_t rounds = baseline_rounds.size();
    std::vector<double> log_ratios(rounds);
    for (std::size_t r = 0; r < rounds; ++r) {
        std::string error;
        const double baseline = RoundMedian(baseline_rounds[r], "baseline", r, &error);
        if (!error.empty()) {
            return Failure(std::move(error));
        }
        const double candidate = RoundMedian(candidate_rounds[r], "candidate", r, &error);
        if (!error.empty()) {
            return Failure(std::move(error));
        }
        log_ratios[r] = std::log(candidate) - std::log(baseline);
    }

    PairedRatio result;
    result.rounds = static_cast<int>(rounds);
    std::vector<double> scratch = log_ratios;
    result.ratio = std::exp(MedianInPlace(scratch));
    if (rounds < 2) {
        // A single round says nothing about how much rounds vary: every ratio stays possible.
        result.ci = {0.0, std::numeric_limits<double>::infinity()};
        return result;
    }

    std::mt19937_64 engine(seed);
    std::vector<double> estimates(static_cast<std::size_t>(kBootstrapResamples));
    for (double& estimate : estimates) {
        for (double& value : scratch) {
            value = log_ratios[DrawIndex(engine, rounds)];
        }
        estimate = MedianInPlace(scratch);
    }
    std::sort(estimates.begin(), estimates.end());
    const double tail = (1 - kConfidenceLevel) / 2;
    result.ci = {std::exp(Quantile(estimates, tail)), std::exp(Quantile(estimates, 1 - tail))};
    return result;
}

double PerformanceChangePercent(double frame_time_ratio) {
    if (!std::isfinite(frame_time_ratio) || frame_time_ratio <= 0) {
        return kNaN;
    }
    return (1 / frame_time_ratio - 1) * 100;
}

double FrameTimeRatioFromPerformanceChange(double percent) {
    if (!std::isfinite(percent) || percent <= -100) {
        return kNaN;
    }
    return 1 / (1 + percent / 100);
}

SplitHalf CompareSplitHalves(const std::vector<std::vector<double>>& baseline_rounds,
                             const std::vector<std::vector<double>>& candidate_rounds,
                             std::uint64_t seed) {
    SplitHalf result;
    std::string error = CheckRoundCounts(baseline_rounds, candidate_rounds);
    if (error.empty() && baseline_rounds.size() < 2) {
        error = "a split-half check needs at least two timing rounds";
    }
    if (!error.empty()) {
        result.odd = Failure(error);
        result.even = Failure(std::move(error));
        return result;
    }
    std::vector<std::vector<double>> halves[2][2];  // [parity][baseline, candidate]
    for (std::size_t r = 0; r < baseline_rounds.size(); ++r) {
        halves[r % 2][0].push_back(baseline_rounds[r]);
        halves[r % 2][1].push_back(candidate_rounds[r]);
    }
    result.odd = ComparePaired(halves[0][0], halves[0][1], seed);  // rounds 1, 3, ...
    result.even = ComparePaired(halves[1][0], halves[1][1], seed);
    // NaN propagates when either half failed.
    result.disagreement_percent_points = std::abs(PerformanceChangePercent(result.odd.ratio) -
                                                  PerformanceChangePercent(result.even.ratio));
    return result;
}

std::string_view AgreementName(Agreement agreement) {
    switch (agreement) {
        case Agreement::kSameDirectionAndMagnitude:
            return "same-direction-and-magnitude";
        case Agreement::kSameDirectionOnly:
            return "same-direction-only";
        case Agreement::kOpposite:
            return "opposite";
        case Agreement::kInconclusive:
            return "inconclusive";
    }
    return "inconclusive";  // unreachable for valid enumerators
}

Agreement CompareWithWhitepaper(double whitepaper_percent, const PairedRatio& measured,
                                double magnitude_tolerance_percent_points) {
    const Interval& ci = measured.ci;
    if (!std::isfinite(whitepaper_percent) || !std::isfinite(measured.ratio) ||
        !(measured.ratio > 0) || !(ci.low > 0) || !std::isfinite(ci.high)) {
        return Agreement::kInconclusive;
    }
    const double tolerance =
            magnitude_tolerance_percent_points >= 0 ? magnitude_tolerance_percent_points : 0.0;
    const double change = PerformanceChangePercent(measured.ratio);
    // The performance change falls as the frame-time ratio grows, so the interval's ends swap.
    const double change_low = PerformanceChangePercent(ci.high);
    const double change_high = PerformanceChangePercent(ci.low);
    const bool magnitude_agrees =
            std::abs(change - whitepaper_percent) <= tolerance ||
            (change_low <= whitepaper_percent && whitepaper_percent <= change_high);
    if (whitepaper_percent == 0) {
        return magnitude_agrees ? Agreement::kSameDirectionAndMagnitude : Agreement::kOpposite;
    }
    if (ci.low <= 1 && 1 <= ci.high) {
        return Agreement::kInconclusive;
    }
    const bool measured_faster = ci.high < 1;
    const bool claimed_faster = whitepaper_percent > 0;
    if (measured_faster != claimed_faster) {
        return Agreement::kOpposite;
    }
    return magnitude_agrees ? Agreement::kSameDirectionAndMagnitude : Agreement::kSameDirectionOnly;
}

double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y) {
    const auto has_nan = [](const std::vector<double>& v) {
        return std::any_of(v.begin(), v.end(), [](double value) { return std::isnan(value); });
    };
    if (x.size() != y.size() || x.size() < 2 || has_nan(x) || has_nan(y)) {
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

std::vector<std::size_t> ParetoFrontier(const std::vector<double>& time,
                                        const std::vector<double>& error) {
    if (time.size() != error.size()) {
        return {};
    }
    const auto usable = [&](std::size_t i) {
        return !std::isnan(time[i]) && !std::isnan(error[i]);
    };
    // Quadratic, which is plenty for the hundreds of configurations a report compares.
    std::vector<std::size_t> frontier;
    for (std::size_t i = 0; i < time.size(); ++i) {
        if (!usable(i)) {
            continue;
        }
        bool dominated = false;
        for (std::size_t j = 0; j < time.size() && !dominated; ++j) {
            dominated = j != i && usable(j) && time[j] <= time[i] && error[j] <= error[i] &&
                        (time[j] < time[i] || error[j] < error[i]);
        }
        if (!dominated) {
            frontier.push_back(i);
        }
    }
    std::sort(frontier.begin(), frontier.end(), [&](std::size_t a, std::size_t b) {
        return std::tuple(time[a], error[a], a) < std::tuple(time[b], error[b], b);
    });
    return frontier;
}

}  // namespace tidepool::report
