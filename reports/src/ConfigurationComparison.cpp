// Paired comparisons (the base estimator as the report shows it), whitepaper conversions and the
// time/error Pareto frontier.
#include "tidepool/report/ConfigurationComparison.h"

#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

}  // namespace

PairedRatio ComparePairs(const std::vector<double>& baseline_ms,
                         const std::vector<double>& candidate_ms,
                         const std::vector<double>& contended_baseline_ms,
                         const std::vector<double>& contended_candidate_ms) {
    const base::PairedEstimate as_run = base::EstimatePaired(baseline_ms, candidate_ms);
    const base::PairedEstimate contended =
            base::EstimatePaired(contended_baseline_ms, contended_candidate_ms);
    const base::PairedEstimate e = base::AcrossHostStates(as_run, contended);
    PairedRatio out;
    if (!e.Valid()) {
        out.error = e.error.empty() ? "no interval" : e.error;
        return out;
    }
    out.ratio = e.ratio;
    out.ci = {e.ratio_low, e.ratio_high};
    out.pairs = e.pairs;
    out.as_run_ci = {as_run.ratio_low, as_run.ratio_high};
    if (contended.pairs > 0) {
        out.contended_ratio = contended.ratio;
        out.contended_ci = {contended.ratio_low, contended.ratio_high};
        out.contended_pairs = contended.pairs;
    }
    return out;
}

std::string PairsFromRounds(const std::vector<std::vector<double>>& baseline_rounds,
                            const std::vector<std::vector<double>>& candidate_rounds,
                            std::vector<double>* baseline_ms, std::vector<double>* candidate_ms) {
    if (baseline_rounds.size() != candidate_rounds.size()) {
        return fmt::format("the baseline has {} rounds and the candidate {}",
                           baseline_rounds.size(), candidate_rounds.size());
    }
    baseline_ms->clear();
    candidate_ms->clear();
    for (std::size_t r = 0; r < baseline_rounds.size(); ++r) {
        if (baseline_rounds[r].empty() || candidate_rounds[r].empty()) {
            return fmt::format("round {} has no samples", r + 1);
        }
        baseline_ms->push_back(base::Median(baseline_rounds[r]));
        candidate_ms->push_back(base::Median(candidate_rounds[r]));
    }
    return "";
}

double PerformanceChangePercent(double frame_time_ratio) {
    return base::PerformanceChangePercent(frame_time_ratio);
}

double FrameTimeRatioFromPerformanceChange(double percent) {
    if (!std::isfinite(percent) || percent <= -100) {
        return kUndefined;
    }
    return 1.0 / (1.0 + percent / 100.0);
}

SplitHalf CompareSplitPairs(const std::vector<double>& baseline_ms,
                            const std::vector<double>& candidate_ms) {
    std::vector<double> a[2];
    std::vector<double> b[2];
    for (std::size_t i = 0; i < baseline_ms.size() && i < candidate_ms.size(); ++i) {
        a[i % 2].push_back(baseline_ms[i]);
        b[i % 2].push_back(candidate_ms[i]);
    }
    SplitHalf split;
    split.even = ComparePairs(a[0], b[0]);
    split.odd = ComparePairs(a[1], b[1]);
    if (split.even.error.empty() && split.odd.error.empty()) {
        split.disagreement_percent_points = std::fabs(PerformanceChangePercent(split.odd.ratio) -
                                                      PerformanceChangePercent(split.even.ratio));
    }
    return split;
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
