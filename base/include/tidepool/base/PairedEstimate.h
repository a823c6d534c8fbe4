// The one way tidepool compares two configurations' frame times: pairs of frames rendered
// back to back (milliseconds apart, so slow drift on a shared machine hits both sides), the
// per-pair log ratio, its Hodges-Lehmann estimate and the Wilcoxon signed-rank interval, and
// the sequential rule that decides when a comparison has enough pairs.
//
// Why this estimator: the pair differences of log frame times are symmetric about the effect
// (the two sides alternate who goes first, so neither order nor drift favours a side), which is
// what the signed-rank interval assumes; the Hodges-Lehmann estimate keeps 95% of the mean's
// efficiency on normal noise yet ignores the odd disturbed frame (breakdown point 29%), where
// the mean does not and the plain median needs about 1.5x the pairs for the same interval.
//
// Units: a frame-time ratio is candidate / baseline (2.5: the candidate takes 2.5x as long).
// A performance change is in percent of frame rate, + = faster, as the whitepaper words it:
// (1 / ratio - 1) * 100. Failures are values: never throws, never prints.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::base {

/// Coverage of every interval PairedEstimate reports (two-sided).
inline constexpr double kConfidenceLevel = 0.95;

/// Fewer pairs than this give no interval: the signed-rank interval's normal approximation
/// (used for every n, so coverage does not jump between an exact table and the formula) is
/// within a point of its nominal coverage from about 10 pairs on.
inline constexpr int kMinimumPairs = 10;

/// A direction (faster, slower) is claimed only when the whole 95% interval of a change lies
/// beyond this many percent points of no change: the report's verdicts and the planner's choices
/// alike. Why not beyond 0: contention is not only noise. bench/verdict_stability.sh moved one
/// comparison (row 7, low-resolution water) from -1.2% [-2.4, -0.1] on a quiet machine to
/// +1.2% [+0.1, +2.5] with two competing processes: shared caches and cores slow memory-bound
/// and arithmetic-bound passes by different amounts, a systematic shift of up to 2.4 points that
/// an interval from pairs taken in one state of the machine cannot show. AcrossHostStates now
/// states the span of two states; the margin stays for loads unlike either, and for the scene
/// planner, which times in one. 1.5 points, the default resolution, keeps such a shift from
/// turning into two opposite directions; effects of 3% and more still clear it.
inline constexpr double kDirectionMarginPoints = 1.5;

/// A paired comparison of candidate against baseline frame times.
struct PairedEstimate {
    int pairs = 0;
    double ratio = std::numeric_limits<double>::quiet_NaN();  // candidate / baseline
    double ratio_low = std::numeric_limits<double>::quiet_NaN();
    double ratio_high = std::numeric_limits<double>::quiet_NaN();
    double change_percent = std::numeric_limits<double>::quiet_NaN();  // + = faster
    double change_low = std::numeric_limits<double>::quiet_NaN();      // ends of its interval
    double change_high = std::numeric_limits<double>::quiet_NaN();
    std::string error;  // "" on success, otherwise why the figures are NaN

    /// True when an estimate and a bounded interval exist.
    bool Valid() const { return error.empty() && pairs >= kMinimumPairs; }
    /// Half the interval's width in percent points of performance change; NaN when invalid.
    double HalfWidthPoints() const;
    /// True when the interval lies entirely on one side of no change.
    bool ExcludesNoChange() const;
};

/// Estimates the paired ratio of `candidate_ms[i] / baseline_ms[i]` over every pair i:
/// exp(Hodges-Lehmann estimate of the log ratios) with the `confidence` Wilcoxon signed-rank
/// interval (normal approximation, ranks of the Walsh averages). Fails (NaN figures, `error`
/// set) when the sides differ in length, a time is not finite and positive, or there are
/// fewer than kMinimumPairs pairs (then `ratio` is still the estimate when there is one pair).
PairedEstimate EstimatePaired(const std::vector<double>& baseline_ms,
                              const std::vector<double>& candidate_ms,
                              double confidence = kConfidenceLevel);

/// Converts a frame-time ratio to a performance change in percent of frame rate,
/// (1 / ratio - 1) * 100 (+ = faster). Fails (NaN) when the ratio is not finite and positive.
double PerformanceChangePercent(double frame_time_ratio);

/// When a comparison has enough pairs: its interval's half-width is at most
/// `resolution_points` and it is not near a verdict's boundary (NearVerdictBoundary), or its
/// half-width is at most FinestHalfWidthPoints (half the resolution or half the direction
/// margin, whichever is smaller) and it holds none of `boundaries_points`
/// (HoldsVerdictBoundary), or it has `boundary_pairs`, its half-width is at most
/// `resolution_points` and no end lies near one of `boundaries_points` that it does not hold
/// (NearUnheldBoundary), or it has `max_pairs`. Never fewer than `min_pairs`.
///
/// Why the boundary clause: a direction is claimed when an end of the interval clears
/// +/-kDirectionMarginPoints. An interval that stops with that end within a standard error or so
/// of the margin would come out on the other side in every other run, so a row would be firm in
/// one run and below resolution in the next (bench/verdict_stability.sh saw it: -2.6% [-3.9,
/// -1.4] quiet, -2.9% [-4.4, -1.6] loaded). Such a comparison keeps taking pairs until that end
/// clears the margin by `boundary_standard_errors`, up to the finer resolution. So does one whose
/// estimate lies beyond a margin while its interval still reaches over it (the planner's
/// half-size reflection: -2.0% [-3.3, -0.1] after 20 pairs quiet, stopped and not claimed;
/// -2.7% [-3.4, -2.0] after 187 pairs loaded, claimed), and one whose interval holds or ends
/// near any of `boundaries_points`, the other boundaries of its verdict (the whitepaper's
/// magnitude band: row 2 read -3.2% [-4.8, -2.6] quiet, overlapping the band that starts at
/// -4.5% (half the whitepaper's -9%), and -3.4% [-4.5, -2.4] loaded, outside it). Comparisons far
/// from every boundary, most of them, stop as before.
///
/// Why an interval holding one of `boundaries_points` goes on past the finest half-width: an
/// interval that holds the direction margin gives no direction ("below resolution"), and one
/// that holds the edge of a magnitude band decides no magnitude (once "overlapping the band"
/// claimed the same magnitude, a firm verdict; report::GradeRow now calls it the band's edge),
/// so the comparison goes on while more pairs can still decide it. Row 4 read +8.4% [+7.7,
/// +9.3] quiet, outside its band (up to 7%), and +7.3% [+6.9, +7.7] loaded after 20 pairs, where
/// the half-width of 0.4 was already below the finest and the rule stopped holding the edge:
/// then two firm verdicts that disagreed. Such an interval takes pairs until it clears the edge,
/// or until it has `boundary_pairs` (see below), or reaches the cap.
///
/// Why a comparison that holds a boundary stops at `boundary_pairs`: an interval that holds a
/// boundary gives an undecided verdict there (below resolution, or the magnitude at the band's
/// edge), never a firm one, so stopping it cannot make two runs contradict each other. Going on
/// decides it only when the change lies clear of the boundary; when the change lies on it, the
/// pairs run to the cap. On the default matrix row 4 (+7.1 to +7.7% against its band's end at
/// 7%) ran to the cap of 400 pairs in 7 of 11 main-job halves of 2026-11-27 (up to 85 s beside
/// two `yes`) and still held the edge in 6 of them. Those pairs were the largest part of the
/// main job's time that the progress line could not foresee (its ETA was 45 to 62% short). An
/// interval with an end near a band's boundary that it does not hold still goes on: that
/// magnitude is firm, and a run that read it the other way would contradict it. So does one
/// near the direction margin (NearVerdictBoundary's first clauses, unbounded as before): an
/// effect of 3% must stay firm in every run.
struct StoppingRule {
    double resolution_points = 1.5;  // half-width of the 95% interval, percent points
    int min_pairs = 20;
    int max_pairs = 400;
    // Pairs taken between two looks at the interval: at least this many, and a quarter of the
    // pairs so far, so a comparison needing n pairs is looked at about 5 ln(n / min_pairs)
    // times (each look costs O(n^2) Walsh averages, and fewer looks bias the stop less).
    int batch_pairs = 10;
    // How far, in standard errors of the estimate, an end of the interval must lie from the
    // direction margin before the rule stops at `resolution_points` (0: no boundary clause at
    // all, NearVerdictBoundary is then always false).
    double boundary_standard_errors = 1.5;
    // Pairs after which a comparison stops once its half-width is at most `resolution_points`,
    // unless an end lies near a band's boundary it does not hold (NearUnheldBoundary); 0: the
    // boundary clauses go on to `max_pairs`. 80 is four times `min_pairs`; the looks fall at
    // 77 and 96 pairs, so such a comparison stops at 96.
    int boundary_pairs = 80;
    // Performance changes (percent points, + = faster) at which the comparison's verdict changes
    // beyond the direction margins, e.g. the ends of a whitepaper row's magnitude band; none for
    // most comparisons.
    std::vector<double> boundaries_points = {};
    // Contended pairs (timed with a CoreCompetitor on the render thread's core, see
    // AcrossHostStates) per pair timed as the machine runs; 0 times none, and the rule then
    // watches the as-run interval alone.
    double contended_share = 0;
};

/// The interval a comparison states when it was also timed with its core shared: the as-run
/// estimate, with an interval from the lower of the two intervals' ends to the higher
/// (`contended` is the same comparison timed while a CoreCompetitor ran). `pairs` stays the
/// as-run pairs. `as_run` unchanged when `contended` has no pairs (no contended timing, or none
/// yet); NaN figures with `error` set when either side gives no interval.
///
/// Why: contention is not only noise. On the 2-core host of 2026-11-26, main-job comparisons
/// moved systematically with the load: row 9 read +26.5 to +26.9% quiet in four runs (intervals
/// about 0.5 points wide), +26.3% [+26.0, +26.7] beside two competing processes and +26.0%
/// [+25.8, +26.2] beside four; row 7 read 0.0% quiet and -0.6% [-0.8, -0.4] beside four. No
/// interval from pairs taken in one state of the machine covers the other, so each comparison
/// is measured in both, the one it runs in and one with a competitor on its core, and states
/// the span, which a second run under another load then reaches (bench/main_job.sh: no row's
/// quiet and loaded intervals disjoint in four runs, two or four `yes` beside the loaded one).
PairedEstimate AcrossHostStates(const PairedEstimate& as_run, const PairedEstimate& contended);

/// How many contended pairs to take after a look's as-run pairs, given `as_run_pairs` after
/// them and `contended_pairs` so far: up to `rule.contended_share` of the as-run pairs, and at
/// least kMinimumPairs in all once there are any (an interval needs them). 0 when the share is
/// 0. Never fails.
int ContendedPairsBeforeNextLook(int as_run_pairs, int contended_pairs, const StoppingRule& rule);

/// The half-width at which a comparison near the direction margin stops wherever its end lies:
/// half of `rule.resolution_points` or half of kDirectionMarginPoints, whichever is smaller.
/// Why the margin bounds it: the scene planner times to a coarse resolution (3 points), but
/// whether an end lies beyond the 1.5-point margin is a question of the margin's scale; with
/// half the resolution (1.5) an effect of 2.5 to 3% was chosen in one run and not the next
/// (`open_sea`'s half-size reflection, bench/main_job.sh), while the comparisons far from the
/// margin, most of them, still stop at the coarse resolution. Never fails.
double FinestHalfWidthPoints(const StoppingRule& rule);

/// What the sequential rule says after a look.
enum class StopDecision {
    kContinue,  // take another batch
    kResolved,  // the interval is as narrow as the resolution
    kCapped,    // max_pairs reached first; the achieved resolution is wider than asked
};

/// Applies `rule` to the estimate of the pairs so far. Never fails: an invalid estimate below
/// max_pairs continues, at max_pairs it is capped.
StopDecision DecideStop(const PairedEstimate& estimate, const StoppingRule& rule);

/// True when a look's pairs narrow the interval AcrossHostStates states more if taken with the
/// core shared than as the machine runs. Both estimates must be valid, and the contended interval
/// must set an end of the stated one: both ends (the as-run interval lies strictly inside it), or
/// one end while its half-width per pair is the larger of the two states' (by the square-root law
/// an end moves in by about half-width / (2 pairs) for each pair its state adds).
/// Why: with a competitor on its core a frame's time varies two to five times as much as
/// without (per-pair standard deviation 3-5% against 1-1.7% in the longest comparisons of a main
/// job run of 2026-11-28) and the contended pairs are a share of the as-run ones, so the contended
/// interval is the wider one and sets an end of the stated interval, often both. A comparison held
/// near a boundary by it took as-run pairs to the cap: row 2 read -2.5% [-2.64, -2.36] as run and
/// -2.6% [-3.34, -1.77] contended after 363 as-run pairs. Where contention moves the change, the
/// contended interval sets one end only, and that was the one deciding: the planner's half-size
/// reflection for `open_sea` (`tidepool plan --scene open_sea`), beside two `yes`, read -2.8%
/// [-3.17, -2.48] after 400 as-run pairs and -2.2% [-2.97, -1.44] after 200 contended ones, so the
/// plan kept the full reflection where the quiet runs chose the half size (2026-11-28). Never
/// fails.
bool ContendedPairsNarrowMore(const PairedEstimate& as_run, const PairedEstimate& contended);

/// How many contended pairs a look takes, with no as-run pairs, while ContendedPairsNarrowMore:
/// as PairsBeforeNextLook counts as-run pairs (`rule.batch_pairs`, or a quarter of the pairs so
/// far), up to `rule.max_pairs` contended pairs in all; 0 there. Never fails.
int ContendedPairsForLook(int contended_pairs, const StoppingRule& rule);

/// DecideStop for the interval AcrossHostStates states after `contended_pairs` contended pairs:
/// the rule's pair counts (its boundary clause's `boundary_pairs` and its cap `max_pairs`) count
/// the larger of the two states' pairs, since a look at which contended pairs narrow the stated
/// interval more takes contended pairs only (ContendedPairsNarrowMore). Never fails.
StopDecision DecideStopAcrossStates(const PairedEstimate& stated, int contended_pairs,
                                    const StoppingRule& rule);

/// True when stopping now could give a verdict the next run would not: an end of the interval
/// lies within `rule.boundary_standard_errors` standard errors of the direction margin it is
/// compared with (the upper end with -kDirectionMarginPoints, the lower end with
/// +kDirectionMarginPoints); or the estimate lies beyond a margin and the interval still reaches
/// over it (the estimate, not the interval's midpoint: the interval AcrossHostStates states is
/// lopsided about it; the planner's half-size reflection beside two `yes` read -2.7% [-3.6,
/// +0.8] in frame time after 20 pairs, its midpoint inside the margin, and stopped unclaimed
/// where the quiet run claimed -2.4% [-2.9, -1.7] after 150); or one of `rule.boundaries_points`
/// lies inside the interval or within that many standard errors of an end. False when invalid.
bool NearVerdictBoundary(const PairedEstimate& estimate, const StoppingRule& rule);

/// True when one of `rule.boundaries_points` lies strictly inside the interval. False when
/// invalid.
bool HoldsVerdictBoundary(const PairedEstimate& estimate, const StoppingRule& rule);

/// True when an end of the interval lies within `rule.boundary_standard_errors` standard errors
/// of one of `rule.boundaries_points` that the interval does not hold. Its verdict there is
/// firm (the same or a different magnitude) and would turn into the other firm one if the end
/// crossed: a contradiction between two runs. (The direction margins are left out: an end
/// crossing one turns a direction into "below resolution", never into the opposite direction.)
/// False when invalid.
bool NearUnheldBoundary(const PairedEstimate& estimate, const StoppingRule& rule);

/// A guess, for progress reports, of the pairs the rule will have stopped at: the pairs so far
/// when DecideStop stops at this estimate; otherwise the mean, over where the true change may
/// lie (normal about the estimate, with the interval's standard error), of the first later look at
/// which DecideStop would stop if the interval narrowed by the square-root law about that change;
/// at most max_pairs. Without an interval, the first look at or after `fallback`.
int PairsExpectedAtStop(const PairedEstimate& estimate, const StoppingRule& rule, int fallback);

/// A guess like PairsExpectedAtStop's (the mean over where the true change may lie of the first
/// later look at which the rule would stop) from the pairs' own spread instead of their
/// interval: the median log ratio and its spread (1.4826 times the median absolute deviation, a
/// standard deviation's worth for normal noise), with later looks' stated intervals as the
/// contended pairs would give them at the same centre and spread (the as-run and contended
/// intervals narrow by the square-root law in their own pairs, so the contended one, of fewer
/// pairs, is the wider). 0 when there are fewer than kMinimumPairs pairs, the sides differ in
/// length, or a time is not finite and positive.
int PairsExpectedFromSpread(const std::vector<double>& baseline_ms,
                            const std::vector<double>& candidate_ms, const StoppingRule& rule);

/// The progress line's guess of the pairs a comparison will have stopped at, from its as-run
/// pairs so far and the interval it states (`stated`): the pairs so far when the rule stops
/// now; otherwise the geometric mean of PairsExpectedAtStop (from `stated`) and
/// PairsExpectedFromSpread (from the pairs), PairsExpectedAtStop alone when the spread gives
/// none, and the spread's guess alone when there are fewer pairs than `rule.min_pairs` (a
/// probe's). Why the spread alone then: a rank interval from ten pairs reaches into the tails of
/// the noise, where from more pairs it reaches into its core only, so the square-root law from it
/// guesses long when the noise has heavy tails. On the 2-core host of 2026-12-07 the pairs'
/// standard deviation was 1.5 to 4 times their normal-equivalent median absolute deviation, and,
/// replayed over eight main-job halves (`bench/replay_comparisons`), the guessed comparison work
/// missed at its worst moment by a median 27% (at most 38%) this way, against 64% (109%) with
/// the interval alone and 43% (53%) with both guesses' geometric mean.
/// (On the earlier host the interval alone had done better than both, a median 21% against 46%
/// over 11 halves of 2026-11-27, when a probe's contended pairs were not yet pulled in; those
/// recordings are gone, so the spread alone was never replayed there.)
/// AProbesGuessFollowsTheRulesStopsOnHeavyTailedNoise simulates it. Why two guesses after the
/// probe: they err in opposite directions. An interval from 10 to 20 pairs is
/// often far wider than the square-root law makes it later (one disturbed pair of ten contended
/// ones read [-1.5, +14.7] where twenty read [-1.8, -0.3]), so the interval's guess is long. The
/// spread ignores a contended state that reads differently and the tails that widen a rank
/// interval, so its guess is short. Replayed look by look, probes first, over the comparisons
/// of 34 main-job runs (2026-11-26 and 27, quiet and beside two `yes`; 12 more runs had every
/// comparison stop at its first look, which every guess gets right), the comparisons' guessed
/// work missed the actual at its worst moment by up to 114% of the run's time with the
/// interval's guess (median run 36%, 24 runs beyond 20%), 60% with the spread's (median 16%,
/// 11 runs), and 41% with their geometric mean (median 14%, 8 runs).
int PairsExpectedFromPairs(const std::vector<double>& baseline_ms,
                           const std::vector<double>& candidate_ms, const PairedEstimate& stated,
                           const StoppingRule& rule, int fallback);

/// The pairs of each state a comparison is expected to have when its rule stops.
struct ExpectedPairs {
    int as_run = 0;
    int contended = 0;
};

/// `candidate_ms` with the pair of the lowest and the pair of the highest log ratio moved in to
/// the next lowest and next highest (one pair at each end, winsorised), the baselines as they are;
/// as given when the sides differ in length, a time is not finite and positive, or there are
/// fewer than 3 pairs. Never fails.
std::vector<double> WithOuterRatiosPulledIn(const std::vector<double>& baseline_ms,
                                            const std::vector<double>& candidate_ms);

/// The normal-equivalent spread of the pairs' log ratios (candidate over baseline): 1.4826 times
/// their median absolute deviation. NaN with fewer than kMinimumPairs pairs, sides of different
/// lengths, or a time that is not finite and positive.
double LogRatioSpread(const std::vector<double>& baseline_ms,
                      const std::vector<double>& candidate_ms);

/// `candidate_ms` with every pair's log ratio moved towards their median by one factor, so that
/// their LogRatioSpread is `spread`; as given when it is already at most `spread`, or either is
/// not finite. Never fails.
std::vector<double> WithSpreadAtMost(const std::vector<double>& baseline_ms,
                                     const std::vector<double>& candidate_ms, double spread);

/// The spreads (LogRatioSpread) of a run's probes so far, by state.
struct ProbeSpreads {
    std::vector<double> as_run;
    std::vector<double> contended;
};

/// A probe's candidate times as its guesses take them, by state.
struct ProbeCandidates {
    std::vector<double> as_run;
    std::vector<double> contended;
};

/// How many times the median of the run's probes' spreads (of its state, this probe's included,
/// once there are three and it is above 0) a probe's spread may be before its pairs count as
/// disturbed.
inline constexpr double kDisturbedProbeSpread = 3.0;

/// Adds a probe's spreads to `spreads` and returns its candidate times for its guesses: each
/// state's as given, or, when its spread is more than kDisturbedProbeSpread times the median of
/// the run's probes' spreads, pulled in to that (WithSpreadAtMost). Why: a few probes' ten pairs
/// are disturbed, and one such probe set the progress line's guess: in a traced quiet main job
/// of 2026-12-07, row 11's ten as-run log ratios ran from -33% to +40% (spread 17%, its next ten
/// pairs' under 2%, the median probe's 1.3%); its probe guessed 1,214 frames, it took 174, and
/// with three more such probes the line read up to 49% long for a minute. Replayed over 15
/// main-job halves of that day (`bench/replay_comparisons`), the guessed comparison work missed
/// at its worst moment by at most 47% (median 26%) this way, against 95% (26%), and at the start,
/// every comparison at its probe's guess, by at most 32% (median 16%) against 76% (22%). Three
/// times: a spread from ten pairs is itself uncertain by about a third, and the comparisons of
/// one run differ in their noise by up to about twice, so less would pull in honest probes
/// (twice did about as well on these runs, at most 43% and 35%; four times less well, 61% and
/// 34%).
ProbeCandidates UndisturbedProbe(const std::vector<double>& baseline_ms,
                                 const std::vector<double>& candidate_ms,
                                 const std::vector<double>& contended_baseline_ms,
                                 const std::vector<double>& contended_candidate_ms,
                                 ProbeSpreads& spreads);

/// The progress line's guess of both states' pairs at the stop, from the pairs so far (as run:
/// `baseline_ms`, `candidate_ms`; with the core shared: `contended_baseline_ms`,
/// `contended_candidate_ms`) and their estimates (`as_run`, `contended`; the interval they
/// state is AcrossHostStates's). While contended pairs narrow that interval more
/// (ContendedPairsNarrowMore; at a probe, before the as-run pairs reach `rule.min_pairs`, too)
/// the looks to come take contended pairs alone: the as-run pairs stay at least at
/// `rule.min_pairs`, and the contended ones are PairsExpectedFromPairs's guess with the contended
/// pairs in the as-run ones' place (the stated interval then narrows with them, and the rule
/// counts them, DecideStopAcrossStates). Otherwise the as-run pairs are PairsExpectedFromPairs's
/// guess and the contended ones their share of them (ContendedPairsBeforeNextLook). Never fewer
/// than so far. Why: guessing the as-run pairs alone, with their contended share beside them,
/// counted a contended-bound comparison's pairs one and a half times over; the progress line of
/// the first main-job run after the change read 75% long 13 s in (2026-11-28).
/// At a probe (fewer as-run pairs than `rule.min_pairs`) each state's pairs are taken
/// WithOuterRatiosPulledIn first, and their estimates worked out again from them. Why: with ten
/// pairs a state's 95% interval runs between the ninth lowest and ninth highest of 55 Walsh
/// averages, and one disturbed pair sets ten of them: row 7's probe in a quiet main job read
/// [-1.0, +20.3] as run, was guessed at the cap (400 + 200 pairs) and took 20 + 20; the line
/// read 41% long 12 s in (2026-11-28). Replayed over the ten main-job halves of that day on this
/// rule (`bench/replay_comparisons`), the guessed comparison work missed at its worst moment by
/// at most 16% (median 14%) this way, against 51% (median 22%); over 16 earlier halves, whose
/// recordings end before this rule stops some comparisons, 44% (median 22%) against 141% (38%).
/// On the four halves recorded after (not used to choose it) 38, 12, 19 and 15% against 31, 17,
/// 10 and 14%; over all fourteen of that day at most 38% (median 14%) against 51% (20%). Pulling
/// the ends in at every look gained nothing (17%, median 14%). Never fails.
ExpectedPairs PairsExpectedAcrossStates(const std::vector<double>& baseline_ms,
                                        const std::vector<double>& candidate_ms,
                                        const std::vector<double>& contended_baseline_ms,
                                        const std::vector<double>& contended_candidate_ms,
                                        const PairedEstimate& as_run,
                                        const PairedEstimate& contended, const StoppingRule& rule,
                                        int fallback);

/// The order a run probes its `comparisons` in: from both ends of their list in turn (0, n-1, 1,
/// n-2, ...). Why: until every probe is in, the progress line guesses the comparisons not yet
/// probed from those that are (the mean of their guesses), so the probes that come first must
/// be a fair sample. In list order they were not: the default matrix lists the whitepaper rows
/// near a verdict's boundary first and the reflection techniques, which stop at the minimum,
/// last. Replayed over eight main-job halves of 2026-12-07 (`bench/replay_comparisons`), the
/// guess of the comparisons not yet probed after eight probes was 0.61 to 2.62 times the frames
/// they took (median 1.44) in this order, against 1.27 to 3.81 (median 2.82) in list order; the
/// progress line of the quietest of those runs read 103% long 13 s in.
std::vector<std::size_t> ProbeOrder(std::size_t comparisons);

/// How many pairs to take before the next look, given `pairs` so far: up to min_pairs first,
/// then max(batch_pairs, pairs / 4), never past max_pairs. Never fails (0 at max_pairs).
int PairsBeforeNextLook(int pairs, const StoppingRule& rule);

/// "resolved", "capped" or "continue"; never fails.
const char* StopDecisionName(StopDecision decision);
/// The decision StopDecisionName gives `name`; nothing for any other text.
std::optional<StopDecision> StopDecisionFromName(std::string_view name);

}  // namespace tidepool::base
