// Everything the report shows, computed once from the saved inputs: the whitepaper table with
// verdicts, accuracy against the reference versus time with its Pareto frontier, static cost
// versus measured time, the validation summary, image panels, method and noise, and the
// reflection techniques (cube map, Fourier) against planar reflection with the depth optics.
// The report document (ReportDocument.h) and data.json (ReportWriter.h) are built from this
// model alone, so HTML, Markdown and data.json always agree.
#pragma once

#include "tidepool/base/PairedEstimate.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/report/ConfigurationComparison.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/WhitepaperTable.h"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::report {

/// The preset whose images every other configuration is compared with.
inline constexpr std::string_view kReferencePreset = "reference";

/// Magnitude agreement is relative: a measured change agrees with a whitepaper figure f when
/// its whole 95% interval lies within f / kMagnitudeFactor .. f x kMagnitudeFactor, differs
/// when the whole interval lies outside, and is not decided when the interval holds an end of
/// that band. For the "<1%" row the band is |change| <= 1% x kMagnitudeFactor. Why relative
/// and decided by the interval: a fixed tolerance in points called -1.9% "the same magnitude"
/// as -11%, and verdicts decided by the estimate alone flipped between runs whenever the
/// estimate sat near a boundary. Why an interval holding an end decides nothing: "overlaps the
/// band" called row 4's +7.0% [+6.6, +7.2] the same magnitude as the whitepaper's +3.5% (band up
/// to 7%), while the next run's +7.4% [+7.0, +7.7] differed: an effect on a band's end is on both
/// sides of it in turn, and only a verdict that claims neither side is one a second run cannot
/// contradict.
inline constexpr double kMagnitudeFactor = 2.0;

/// A direction is claimed only beyond this margin (base/PairedEstimate.h says why).
inline constexpr double kDirectionMarginPoints = base::kDirectionMarginPoints;

/// How many configurations the static-cost section lists as most misleading.
inline constexpr std::size_t kMisleadingCount = 6;

/// The verdict of one whitepaper row, decided by its 95% interval.
enum class Verdict {
    kSameDirectionAndMagnitude,         // the whole interval lies in the figure's magnitude band
    kSameDirectionDifferentMagnitude,   // the figure's direction, the whole interval outside it
    kSameDirectionMagnitudeAtBandEdge,  // the figure's direction, the interval holds an end of
                                        // the band: the magnitude is not decided
    kSameDirectionOnly,                 // the figure's direction; the figure is qualitative
    kNegligibleAsClaimed,               // a "<1%" row whose interval lies within the band
    kOpposite,                          // the whole interval on the other side of no change
    kBelowResolution,                   // the interval reaches within kDirectionMarginPoints of
                                        // no change: no direction
    kFailed,                            // a configuration failed or is missing
};

/// A stable lower-case name of `verdict` for tables and JSON; never fails.
std::string_view VerdictName(Verdict verdict);

/// How a verdict stands against the whitepaper, the one grouping the report's table and chart
/// colour by: agrees (in magnitude, or negligible as claimed), agrees in direction (only the
/// direction is claimed or the magnitude differs), disagrees (opposite, or failed), undecided
/// (below resolution).
enum class VerdictStanding { kAgrees, kAgreesInDirection, kDisagrees, kUndecided };
VerdictStanding StandingOf(Verdict verdict);

/// True when `verdict` makes a claim another run could contradict: a magnitude (agreeing,
/// different, negligible), the opposite direction, or a direction the figure states (of a
/// qualitative figure, or of a percent figure whose magnitude is at the band's edge). "Below
/// resolution" is not firm. Never fails.
bool IsFirmVerdict(Verdict verdict, FigureKind kind);

/// Grades a measured paired ratio against a row by its 95% interval (as a performance change,
/// + = faster): below resolution when the interval reaches within kDirectionMarginPoints of no
/// change ("|change| < X%", X the larger end); opposite when it lies beyond the margin on the
/// other side; for a percent figure, same direction and magnitude when it lies within
/// kMagnitudeFactor's band, different magnitude when it lies wholly outside, and the magnitude
/// at the band's edge when it holds an end; for "<1%", negligible as claimed when the interval
/// lies within the band and, beyond the margin, different magnitude or at the band's edge as for
/// a percent figure; direction only for qualitative figures. `reason` says
/// why in one line, with the interval and, when `split` (may be null) shows the two halves of the
/// pairs on opposite sides, that too. Never fails (no ratio is kFailed).
Verdict GradeRow(const WhitepaperRow& row, const PairedRatio& measured, const SplitHalf* split,
                 std::string* reason);

/// The performance changes (percent points, + = faster) at which GradeRow's verdict for `row`
/// changes besides the direction margins: the ends of a percent figure's magnitude band on its
/// side of no change (those a frame rate can reach: a loss of 100% or more cannot be measured),
/// +/- the "<1%" band, none for a qualitative figure. The runner keeps timing
/// a row while its interval holds or nears one (base::StoppingRule::boundaries_points), so that
/// the verdict does not depend on where one run happened to stop. Never fails.
std::vector<double> VerdictBoundaries(const WhitepaperRow& row);

/// One side of a comparison.
struct ComparisonSide {
    std::string preset;
    const MeasuredConfiguration* configuration = nullptr;  // null when no configuration has it
};

/// A whitepaper row as measured here.
struct RowComparison {
    WhitepaperRow row;
    ComparisonSide baseline;
    ComparisonSide candidate;
    PairedRatio ratio;  // candidate / baseline frame time over the pairs
    double change_percent = std::numeric_limits<double>::quiet_NaN();     // + = faster
    Interval change_ci;                                                   // of change_percent
    double resolution_points = std::numeric_limits<double>::quiet_NaN();  // achieved half-width
    // "pairs of frames rendered back to back" (", by the process beside the render" when `run`'s
    // second process timed them) or "one pair per timing round" (older results).
    std::string pairs_source;
    // Measured "why": each pass's time in both configurations and the pass that changed most,
    // with its share of the frame; "" when the results have no per-pass times.
    std::string measured_why;
    SplitHalf split;
    double odd_change_percent = std::numeric_limits<double>::quiet_NaN();
    double even_change_percent = std::numeric_limits<double>::quiet_NaN();
    Verdict verdict = Verdict::kFailed;
    std::string verdict_reason;
    // What the change costs in image quality (candidate minus baseline; NaN when unknown).
    double time_change_ms = std::numeric_limits<double>::quiet_NaN();
    double ssim_loss_change = std::numeric_limits<double>::quiet_NaN();
    double psnr_change_db = std::numeric_limits<double>::quiet_NaN();
};

/// A configuration's image error against the reference and its time.
struct AccuracyEntry {
    const MeasuredConfiguration* configuration = nullptr;
    bool measured = false;  // has a time and an image error (false for failed configurations)
    double median_ms = std::numeric_limits<double>::quiet_NaN();  // on the model's clock
    double psnr_db = std::numeric_limits<double>::quiet_NaN();    // from the mean MSE over views
    double ssim = std::numeric_limits<double>::quiet_NaN();       // mean over views
    double share_visible = std::numeric_limits<double>::quiet_NaN();  // mean over views, 0..1
    int views_compared = 0;
    bool on_frontier = false;
    bool is_reference = false;
    std::string note;  // why it is not measured, when it is not

    /// 1 - SSIM, the error axis of the chart.
    double SsimLoss() const { return 1.0 - ssim; }
};

/// A variant's static operation count beside its time.
struct StaticCostEntry {
    const MeasuredConfiguration* configuration = nullptr;
    int vertex_ops = 0;
    int fragment_ops = 0;
    int total_ops = 0;
    double median_ms = std::numeric_limits<double>::quiet_NaN();  // on the model's clock
    double ops_rank = 0;   // 1 = fewest operations (ties averaged)
    double time_rank = 0;  // 1 = fastest
};

/// Static cost versus measured time.
struct StaticCostAnalysis {
    std::vector<StaticCostEntry> entries;  // default-pass configurations with a static cost
    double spearman_rho = std::numeric_limits<double>::quiet_NaN();
    std::vector<std::size_t> misleading;  // indices into entries, largest |rank gap| first
    std::string note;                     // why there is no correlation, when there is none
};

/// A pair of verdicts that differ between glslang and Mesa.
struct VerdictDisagreementRow {
    std::string variant;
    bool glslang_valid = false;
    bool mesa_valid = false;
};

/// How many combinations one rule of the variant matrix pruned (the manifest's pruned_by_rule).
struct PrunedRuleRow {
    std::string program;
    std::string rule;
    std::string file;
    int line = 0;
    std::uint64_t count = 0;
};

/// The compiler's and the driver's verdicts.
struct ValidationSummary {
    stagefiles::ManifestCounts counts;          // the manifest's counts
    std::vector<std::string> glslang_invalid;   // variant ids glslang rejected
    std::vector<PrunedRuleRow> pruned_by_rule;  // every rule, declaration order
    int configurations = 0;
    std::vector<const MeasuredConfiguration*> failed;  // configurations not ok
    std::vector<VerdictDisagreementRow> disagreements;
    std::vector<std::string> run_diagnostics;  // results.json diagnostics (GCC-style text)
};

/// A configuration's image at a view beside the reference's and their difference.
struct ImagePanel {
    std::string title;  // the preset(s), e.g. "full_no_fog (row 4)"
    const MeasuredConfiguration* configuration = nullptr;  // null when no configuration has it
    std::string view;
    base::RgbaImage image;
    base::RgbaImage reference;
    base::RgbaImage heat_map;
    // Whose image `reference` is: the reference preset, or (in the Reflection techniques
    // section) the planar counterpart the candidate is compared with.
    std::string reference_preset = std::string(kReferencePreset);
    std::string reference_caption = "reference";
    double psnr_db = std::numeric_limits<double>::quiet_NaN();
    double ssim = std::numeric_limits<double>::quiet_NaN();
    double share_visible = std::numeric_limits<double>::quiet_NaN();
    std::string note;  // why there is no image, when there is none
};

/// What a TechniqueComparison measures.
enum class TechniqueKind {
    kCubemapReflection,  // the sky cube map instead of the planar reflection pass (seeds/001)
    kFourierReflection,  // per-vertex Fourier terrain horizon instead of the pass (seeds/004)
    kDepthOptics,        // extinction, shore foam, soft shore and sun specular added (seeds/003)
};

/// A stable lower-case name of `kind` for JSON and CSS ("cubemap", "fourier", "depth-optics");
/// never fails.
std::string_view TechniqueKindName(TechniqueKind kind);

/// One view's image error of a candidate against its baseline.
struct ViewError {
    std::string view;
    double psnr_db = std::numeric_limits<double>::quiet_NaN();  // +infinity when identical
    double ssim = std::numeric_limits<double>::quiet_NaN();
    double share_visible = std::numeric_limits<double>::quiet_NaN();  // 0..1
};

/// A technique against its baseline: a reflection technique against the planar reflection it
/// replaces, or the depth optics against the full effect they are added to. Missing or failed
/// configurations keep their entry, with `note` saying which and NaN figures.
struct TechniqueComparison {
    TechniqueKind kind = TechniqueKind::kCubemapReflection;
    std::string technique;    // "cube-map reflection", "Fourier reflection", "depth optics"
    std::string context;      // what both sides share: "reflection only", "full effect"
    ComparisonSide baseline;  // the planar reflection (or the full effect, for the optics)
    ComparisonSide candidate;
    // Pass names of one frame at the timing view (empty when unknown: older results, missing
    // or failed configuration) and the baseline's passes the candidate does not run.
    std::vector<std::string> baseline_passes;
    std::vector<std::string> candidate_passes;
    std::vector<std::string> passes_dropped;
    std::optional<int> baseline_draw_calls;  // per frame at the timing view
    std::optional<int> candidate_draw_calls;
    double baseline_median_ms = std::numeric_limits<double>::quiet_NaN();  // model's clock
    double candidate_median_ms = std::numeric_limits<double>::quiet_NaN();
    PairedRatio ratio;  // candidate / baseline frame time over the pairs
    double change_percent = std::numeric_limits<double>::quiet_NaN();  // + = faster
    Interval change_ci;                                                // of change_percent
    // +1 faster, -1 slower: the whole interval lies on that side of no change (as GradeRow's
    // direction); 0 when it does not or nothing was measured.
    int direction = 0;
    // Image error of the candidate against the baseline over every view both have images for:
    // PSNR from the mean squared error over views (+infinity when identical), mean SSIM, mean
    // share of visibly different pixels; NaN when no view was compared.
    double psnr_db = std::numeric_limits<double>::quiet_NaN();
    double ssim = std::numeric_limits<double>::quiet_NaN();
    double share_visible = std::numeric_limits<double>::quiet_NaN();
    int views_compared = 0;
    std::vector<ViewError> per_view;  // in the candidate's view order
    std::string worst_view;           // the view of lowest PSNR when 2+ views differ; else empty
    double worst_psnr_db = std::numeric_limits<double>::quiet_NaN();
    // One line: where the technique breaks (reflections) or what the addition changes (optics),
    // naming the worst view when there is one.
    std::string reading;
    // Why figures are missing (a configuration missing or FAILED, no paired time, no common
    // view); "" when everything was measured.
    std::string note;

    /// True when both sides rendered and at least one view was compared.
    bool HasError() const { return views_compared > 0; }
};

/// How noisy one comparison's pairs were on the compared clock and on the wall clock beside it:
/// what the choice of clock buys, measured in this run.
struct ClockNoiseRow {
    std::string label;
    int pairs = 0;
    std::string decision;  // "resolved" or "capped"
    double half_width_points = std::numeric_limits<double>::quiet_NaN();
    // Standard deviation of the per-pair log frame-time ratio, in percent.
    double pair_sd_clock_percent = std::numeric_limits<double>::quiet_NaN();
    double pair_sd_wall_percent = std::numeric_limits<double>::quiet_NaN();
};

/// Options of a report build.
struct ReportOptions {
    std::string name = "default";
    std::string generated_utc;             // supplied by the caller (the library reads no clock)
    std::vector<std::string> panel_views;  // views shown in the image panels; empty: timing view
};

/// The whole report.
struct ReportModel {
    ReportOptions options;
    const ReportInputs* inputs = nullptr;  // the model points into these; keep them alive
    // The clock every time below is on (inputs->clock): ratios, medians, Pareto, static cost.
    TimingClock clock = TimingClock::kWall;
    const MeasuredConfiguration* reference = nullptr;
    std::vector<RowComparison> rows;
    std::vector<AccuracyEntry> accuracy;  // one per configuration, run order
    std::vector<std::size_t> frontier;    // indices into accuracy, by time
    StaticCostAnalysis static_cost;
    ValidationSummary validation;
    std::vector<ImagePanel> panels;
    // Reflection techniques against planar reflection: (reflection_only -> cubemap_reflection),
    // (reflection_only -> fourier_reflection), (full -> full_cubemap_reflection),
    // (full -> full_fourier_reflection), in that order, always all four.
    std::vector<TechniqueComparison> reflections;
    // The full_* candidate of each reflection technique beside planar `full` at the panel view;
    // `reference` here is the planar image, not the reference preset's.
    std::vector<ImagePanel> reflection_panels;
    std::vector<TechniqueComparison> optics;  // (full -> full_depth_optics)
    std::vector<ClockNoiseRow> clock_noise;   // one per recorded comparison
    double largest_split_half_disagreement = std::numeric_limits<double>::quiet_NaN();
    int largest_split_half_row = 0;
    int failed_configurations = 0;
};

/// What BuildReportModel produced: the model, or an error naming the file at fault.
struct ReportModelResult {
    std::optional<ReportModel> model;
    std::string error;  // "" on success
};

/// Computes every section from `inputs`. Fails (no model, `error` starting with the path) when
/// an image a configuration that rendered claims cannot be read, or when two images of one view
/// differ in size (against the reference, or within a technique's pair). Failed or missing
/// configurations are kept and marked, never dropped. A missing reference leaves the accuracy
/// figures NaN with a note.
ReportModelResult BuildReportModel(const ReportInputs& inputs, const ReportOptions& options);

/// Two presets whose configurations the report compares in time.
struct PresetPair {
    std::string label;     // "row 4", or "cube-map reflection (full effect)"
    std::string baseline;  // preset names
    std::string candidate;
    std::vector<double> boundaries_points;  // VerdictBoundaries of a whitepaper row; else none
};

/// Every pair the report compares: the 11 whitepaper rows, then the reflection techniques and
/// the depth optics; the runner times exactly these pairs. Never fails.
std::vector<PresetPair> ComparedPresetPairs();

/// Rank correlation and largest rank gaps of static counts versus times, for tests and the
/// model. Ranks average ties. Fails softly: rho NaN and `note` set when fewer than 3 entries.
StaticCostAnalysis AnalyseStaticCost(std::vector<StaticCostEntry> entries);

}  // namespace tidepool::report
