// Replays the comparisons a `tidepool run` recorded (its results.json) through the stopping rule
// and the progress line's guesses as built, look by look: the figures behind issue 11's ETA
// target, without rendering a frame.
//
// Usage: replay_comparisons RESULTS.json...
//
// Method, stated again next to the figures it prints:
//  * Each comparison's recorded pairs, as-run and contended, are taken in the order the run took
//    them: a probe of kProbePairs as-run pairs and the contended pairs its first look takes,
//    then the looks of base::PairsBeforeNextLook, each followed by its contended pairs
//    (base::ContendedPairsBeforeNextLook), or, while contended pairs narrow the stated
//    interval more (base::ContendedPairsNarrowMore), of base::ContendedPairsForLook contended
//    pairs alone; each look decides by base::DecideStopAcrossStates. The rule is the one built now
//    (base::StoppingRule's defaults) with the file's resolution, pair counts, contended share and
//    boundary clauses (the defaults where an older file has none), and each whitepaper row's
//    magnitude band (report::ComparedPresetPairs). A comparison whose recording ends before the
//    rule stops (a run on another rule stopped it sooner) is marked "≥".
//  * The guesses are those of runner/src/Results.cpp: base::PairsExpectedAcrossStates at every
//    look, the probe's included (from its few pairs, the spread's guess alone, with the pairs as
//    base::UndisturbedProbe gives them over the run's probes in base::ProbeOrder).
//  * The guessed work's miss at a look of comparison k: its guessed frames less the frames it
//    took, plus the same for every later comparison at its probe's guess, each frame weighed by
//    its comparison's mean frame time; the worst over all looks, in percent of all the
//    comparisons' work. A frame of a comparison: its pairs' and contended pairs' two frames each,
//    and 14 for the warm-up and per-pass frames every comparison renders. Contended frames are
//    weighed as as-run ones.
//  * The comparisons not yet probed after the first kProbesBeforeTheWaitingGuess probes, in the
//    order a run probes them (base::ProbeOrder; about where a main job's progress line first
//    counts): the guess the progress line gives each, the mean of those probes' guesses, over
//    the mean frames they took.
//  * The floor: the same miss at the run's start, before any comparison has gone past its
//    probe, with every comparison's guess at its probe, against a guess that knew each
//    comparison's mean frames over all the files given (in-sample: no guess made in a run from
//    its own pairs does better on average). When that guess misses as far, the miss comes from
//    how much the pairs a comparison takes vary from run to run, not from the probe's guess.
//
// Exit codes: 0 (figures printed), 1 when a file cannot be read, 2 on no argument.
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/stagefiles/ResultsFile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>
#include <vector>

namespace {

using tidepool::base::PairedEstimate;
using tidepool::base::StoppingRule;

constexpr int kProbePairs = tidepool::base::kMinimumPairs;
constexpr int kOverheadFrames = 14;  // 2 warm-up and 5 per-pass frames of each side
// After this many probes, the guess of the comparisons not yet probed is compared with what they
// took: about where a main job's progress line first counts (10% of the render).
constexpr std::size_t kProbesBeforeTheWaitingGuess = 8;

std::vector<double> First(const std::vector<double>& samples, int n) {
    const std::size_t count = std::min(static_cast<std::size_t>(std::max(n, 0)), samples.size());
    return {samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(count)};
}

// One comparison replayed: the guess of its pairs at each look (the probe's first), the pairs
// each look had, and where it stopped.
struct Replay {
    std::vector<int> look_pairs;
    std::vector<double> guesses;  // frames
    int stopped_at = 0;           // as-run pairs
    int contended_at_stop = 0;    // contended pairs
    bool recording_ended = false;
};

// `probe_candidates`: the probe's candidate times as its guesses take them
// (base::UndisturbedProbe).
Replay ReplayComparison(const tidepool::stagefiles::ResultsComparison& c, const StoppingRule& rule,
                        const tidepool::base::ProbeCandidates& probe_candidates) {
    using namespace tidepool::base;
    Replay out;
    const int recorded = static_cast<int>(c.baseline_ms.size());
    const int recorded_contended = static_cast<int>(c.contended_baseline_ms.size());
    int n = std::min(kProbePairs, recorded);
    int m = ContendedPairsBeforeNextLook(n, 0, rule);
    bool probe = true;
    for (;;) {
        if (m > recorded_contended) {
            out.recording_ended = true;
            break;
        }
        const PairedEstimate as_run =
                EstimatePaired(First(c.baseline_ms, n), First(c.candidate_ms, n));
        const PairedEstimate contended = EstimatePaired(First(c.contended_baseline_ms, m),
                                                        First(c.contended_candidate_ms, m));
        const PairedEstimate stated = AcrossHostStates(as_run, contended);
        const bool stops =
                !probe && DecideStopAcrossStates(stated, m, rule) != StopDecision::kContinue;
        const std::vector<double> candidate =
                probe ? probe_candidates.as_run : First(c.candidate_ms, n);
        const std::vector<double> contended_candidate =
                probe ? probe_candidates.contended : First(c.contended_candidate_ms, m);
        out.look_pairs.push_back(n);
        const ExpectedPairs expected =
                stops ? ExpectedPairs{n, m}
                      : PairsExpectedAcrossStates(First(c.baseline_ms, n), candidate,
                                                  First(c.contended_baseline_ms, m),
                                                  contended_candidate, as_run, contended, rule, 60);
        out.guesses.push_back(2.0 * (expected.as_run + expected.contended) + kOverheadFrames);
        out.stopped_at = n;
        out.contended_at_stop = m;
        if (stops) {
            break;
        }
        probe = false;
        if (n >= rule.min_pairs && ContendedPairsNarrowMore(as_run, contended)) {
            const int more = ContendedPairsForLook(m, rule);
            if (more <= 0) {
                break;
            }
            m += more;
            continue;
        }
        const int batch = PairsBeforeNextLook(n, rule);
        if (batch <= 0) {
            break;
        }
        if (n + batch > recorded) {
            out.recording_ended = true;
            break;
        }
        n += batch;
        m += ContendedPairsBeforeNextLook(n, m, rule);
    }
    return out;
}

// The frames a replayed comparison took: its as-run and contended pairs' two frames each, and
// the warm-up and per-pass frames.
double Taken(const Replay& replay) {
    return 2.0 * (replay.stopped_at + replay.contended_at_stop) + kOverheadFrames;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: replay_comparisons RESULTS.json...\n");
        return 2;
    }
    std::map<std::string, std::vector<double>> boundaries;
    for (const auto& pair : tidepool::report::ComparedPresetPairs()) {
        boundaries[pair.label] = pair.boundaries_points;
    }
    std::printf(
            "Comparisons replayed through the stopping rule as built, with the boundary clauses "
            "each file recorded (as built, boundary_pairs %d, where it recorded none), pairs "
            "recorded -> replayed; '>=' where the recording ended first.\n",
            StoppingRule{}.boundary_pairs);
    std::vector<double> misses;
    std::vector<double> waiting_ratios;  // by file: the waiting comparisons' guess over their take
    // Each file's comparisons: label, replay and a frame's mean time, for the floor.
    struct Replayed {
        std::string label;
        Replay replay;
        double cost = 0;
    };
    std::vector<std::vector<Replayed>> files;
    for (int f = 1; f < argc; ++f) {
        const auto read = tidepool::stagefiles::ReadResultsFile(argv[f]);
        if (!read.value) {
            std::fprintf(stderr, "%s\n", read.error.c_str());
            return 1;
        }
        const tidepool::stagefiles::ResultsFile& results = *read.value;
        files.emplace_back();
        StoppingRule rule;
        rule.resolution_points = results.timing.resolution_points.value_or(rule.resolution_points);
        rule.min_pairs = results.timing.min_pairs;
        rule.max_pairs = results.timing.max_pairs;
        rule.batch_pairs = results.timing.batch_pairs;
        rule.contended_share = results.timing.contended_share;
        rule.boundary_pairs = results.timing.boundary_pairs.value_or(rule.boundary_pairs);
        rule.boundary_standard_errors =
                results.timing.boundary_standard_errors.value_or(rule.boundary_standard_errors);
        // Each probe's candidate times as its guesses take them, in the order the run probes.
        const std::size_t count = results.comparisons.size();
        std::vector<tidepool::base::ProbeCandidates> probe_candidates(count);
        tidepool::base::ProbeSpreads spreads;
        for (std::size_t k : tidepool::base::ProbeOrder(count)) {
            const auto& c = results.comparisons[k];
            const int n = std::min(kProbePairs, static_cast<int>(c.baseline_ms.size()));
            const int m = ContendedPairsBeforeNextLook(n, 0, rule);
            probe_candidates[k] = tidepool::base::UndisturbedProbe(
                    First(c.baseline_ms, n), First(c.candidate_ms, n),
                    First(c.contended_baseline_ms, m), First(c.contended_candidate_ms, m), spreads);
        }
        std::vector<Replay> replays;
        std::vector<double> cost;  // a frame's mean time, ms
        std::printf("%s\n ", argv[f]);
        int recorded_total = 0;
        int replayed_total = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const auto& c = results.comparisons[i];
            rule.boundaries_points =
                    boundaries.count(c.label) ? boundaries[c.label] : std::vector<double>{};
            replays.push_back(ReplayComparison(c, rule, probe_candidates[i]));
            const std::vector<double>& b = c.baseline_ms;
            const std::vector<double>& k = c.candidate_ms;
            cost.push_back(b.empty() ? 0.0
                                     : (std::accumulate(b.begin(), b.end(), 0.0) +
                                        std::accumulate(k.begin(), k.end(), 0.0)) /
                                               static_cast<double>(b.size() + k.size()));
            files.back().push_back({c.label, replays.back(), cost.back()});
            recorded_total += c.pairs;
            replayed_total += replays.back().stopped_at;
            std::printf(" %d->%s%d", c.pairs, replays.back().recording_ended ? ">=" : "",
                        replays.back().stopped_at);
        }
        rule.boundaries_points.clear();
        // The comparisons not yet probed after the first few probes: the meter's guess of each
        // (the mean of the probes' guesses) against the mean frames they took.
        if (replays.size() > kProbesBeforeTheWaitingGuess) {
            const std::vector<std::size_t> order = tidepool::base::ProbeOrder(replays.size());
            double probed = 0;
            double probes = 0;
            for (std::size_t i = 0; i < kProbesBeforeTheWaitingGuess; ++i) {
                const Replay& r = replays[order[i]];
                if (!r.guesses.empty()) {
                    probed += r.guesses.front();
                    probes += 1;
                }
            }
            double taken = 0;
            for (std::size_t i = kProbesBeforeTheWaitingGuess; i < replays.size(); ++i) {
                taken += Taken(replays[order[i]]);
            }
            const auto waiting = static_cast<double>(replays.size() - kProbesBeforeTheWaitingGuess);
            const double guess = probes > 0 ? probed / probes : 0.0;
            waiting_ratios.push_back(guess / (taken / waiting));
        }
        double all = 0;
        for (std::size_t i = 0; i < replays.size(); ++i) {
            all += Taken(replays[i]) * cost[i];
        }
        double worst = 0;
        for (std::size_t i = 0; i < replays.size(); ++i) {
            double later = 0;
            for (std::size_t j = i + 1; j < replays.size(); ++j) {
                const double probe_guess =
                        replays[j].guesses.empty() ? 0.0 : replays[j].guesses.front();
                later += (probe_guess - Taken(replays[j])) * cost[j];
            }
            for (double guess : replays[i].guesses) {
                const double miss = (guess - Taken(replays[i])) * cost[i] + later;
                worst = std::fabs(miss) > std::fabs(worst) ? miss : worst;
            }
        }
        const double percent = all > 0 ? 100.0 * worst / all : 0.0;
        misses.push_back(std::fabs(percent));
        std::printf(
                "\n  pairs %d recorded, %d replayed; guessed comparison work missed by at most "
                "%+.0f%%",
                recorded_total, replayed_total, percent);
        if (replays.size() > kProbesBeforeTheWaitingGuess) {
            std::printf("; after %zu probes, the others guessed at %.2f times what they took",
                        kProbesBeforeTheWaitingGuess, waiting_ratios.back());
        }
        std::printf("\n");
    }
    std::sort(misses.begin(), misses.end());
    std::printf(
            "worst miss of the guessed comparison work over %zu files: median %.0f%%, largest "
            "%.0f%% (the progress line's ETA target: within 20%%)\n",
            misses.size(), misses[misses.size() / 2], misses.back());

    if (!waiting_ratios.empty()) {
        std::sort(waiting_ratios.begin(), waiting_ratios.end());
        std::printf(
                "after %zu probes, the comparisons not yet probed were guessed at %.2f to %.2f "
                "times the mean frames they took (median %.2f)\n",
                kProbesBeforeTheWaitingGuess, waiting_ratios.front(), waiting_ratios.back(),
                waiting_ratios[waiting_ratios.size() / 2]);
    }

    // The floor: at the start, the probes' guesses against each comparison's mean frames.
    std::map<std::string, std::pair<double, int>> frames_by_label;  // sum, count
    for (const auto& file : files) {
        for (const Replayed& r : file) {
            frames_by_label[r.label].first += Taken(r.replay);
            frames_by_label[r.label].second += 1;
        }
    }
    std::vector<double> probe_misses;
    std::vector<double> mean_misses;
    for (std::size_t f = 0; f < files.size(); ++f) {
        double all = 0;
        double probe = 0;
        double mean = 0;
        for (const Replayed& r : files[f]) {
            const double taken = Taken(r.replay) * r.cost;
            all += taken;
            const double guess = r.replay.guesses.empty() ? 0.0 : r.replay.guesses.front();
            probe += guess * r.cost - taken;
            const auto& [sum, count] = frames_by_label[r.label];
            mean += sum / count * r.cost - taken;
        }
        probe_misses.push_back(all > 0 ? std::fabs(100.0 * probe / all) : 0.0);
        mean_misses.push_back(all > 0 ? std::fabs(100.0 * mean / all) : 0.0);
    }
    std::sort(probe_misses.begin(), probe_misses.end());
    std::sort(mean_misses.begin(), mean_misses.end());
    std::printf(
            "at the start, every comparison at its probe's guess: the work missed by median "
            "%.0f%%, largest %.0f%%; at each comparison's mean frames over these %zu files "
            "instead (in-sample): median %.0f%%, largest %.0f%%\n",
            probe_misses[probe_misses.size() / 2], probe_misses.back(), files.size(),
            mean_misses[mean_misses.size() / 2], mean_misses.back());
    return 0;
}
