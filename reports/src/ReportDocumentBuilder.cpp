#include "ReportDocumentBuilder.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/CoreCompetitor.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/report/ReportCharts.h"
#include "tidepool/report/WhitepaperTable.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "ReportText.h"
#include <fmt/format.h>

namespace tidepool::report {
namespace {

using base::kVisibleDifferenceThreshold;
using doc::Block;
using doc::Heading;
using doc::Paragraph;
using doc::ParagraphStyle;
using doc::Span;

std::string ConfigurationLabel(const ComparisonSide& side) {
    if (side.configuration == nullptr) {
        return fmt::format("{} (missing)", side.preset);
    }
    return fmt::format("{}{}", side.configuration->id, side.configuration->ok ? "" : " FAILED");
}

// ---------------------------------------------------------------------------------------------
// Environment and settings in display order.

std::vector<std::pair<std::string, std::string>> MethodFacts(const ReportModel& model) {
    const stagefiles::ResultsFile& results = model.inputs->results;
    const stagefiles::ResultsEnvironment& env = results.environment;
    const stagefiles::ResultsSettings& settings = results.settings;
    const stagefiles::ResultsTiming& timing = results.timing;
    // Each field as the file wrote it: text as it is, whole numbers as they are, fractional
    // ones to a tenth, and a number JSON wrote as null (NaN) as a dash.
    struct Text {
        std::string operator()(const std::string& value) const { return value; }
        std::string operator()(int value) const { return std::to_string(value); }
        std::string operator()(double value) const {
            return std::isnan(value) ? "–" : fmt::format("{:.1f}", value);
        }
        std::string operator()(const std::optional<double>& value) const {
            return value ? (*this)(*value) : "–";
        }
    };
    const Text text;
    std::vector<std::pair<std::string, std::string>> facts = {
            {"CPU", text(env.cpu_model)},
            {"Renderer", text(env.gl_renderer)},
            {"GL version", text(env.gl_version)},
            {"Mesa version", text(env.mesa_version)},
            {"Backend", text(env.backend) + " (" + text(env.context_api) + ")"},
            {"LP_NUM_THREADS", text(env.lp_num_threads)},
            {"Build", text(env.build_type)},
            {"Git revision", text(env.git_revision)},
            {"Render command", text(env.command)},
            {"Run started (UTC)", text(results.started_utc)},
            {"Run wall time (s)", text(results.wall_seconds)},
            {"Render size", text(settings.width) + "x" + text(settings.height)},
            {"Timing view", text(settings.timing_view)},
            {"Warm-up frames", text(settings.warmup_frames)},
            {"Coarse frames per configuration", text(settings.coarse_frames)},
            {"Pairs of instrumented frames per comparison", text(settings.pass_frames)},
            {"Rendering threads (workers)", text(settings.workers)},
            {"Resolution asked of each comparison (± points)", text(timing.resolution_points)},
            {"Pairs per comparison (min, max)",
             text(timing.min_pairs) + ", " + text(timing.max_pairs)},
            {"Pairs with the core shared, per as-run pair (at least)",
             text(timing.contended_share)},
            {"Estimator", text(timing.estimator)},
            {"Timing method", text(settings.timing_method)},
            {"Compared on", ClockName(model.clock) + " time: " + model.inputs->clock_reason},
            {"Animation time (s)", text(settings.animation_time_s)},
            {"Config", text(settings.config)},
    };
    return facts;
}

// Why a comparison's first pairs are taken early, when they were (a minimum above the probe's
// pairs, on one rendering thread: runner::ProbesComparisons); "" otherwise.
std::string ProbeText(const stagefiles::ResultsFile& results) {
    if (results.timing.min_pairs <= base::kMinimumPairs || results.settings.workers > 1) {
        return {};
    }
    return fmt::format(
            "Each comparison's first {} pairs (its probe), with the pairs its first look takes "
            "with the core shared, are taken in the run's first seconds and the rest later, on "
            "from the probe: the pairs of each kind, the looks and the stop are those of one "
            "uninterrupted comparison, both sides are warmed again before going on, and the two "
            "frames of every pair still lie milliseconds apart. The probes tell the progress line "
            "early which comparisons lie near a boundary and will take many pairs. ",
            base::kMinimumPairs);
}

// How frames were timed and compared, and why: the Method section's account of the method as
// built (the figures that support it are in the clock-noise table beside it, from this run).
std::string TimingMethodText(const ReportModel& model) {
    return fmt::format(
            "How the times were taken. Every frame is timed on one clock, chosen from the "
            "renderer string ({}). Each compared pair of configurations is rendered back to "
            "back on one thread, the side that goes first alternating from pair to pair, so the "
            "two frames of a pair lie milliseconds apart and share whatever else the machine is "
            "doing; the change is the Hodges-Lehmann estimate of the per-pair log frame-time "
            "ratios with its 95% Wilcoxon signed-rank interval. Pairs are added (the minimum, "
            "then a quarter more at each look) until the interval's half-width is at most the "
            "resolution asked (±{} points) or the cap is reached, and each row states the "
            "resolution it reached. A comparison near a verdict's boundary keeps taking pairs "
            "until it clears it or reaches half the resolution: an end of its interval within "
            "1.5 standard errors of the direction margin (1.5 points either side of no change), "
            "its estimate beyond the margin while the interval still reaches over it, or an end of "
            "the row's magnitude band (half to twice the whitepaper's figure) inside or near the "
            "interval. Stopping there would give a verdict in one run and another in the next. "
            "An interval that holds an end of the magnitude band goes on past half the "
            "resolution, since an interval on the end decides no magnitude while more pairs may "
            "still decide it, but only until {} pairs (of the state, as run or with the core "
            "shared, that took more): a change that lies on the end took pairs "
            "to the cap and still held it, and the band's edge, its verdict then, contradicts no "
            "other run. From that many pairs on, a comparison stops at the resolution unless an "
            "end of its interval lies near the direction margin or near an end of the band that "
            "it does not hold (a firm verdict that the next run could read the other way). {}"
            "Configurations that no comparison names "
            "get a few coarse "
            "frames each, enough for the accuracy-versus-time chart. Why this method: on a "
            "shared 2-core machine about half of a frame's time variance is slow drift that "
            "adjacent frames share, which pairing milliseconds apart cancels and pairing seconds "
            "apart (rounds over the matrix, as before) does not; rendering on the calling "
            "thread (LP_NUM_THREADS=0) and timing that thread's CPU clock takes the scheduling "
            "of llvmpipe's worker threads and of other processes out of the figure; the rank "
            "estimator ignores the odd disturbed frame. Frames render on one thread by default: "
            "llvmpipe's contexts in one process share one rasteriser lock, so a second rendering "
            "thread bought no throughput, and frames timed beside it moved by more than their "
            "interval; `tidepool run` uses the second core with a second process beside the "
            "render, which runs the stability catalogue and the scene plans, then takes "
            "configurations (images and coarse frames), and any comparison the render has not "
            "begun, off the end of the render's work list. Both sides of a comparison always "
            "render on one thread of one process, pair by pair. The table "
            "below shows, for every comparison "
            "of this run, how noisy "
            "its pairs were on the compared clock and on the wall clock recorded beside it. A "
            "deterministic instruction count (callgrind) was not used: it would time a frame "
            "tens of times slower, and the intervals above already reach the resolution.",
            model.inputs->clock_name.empty() ? std::string("unknown: older results")
                                             : model.inputs->clock_name,
            std::isfinite(model.inputs->resolution_points)
                    ? fmt::format("{:.1f}", model.inputs->resolution_points)
                    : std::string("–"),
            base::StoppingRule{}.boundary_pairs, ProbeText(model.inputs->results));
}

// Why each comparison is also timed with its core shared, and what that did in this run.
std::string HostStatesText(const ReportModel& model) {
    const double share = model.inputs->results.timing.contended_share;
    if (!(share > 0)) {
        return "Host states: this run timed every comparison as the machine ran only "
               "(--contended-share 0), so its intervals hold for the load it ran under; another "
               "load may move a comparison by more than its interval.";
    }
    return fmt::format(
            "Host states. Contention is not only noise: the share of a frame a pass takes "
            "depends on what else the machine runs (caches and cores shared with other jobs), "
            "so a comparison timed on a quiet machine and again beside other jobs can move "
            "systematically, by more than the interval either run states from its own pairs "
            "(bench/main_job.sh times the main job both ways). So every comparison is timed in "
            "two states: as the machine runs, and, after each look's pairs, {:.2g} pairs per "
            "as-run pair (at least {}) while a thread of tidepool's own shares the rendering "
            "thread's core (both pinned to it), walking a {} MiB buffer without a pause the way "
            "another job would, and the other cores stay free. Those pairs vary more, so their "
            "interval is usually the wider one and sets an end of the interval stated, often "
            "both: while it sets both, or one with the larger half-width per pair, a look takes "
            "pairs with the core shared alone, since they narrow the interval stated more (the "
            "table's two pair counts show where each row's went). The change stated is the "
            "as-run "
            "estimate; its interval runs from the lower end of the two states' 95% intervals to "
            "the higher, and the stopping rule and the verdicts use that interval, so a run on a "
            "quiet machine states an interval that reaches a busier state too. The table shows "
            "both states for each whitepaper row.",
            share, base::kMinimumPairs, base::CoreCompetitor::kBufferBytes >> 20);
}

std::vector<std::vector<std::string>> HostStatesTable(const ReportModel& model) {
    std::vector<std::vector<std::string>> rows;
    auto change = [](double ratio) { return Fixed(PerformanceChangePercent(ratio), 1, "%"); };
    auto interval = [](const Interval& ci) {
        return fmt::format("[{}, {}]", Fixed(PerformanceChangePercent(ci.high), 1),
                           Fixed(PerformanceChangePercent(ci.low), 1));
    };
    for (const RowComparison& r : model.rows) {
        const PairedRatio& p = r.ratio;
        rows.push_back({std::to_string(r.row.number), r.row.change,
                        change(p.ratio) + " " + interval(p.as_run_ci), std::to_string(p.pairs),
                        p.contended_pairs > 0
                                ? change(p.contended_ratio) + " " + interval(p.contended_ci)
                                : std::string("–"),
                        std::to_string(p.contended_pairs), interval(p.ci)});
    }
    return rows;
}

std::vector<std::vector<std::string>> ClockNoiseTable(const ReportModel& model) {
    std::vector<std::vector<std::string>> rows;
    for (const ClockNoiseRow& r : model.clock_noise) {
        rows.push_back(
                {r.label, std::to_string(r.pairs), r.decision, Fixed(r.half_width_points, 1, " pt"),
                 Fixed(r.pair_sd_clock_percent, 1, "%"), Fixed(r.pair_sd_wall_percent, 1, "%")});
    }
    return rows;
}

const std::vector<std::string>& ClockNoiseHeader() {
    static const std::vector<std::string> header = {"comparison",
                                                    "pairs",
                                                    "stopped",
                                                    "half-width reached",
                                                    "pair noise, compared clock",
                                                    "pair noise, wall clock"};
    return header;
}

std::string ClockText(const ReportModel& model) {
    return fmt::format(
            "Every comparison (whitepaper rows, split halves, accuracy versus time, the Pareto "
            "frontier, static cost versus time) uses {}. Tables list both medians; \"median ms "
            "({})\" is the one compared.",
            model.inputs->clock_reason, ClockName(model.clock));
}

std::string JsonCell(const nlohmann::json& value) {
    if (value.is_null()) {
        return "–";
    }
    if (value.is_string()) {
        return value.get<std::string>();
    }
    if (value.is_number_float()) {
        const double v = value.get<double>();
        return std::abs(v) >= 1e-3 || v == 0 ? fmt::format("{:.4g}", v) : fmt::format("{:.3e}", v);
    }
    if (value.is_array()) {
        std::string out;
        for (const nlohmann::json& item : value) {
            out += (out.empty() ? "" : ", ") + JsonCell(item);
        }
        return out;
    }
    return tidepool::JsonText(value);
}

// A field of a stage file as a table cell, as JsonCell shows its JSON.
template <typename T>
std::string Cell(const T& value) {
    return JsonCell(nlohmann::json(value));
}

// One table of the Numerical stability section: its key in stability.json, its columns (the
// fields shown, in display order) and a row per entry, "bad" when the entry did not pass.
struct StabilityTable {
    std::string key;
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;
    std::vector<std::string> css;
};

std::vector<StabilityTable> StabilityTables(const stagefiles::StabilityFile& file) {
    StabilityTable cases{"cases",
                         {"name", "description", "kind", "variants_checked", "nan_count",
                          "inf_count", "max_error", "bound", "passed", "fix"},
                         {},
                         {}};
    for (const stagefiles::StabilityCase& c : file.cases) {
        cases.rows.push_back({c.name, c.description, c.kind, Cell(c.variants_checked),
                              Cell(c.nan_count), Cell(c.inf_count), Cell(c.max_error),
                              Cell(c.bound), Cell(c.passed), c.fix});
        cases.css.push_back(c.passed ? "" : "bad");
    }
    StabilityTable precision{"precision",
                             {"expression", "max_abs_error_float", "max_abs_error_fp16",
                              "max_rel_error_fp16", "loses_precision", "note"},
                             {},
                             {}};
    for (const stagefiles::PrecisionEntry& p : file.precision) {
        precision.rows.push_back({p.expression, Cell(p.max_abs_error_float),
                                  Cell(p.max_abs_error_fp16), Cell(p.max_rel_error_fp16),
                                  Cell(p.loses_precision), p.note});
        precision.css.push_back("");  // a finding, not a check
    }
    StabilityTable guards{
            "guards", {"guard", "max_channel_diff_normal_views", "tolerance"}, {}, {}};
    for (const stagefiles::GuardEntry& g : file.guards) {
        guards.rows.push_back({g.guard, Cell(g.max_channel_diff_normal_views), Cell(g.tolerance)});
        guards.css.push_back(g.passed ? "" : "bad");
    }
    return {std::move(cases), std::move(precision), std::move(guards)};
}

// The Scenes section's tables, read from plans.json.
struct SceneTables {
    std::vector<std::vector<std::string>> summary;
    std::vector<std::string> summary_css;
    // Per scene: its name and one row per dropped or kept effect.
    std::vector<std::pair<std::string, std::vector<std::vector<std::string>>>> effects;
    int missed = 0;  // plans whose chosen configuration does not meet the target
};

const std::vector<std::string>& SceneSummaryHeader() {
    static const std::vector<std::string> header = {"scene",
                                                    "chosen configuration",
                                                    "full-effect configuration",
                                                    "time chosen / full (ms)",
                                                    "time change",
                                                    "error vs full (PSNR, SSIM, visible)",
                                                    "target",
                                                    "met",
                                                    "passes / draws / pixels saved"};
    return header;
}

const std::vector<std::string>& SceneEffectHeader() {
    static const std::vector<std::string> header = {"effect", "decision", "PSNR alone",
                                                    "time change alone", "reason"};
    return header;
}

// A PSNR of 99 dB is how plans.json writes "identical" (docs/SCENES.md).
std::string PsnrText(double psnr_db) {
    return psnr_db >= 99.0 ? std::string("identical") : Fixed(psnr_db, 1, " dB");
}

SceneTables BuildSceneTables(const stagefiles::PlansFile& plans) {
    SceneTables t;
    for (const stagefiles::PlannedScene& plan : plans.plans) {
        std::string target;
        for (const auto& [key, bound] :
             {std::pair{"frame_budget_ms", &plan.target.frame_budget_ms},
              std::pair{"max_share_visible", &plan.target.max_share_visible},
              std::pair{"min_psnr_db", &plan.target.min_psnr_db}}) {
            if (*bound) {
                target += (target.empty() ? "" : ", ") + std::string(key) + " " +
                          JsonCell(nlohmann::json(**bound));
            }
        }
        t.missed += plan.met ? 0 : 1;
        std::string errors;
        if (!plan.errors.empty()) {
            errors = " (" + JsonCell(nlohmann::json(plan.errors)) + ")";
        }
        const std::string none = "–";  // a plan that failed chose nothing
        const stagefiles::PlanChoice* c = plan.choice ? &*plan.choice : nullptr;
        t.summary.push_back(
                {plan.scene, (c != nullptr ? c->chosen.id : none) + errors,
                 c != nullptr ? c->full.id : none,
                 c != nullptr ? Fixed(c->time_ms_chosen, 2) + " / " + Fixed(c->time_ms_full, 2)
                              : fmt::format("{0} / {0}", none),
                 c != nullptr ? Signed(c->time_change_percent, 0, "%") : none,
                 c != nullptr ? PsnrText(c->error.psnr_db) + ", SSIM " + Fixed(c->error.ssim, 3) +
                                        ", " + Fixed(c->error.share_visible * 100, 1, "%")
                              : fmt::format("{0}, SSIM {0}, {0}", none),
                 target.empty() ? "–" : target, plan.met ? "met" : "NOT met",
                 c != nullptr ? fmt::format("{} / {} / {}", c->passes_saved, c->draws_saved,
                                            c->pixels_saved)
                              : fmt::format("{0} / {0} / {0}", none)});
        t.summary_css.push_back(plan.met ? "" : "bad");
        std::vector<std::vector<std::string>> effects;
        if (c != nullptr) {
            for (const auto& [list, decision] :
                 {std::pair{&c->dropped, "dropped"}, std::pair{&c->kept, "kept"}}) {
                for (const stagefiles::PlanEffect& e : *list) {
                    effects.push_back({e.effect, decision, PsnrText(e.psnr_change_db),
                                       Signed(e.time_change_percent, 0, "%"), e.reason});
                }
            }
        }
        t.effects.emplace_back(plan.scene, std::move(effects));
    }
    return t;
}

std::string ScenesIntro(const stagefiles::PlansFile& plans) {
    // How the candidates were timed, from plans.json's `timing` (a hand-made file may lack it).
    const stagefiles::PlansTiming& timing = plans.timing;
    std::string how =
            timing.resolution_points > 0
                    ? fmt::format(
                              "each candidate timed against the full effect pair by pair "
                              "until its 95% interval is within +/-{:.1f} points ({} to {} "
                              "pairs)",
                              timing.resolution_points, timing.min_pairs, timing.max_pairs)
                    : std::string("each candidate timed against the full effect pair by pair");
    if (timing.contended_share > 0) {
        how += fmt::format(
                ", as the machine runs and, {:.2g} pairs per as-run pair or more, with a thread "
                "of tidepool's own on the rendering thread's core, the interval spanning both "
                "states",
                timing.contended_share);
    }
    if (timing.missed_target_pairs > 0) {
        how += fmt::format(
                "; in a scene with no frame budget, a candidate whose image misses the target, "
                "which is then never chosen, only for {} pairs as the machine runs, with the "
                "wider interval they give",
                timing.missed_target_pairs);
    }
    return fmt::format(
            "Per scene (scenes/*.yaml), the cheapest configuration whose image meets the scene's "
            "target against the full-effect configuration (docs/SCENES.md), from `tidepool plan` "
            "at {}x{}, {}. Times are the planner's own medians at that size, not the whitepaper "
            "run's; the time change is the paired estimate over per-pair ratios (so it can "
            "differ from the ratio of the two medians), negative = faster. \"PSNR alone\" and "
            "\"time change alone\" are those of the candidate that drops only that effect.",
            plans.size[0], plans.size[1], how);
}

std::string VerdictCss(Verdict verdict) {
    switch (StandingOf(verdict)) {
        case VerdictStanding::kAgrees:
            return "good";
        case VerdictStanding::kAgreesInDirection:
            return "fair";
        case VerdictStanding::kDisagrees:
            return "bad";
        case VerdictStanding::kUndecided:
            return "unknown";
    }
    return "unknown";
}

std::string WhitepaperFigureCell(const WhitepaperRow& row) {
    std::string text = row.whitepaper_text;
    if (row.kind == FigureKind::kDirection) {
        text += fmt::format(" (qualitative: expects {})", DirectionText(row.expected_sign));
    }
    return text;
}

std::string MeasuredCell(const RowComparison& r) {
    if (!std::isfinite(r.change_percent)) {
        return "–";
    }
    const bool faster = r.change_percent >= 0;
    return fmt::format("performance {} by {:.1f}%", faster ? "increased" : "reduced",
                       std::abs(r.change_percent));
}

// "reflection, refraction, main", or "–" when the results do not say.
std::string PassesText(const std::vector<std::string>& passes) {
    std::string out;
    for (const std::string& pass : passes) {
        out += (out.empty() ? "" : ", ") + pass;
    }
    return out.empty() ? std::string("–") : out;
}

std::string DrawCallsText(const std::optional<int>& draw_calls) {
    return draw_calls ? std::to_string(*draw_calls) : std::string("–");
}

std::string PsnrCell(double psnr_db) {
    return std::isinf(psnr_db) && psnr_db > 0 ? std::string("identical") : Fixed(psnr_db, 1);
}

// Performance change with its reading: faster, slower, or no clear change.
std::string TechniqueChangeCell(const TechniqueComparison& t) {
    if (!std::isfinite(t.change_percent)) {
        return "–";
    }
    const std::string reading = t.direction > 0 ? "faster"
                                : t.direction < 0
                                        ? "slower"
                                        : fmt::format("below resolution: |change| < {:.1f}%",
                                                      std::max(std::fabs(t.change_ci.low),
                                                               std::fabs(t.change_ci.high)));
    return Signed(t.change_percent, 1, "%") + ", " + reading;
}

std::string PerViewPsnrCell(const TechniqueComparison& t) {
    std::string out;
    for (const ViewError& v : t.per_view) {
        out += fmt::format(
                "{}{}: {}{}", out.empty() ? "" : "; ", v.view,
                std::isinf(v.psnr_db) ? std::string("identical") : Fixed(v.psnr_db, 1, " dB"),
                v.view == t.worst_view ? " (worst)" : "");
    }
    return out.empty() ? std::string("–") : out;
}

// The rows of the Reflection techniques and Depth optics tables (the same columns; the
// baseline is named in the header).
std::vector<std::string> TechniqueHeader(const ReportModel& model, const std::string& baseline,
                                         const std::string& reading) {
    return {"technique",
            fmt::format("configurations ({} → candidate)", baseline),
            "status",
            "passes per frame",
            "draw calls",
            fmt::format("median ms ({}): {} / candidate", ClockName(model.clock), baseline),
            "performance change (+ = faster)",
            "95% interval",
            fmt::format("PSNR vs {}", baseline),
            "SSIM",
            "visibly different",
            "PSNR per view",
            reading};
}

std::vector<std::string> TechniqueRow(const TechniqueComparison& t) {
    std::string passes = PassesText(t.baseline_passes) + " → " + PassesText(t.candidate_passes);
    if (!t.passes_dropped.empty()) {
        passes += " (no " + PassesText(t.passes_dropped) + " pass)";
    }
    return {fmt::format("{} ({})", t.technique, t.context),
            fmt::format("{} [{}] → {} [{}]", t.baseline.preset, ConfigurationLabel(t.baseline),
                        t.candidate.preset, ConfigurationLabel(t.candidate)),
            t.note.empty() ? std::string("measured") : t.note,
            passes,
            DrawCallsText(t.baseline_draw_calls) + " → " + DrawCallsText(t.candidate_draw_calls),
            Fixed(t.baseline_median_ms, 2) + " / " + Fixed(t.candidate_median_ms, 2),
            TechniqueChangeCell(t),
            IntervalText(t.change_ci, 1, "%"),
            t.HasError() ? PsnrCell(t.psnr_db) : std::string("–"),
            Fixed(t.ssim, 4),
            t.HasError() ? Fixed(t.share_visible * 100, 2, "%") : std::string("–"),
            PerViewPsnrCell(t),
            t.reading};
}

// The row class names the comparison so tools (and tests) can find each one.
std::string TechniqueCss(const TechniqueComparison& t) {
    return fmt::format("{}technique-{}-{}", t.note.empty() ? "" : "bad ", TechniqueKindName(t.kind),
                       t.baseline.preset);
}

std::string ReflectionsIntro(const ReportModel& model) {
    return fmt::format(
            "Each reflection technique against the planar reflection it replaces (the "
            "whitepaper's reflection pass, the REFLECTION axis default), the rest of the frame "
            "equal: `reflection_only` → `cubemap_reflection` and `fourier_reflection`, `full` → "
            "`full_cubemap_reflection` and `full_fourier_reflection`. Passes and draw calls are "
            "one frame's at the timing view ({}); times are medians on the {} clock, and the "
            "change is estimated from pairs of frames as in the whitepaper table (+ = faster; a "
            "direction is called only when the whole 95% interval excludes no change). The error "
            "is against the "
            "planar image, not the reference: PSNR from the mean squared error over every view "
            "both configurations rendered, mean SSIM, the share of pixels visibly different "
            "(more than {:.0f}/255), and PSNR per view, so the view where a technique breaks "
            "stands out. A missing or failed configuration is listed as such.",
            model.inputs->timing_view.empty() ? std::string("–") : model.inputs->timing_view,
            ClockName(model.clock), kVisibleDifferenceThreshold);
}

std::string ReflectionPanelsIntro(const ReportModel& model) {
    const std::string view = model.reflection_panels.empty() ? std::string("–")
                                                             : model.reflection_panels.front().view;
    return fmt::format(
            "The full-effect candidate of each technique at view {} beside planar reflection "
            "(preset `full`), which takes the place the reference has in the Images section, and "
            "their difference (black = identical, red → yellow → white = up to 32/255 and "
            "more).",
            view);
}

std::string OpticsIntro() {
    return "`full` → `full_depth_optics`: extinction, shore foam, soft shore and sun specular "
           "added to the full effect. This is an addition, not a replacement, so the \"error\" "
           "against `full` is how much the image changes, not a loss of accuracy.";
}

std::string GlossaryText() {
    return fmt::format(
            "Performance change is in percent of frame rate as the whitepaper words it (+ = "
            "faster; "
            "\"reduced by 60%\" = -60% = 2.5x the frame time), estimated from pairs of frames "
            "rendered back to back (Hodges-Lehmann estimate of the per-pair log ratios, {:.0f}% "
            "Wilcoxon signed-rank interval); each comparison took pairs until its interval's "
            "half-width reached the stated resolution or the cap, and the table states the "
            "resolution each row reached.",
            kConfidenceLevel * 100);
}

std::string VerdictRuleText(const ReportModel& /*model*/) {
    return fmt::format(
            "Verdicts are decided by the 95% interval, never by the estimate alone. Below "
            "resolution when the interval reaches within ±{1:.1f} points of no change: no "
            "direction is claimed, and the verdict says how small the change must be (|change| "
            "< X%, X the interval's larger end). Why a margin and not 0: contention shifts "
            "comparisons systematically, not only by noise (bench/verdict_stability.sh renders "
            "the compared presets quiet and under load and shows how far), so only a direction "
            "beyond that margin is one a second run will repeat. Opposite when the whole "
            "interval lies beyond the margin on the other side. "
            "For a figure in percent, magnitude agreement is relative: same direction and "
            "magnitude when the whole interval lies within half to twice the whitepaper's figure "
            "(factor {0:.0f}), different magnitude when it lies wholly outside, and the magnitude "
            "at the band's edge, decided neither way, when the interval holds an end of the band "
            "(an effect on the end comes out on either side of it from run to run, so only a "
            "verdict that claims neither side is one a second run will not contradict; the "
            "direction is still claimed). Row 6's \"<1%\" is "
            "negligible as claimed when the whole interval lies within ±{0:.0f}% (beyond the "
            "margin, different magnitude wholly beyond it and at the band's edge holding it). "
            "Rows 8-11 "
            "quote no number, so only the direction is compared. Why relative: a fixed "
            "tolerance in points called a fifth of a figure \"the same magnitude\". The halves of "
            "the pairs (baseline first, candidate first) are compared too, and a disagreement in "
            "sign is said in the reason.",
            kMagnitudeFactor, kDirectionMarginPoints);
}

// The report's larger tables, built together before the sections place them.
struct Tables {
    std::vector<std::string> whitepaper_header = {"#",
                                                  "change",
                                                  "configurations compared (baseline → candidate)",
                                                  "whitepaper's figure",
                                                  "measured here",
                                                  "95% interval",
                                                  "resolution reached",
                                                  "verdict",
                                                  "why",
                                                  "measured per pass",
                                                  "context (fixed prose, not measured)"};
    std::vector<std::vector<std::string>> whitepaper;
    std::vector<std::string> whitepaper_css;
    std::vector<std::string> accuracy_header;  // set by BuildTables (names the clocks)
    std::vector<std::string> frontier_header;
    std::vector<std::string> static_header;
    std::vector<std::string> misleading_header;
    std::vector<std::vector<std::string>> accuracy;
    std::vector<std::string> accuracy_css;
    std::vector<std::vector<std::string>> frontier;
    std::vector<std::vector<std::string>> optimisation;
    std::vector<std::vector<std::string>> static_rows;
    std::vector<std::vector<std::string>> misleading;
    std::vector<std::vector<std::string>> split;
    std::vector<std::vector<std::string>> method;
    std::vector<std::string> reflections_header;
    std::vector<std::vector<std::string>> reflections;
    std::vector<std::string> reflections_css;
    std::vector<std::string> optics_header;
    std::vector<std::vector<std::string>> optics;
    std::vector<std::string> optics_css;
};

std::string Presets(const MeasuredConfiguration& c) {
    std::string out;
    for (const std::string& p : c.presets) {
        out += (out.empty() ? "" : ", ") + p;
    }
    return out;
}

// "median ms (CPU)" and "median ms (wall)", the compared clock first.
std::vector<std::string> MedianHeaders(const ReportModel& model) {
    const TimingClock other =
            model.clock == TimingClock::kCpu ? TimingClock::kWall : TimingClock::kCpu;
    return {fmt::format("median ms ({}, compared)", ClockName(model.clock)),
            fmt::format("median ms ({})", ClockName(other))};
}

// The two medians of `c`, the compared clock first.
std::vector<std::string> MedianCells(const ReportModel& model, const MeasuredConfiguration& c) {
    const TimingClock other =
            model.clock == TimingClock::kCpu ? TimingClock::kWall : TimingClock::kCpu;
    return {Fixed(c.MedianOn(model.clock), 2), Fixed(c.MedianOn(other), 2)};
}

std::vector<std::string> Concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

Tables BuildTables(const ReportModel& model) {
    Tables t;
    const std::vector<std::string> medians = MedianHeaders(model);
    t.accuracy_header =
            Concat(Concat({"configuration", "presets", "passes"}, medians),
                   {"PSNR dB", "SSIM", "1-SSIM", "pixels visibly different", "frontier"});
    t.frontier_header = Concat(Concat({"configuration", "presets", "passes"}, medians),
                               {"1-SSIM", "PSNR dB", "visibly different"});
    t.static_header =
            Concat(Concat({"configuration", "presets", "vertex ops", "fragment ops", "total ops"},
                          medians),
                   {"ops rank", "time rank"});
    t.misleading_header = {"configuration", "total ops", medians.front(),
                           "ops rank",      "time rank", "reading"};
    for (const RowComparison& r : model.rows) {
        t.whitepaper.push_back(
                {std::to_string(r.row.number), r.row.change,
                 fmt::format("{} [{}] → {} [{}]", r.baseline.preset, ConfigurationLabel(r.baseline),
                             r.candidate.preset, ConfigurationLabel(r.candidate)),
                 "whitepaper: " + WhitepaperFigureCell(r.row), MeasuredCell(r),
                 IntervalText(r.change_ci, 1, "%"),
                 std::isfinite(r.resolution_points)
                         ? fmt::format("±{:.1f} points, {} pairs", r.resolution_points,
                                       r.ratio.pairs)
                         : std::string("–"),
                 std::string(VerdictName(r.verdict)), r.verdict_reason,
                 r.measured_why.empty() ? std::string("–") : r.measured_why, r.row.llvmpipe_note});
        // The row class names the row so tools (and the browser test) can find each one.
        t.whitepaper_css.push_back(VerdictCss(r.verdict) + " wp-row-" +
                                   std::to_string(r.row.number));
    }
    for (const AccuracyEntry& e : model.accuracy) {
        const MeasuredConfiguration& c = *e.configuration;
        if (!e.measured) {
            t.accuracy.push_back(
                    Concat(Concat({c.id, Presets(c), c.PassLabel()}, MedianCells(model, c)),
                           {"–", "–", "–", "–", e.note}));
            t.accuracy_css.push_back(c.ok ? "" : "bad");
            continue;
        }
        t.accuracy.push_back(
                Concat(Concat({c.id, Presets(c), c.PassLabel()}, MedianCells(model, c)),
                       {std::isinf(e.psnr_db) ? "identical" : Fixed(e.psnr_db, 1), Fixed(e.ssim, 4),
                        Fixed(e.SsimLoss(), 4), Fixed(e.share_visible * 100, 2, "%"),
                        e.is_reference  ? "reference"
                        : e.on_frontier ? "yes"
                                        : ""}));
        t.accuracy_css.push_back(e.on_frontier ? "frontier" : "");
    }
    for (std::size_t i : model.frontier) {
        const AccuracyEntry& e = model.accuracy[i];
        t.frontier.push_back(Concat(
                Concat({e.configuration->id, Presets(*e.configuration),
                        e.configuration->PassLabel()},
                       MedianCells(model, *e.configuration)),
                {Fixed(e.SsimLoss(), 4), std::isinf(e.psnr_db) ? "identical" : Fixed(e.psnr_db, 1),
                 Fixed(e.share_visible * 100, 2, "%")}));
    }
    for (const RowComparison& r : model.rows) {
        t.optimisation.push_back({std::to_string(r.row.number), r.row.change,
                                  r.baseline.preset + " → " + r.candidate.preset,
                                  Signed(r.time_change_ms, 2, " ms"),
                                  Signed(r.change_percent, 1, "%"), Signed(r.ssim_loss_change, 4),
                                  Signed(r.psnr_change_db, 1, " dB")});
    }
    for (const StaticCostEntry& e : model.static_cost.entries) {
        t.static_rows.push_back(
                Concat(Concat({e.configuration->id, Presets(*e.configuration),
                               std::to_string(e.vertex_ops), std::to_string(e.fragment_ops),
                               std::to_string(e.total_ops)},
                              MedianCells(model, *e.configuration)),
                       {Fixed(e.ops_rank, 1), Fixed(e.time_rank, 1)}));
    }
    for (std::size_t i : model.static_cost.misleading) {
        const StaticCostEntry& e = model.static_cost.entries[i];
        const double gap = e.time_rank - e.ops_rank;
        t.misleading.push_back(
                {e.configuration->id, std::to_string(e.total_ops), Fixed(e.median_ms, 2),
                 Fixed(e.ops_rank, 1), Fixed(e.time_rank, 1),
                 gap > 0 ? fmt::format("slower than its count suggests ({:+.0f} ranks)", gap)
                         : fmt::format("faster than its count suggests ({:+.0f} ranks)", gap)});
    }
    for (const RowComparison& r : model.rows) {
        t.split.push_back({std::to_string(r.row.number),
                           r.baseline.preset + " → " + r.candidate.preset,
                           Signed(r.change_percent, 1, "%"), Signed(r.odd_change_percent, 1, "%"),
                           Signed(r.even_change_percent, 1, "%"),
                           Fixed(r.split.disagreement_percent_points, 1, " pt"),
                           std::to_string(r.ratio.pairs)});
    }
    for (const auto& [key, value] : MethodFacts(model)) {
        t.method.push_back({key, value});
    }
    t.reflections_header = TechniqueHeader(model, "planar", "where it breaks");
    for (const TechniqueComparison& r : model.reflections) {
        t.reflections.push_back(TechniqueRow(r));
        t.reflections_css.push_back(TechniqueCss(r));
    }
    t.optics_header = TechniqueHeader(model, "full", "what it changes");
    for (const TechniqueComparison& r : model.optics) {
        t.optics.push_back(TechniqueRow(r));
        t.optics_css.push_back(TechniqueCss(r));
    }
    return t;
}

// The validation summary's pruned-combinations table: one row per rule of the matrix.
const std::vector<std::string> kPrunedRuleHeader = {"program", "rule", "written at",
                                                    "combinations pruned"};

std::vector<std::vector<std::string>> PrunedRuleTable(const ReportModel& model) {
    std::vector<std::vector<std::string>> rows;
    for (const PrunedRuleRow& row : model.validation.pruned_by_rule) {
        rows.push_back({row.program, row.rule, fmt::format("{}:{}", row.file, row.line),
                        std::to_string(row.count)});
    }
    return rows;
}

std::string ValidationLine(const ReportModel& model) {
    const stagefiles::ManifestCounts& c = model.validation.counts;
    auto n = [](const std::optional<long long>& count) {
        return count ? std::to_string(*count) : std::string("–");
    };
    return fmt::format(
            "{} variants ({} pruned combinations); {} stage slots compiled as {} distinct stage "
            "programs ({} slots shared); {} links; glslang rejected {}. Mesa: {} configurations "
            "rendered, {} failed; glslang and Mesa disagree on {} variant(s).",
            c.variants, c.pruned, n(c.stage_slots), n(c.stage_programs), n(c.shared_stage_slots),
            n(c.links), model.validation.glslang_invalid.size(), model.validation.configurations,
            model.validation.failed.size(), model.validation.disagreements.size());
}

std::string AccuracyIntro() {
    return fmt::format(
            "Every configuration's images against the reference (preset `reference`) at every "
            "view: PSNR over R, G, B (from the mean squared error over views), mean SSIM "
            "(Gaussian 11x11 on luma), and the share of pixels whose largest channel difference "
            "exceeds {:.0f}/255 (about where a difference becomes visible). The chart plots "
            "median frame time against 1 - SSIM; the dashed line is the Pareto frontier "
            "(no configuration is both faster and closer to the reference). Failed configurations "
            "have no point; they are listed in the table as FAILED.",
            kVisibleDifferenceThreshold);
}

// One paragraph a reader can stop after: verdict counts, the frontier, the static-cost fit.
std::string AtAGlance(const ReportModel& model) {
    std::map<Verdict, int> counts;
    std::map<VerdictStanding, int> standings;
    for (const RowComparison& r : model.rows) {
        ++counts[r.verdict];
        ++standings[StandingOf(r.verdict)];
    }
    std::string frontier;
    for (std::size_t i : model.frontier) {
        const MeasuredConfiguration& c = *model.accuracy[i].configuration;
        if (!c.presets.empty()) {
            frontier += (frontier.empty() ? "" : ", ") + c.presets.front();
        }
    }
    return fmt::format(
            "At a glance: of the whitepaper's 11 rows, {} agree in direction and magnitude, {} in "
            "direction only (a qualitative figure, a different magnitude or one at the band's "
            "edge), {} go the opposite way, {} are below the resolution reached and {} failed. {} "
            "of {} configurations are on the time/accuracy Pareto frontier{}. The "
            "static operation count ranks configurations by time with Spearman rho {}.{}",
            standings[VerdictStanding::kAgrees], standings[VerdictStanding::kAgreesInDirection],
            counts[Verdict::kOpposite], counts[Verdict::kBelowResolution], counts[Verdict::kFailed],
            model.frontier.size(), model.accuracy.size(),
            frontier.empty() ? "" : " (presets among them: " + frontier + ")",
            Fixed(model.static_cost.spearman_rho, 2),
            model.failed_configurations > 0
                    ? fmt::format(" {} configuration(s) FAILED.", model.failed_configurations)
                    : std::string());
}
Paragraph Note(std::string_view text) {
    return {ParagraphStyle::kNote, doc::SpansWithCode(text)};
}

Paragraph Body(std::string text) {
    return {ParagraphStyle::kBody, {{Span::Kind::kText, std::move(text)}}};
}

doc::Table TableOf(std::vector<std::string> header, std::vector<std::vector<std::string>> rows,
                   std::vector<std::string> row_classes = {}) {
    return {std::move(header), std::move(rows), std::move(row_classes), ""};
}

// One image panel: its figures and the three images (this configuration, what it is compared
// with, their difference), or its note instead.
doc::ImagePanel Panel(const ImagePanel& p, const PanelFiles& files,
                      const std::array<std::string, 3>& data_uris) {
    doc::ImagePanel panel{p.title, "view " + p.view, PanelId(p), "", p.note, {}};
    if (!p.note.empty()) {
        return panel;
    }
    panel.summary = fmt::format("PSNR {} dB, SSIM {}, {} of pixels visibly different",
                                std::isinf(p.psnr_db) ? "inf" : Fixed(p.psnr_db, 1),
                                Fixed(p.ssim, 4), Fixed(p.share_visible * 100, 2, "%"));
    const std::array<std::string, 3> links = {files.image, files.reference, files.heat};
    const std::array<std::string, 3> captions = {"this configuration", p.reference_caption,
                                                 "difference"};
    for (std::size_t k = 0; k < 3; ++k) {
        panel.images.push_back({captions[k], p.title + " " + captions[k], links[k], data_uris[k]});
    }
    return panel;
}

doc::Section WhitepaperSection(const ReportModel& model, const Tables& t) {
    return {"1. The whitepaper's cost table, measured",
            "whitepaper",
            "Whitepaper table",
            {Note(GlossaryText()), Note(VerdictRuleText(model)),
             doc::Figure{WhitepaperChartSvg(model), "charts/whitepaper.svg", "whitepaper chart"},
             TableOf(t.whitepaper_header, t.whitepaper, t.whitepaper_css)}};
}

doc::Section AccuracySection(const ReportModel& model, const Tables& t) {
    doc::Table every = TableOf(t.accuracy_header, t.accuracy, t.accuracy_css);
    every.folded_under = "Every configuration";
    return {"2. What accuracy costs in time",
            "accuracy",
            "Accuracy vs time",
            {Note(AccuracyIntro()),
             doc::Figure{AccuracyChartSvg(model), "charts/accuracy.svg", "accuracy vs time"},
             Heading{"Pareto frontier", ""}, TableOf(t.frontier_header, t.frontier),
             Heading{"Each whitepaper optimisation: time saved, error added", ""},
             TableOf({"#", "change", "baseline → candidate", "Δ median frame time",
                      "performance change", "Δ(1-SSIM)", "Δ PSNR"},
                     t.optimisation),
             std::move(every)}};
}

doc::Section StaticCostSection(const ReportModel& model, const Tables& t) {
    const Paragraph intro{
            ParagraphStyle::kNote,
            {{Span::Kind::kText, "The compiler's static operation count (vertex + fragment "},
             {Span::Kind::kCode, "total_ops"},
             {Span::Kind::kText,
              " of the water variant, from the manifest) beside the measured median frame time, "
              "for configurations with default pass options. Spearman rank correlation: "},
             {Span::Kind::kStrong, Fixed(model.static_cost.spearman_rho, 3)},
             {Span::Kind::kText,
              (model.static_cost.note.empty() ? "" : " (" + model.static_cost.note + ")") +
                      ". Red points: the configurations where the count misleads most. The "
                      "count sees only the water shader, not the passes a feature adds "
                      "(refraction renders the scene once more), nor that llvmpipe samples "
                      "textures in software."}}};
    doc::Table all = TableOf(t.static_header, t.static_rows);
    all.folded_under = "All";
    return {"3. Static cost versus measured time",
            "static",
            "Static cost",
            {intro,
             doc::Figure{StaticCostChartSvg(model), "charts/static_cost.svg",
                         "static cost vs time"},
             Heading{"Where the static count misleads (largest rank disagreements)", ""},
             TableOf(t.misleading_header, t.misleading), std::move(all)}};
}

doc::Section ValidationSection(const ReportModel& model) {
    doc::Section s{
            "4. Validation summary", "validation", "Validation", {Body(ValidationLine(model))}};
    if (!model.validation.failed.empty()) {
        std::vector<std::vector<std::string>> rows;
        std::vector<std::string> css;
        for (const MeasuredConfiguration* c : model.validation.failed) {
            std::string why =
                    c->driver_valid ? "GL error " + c->gl_error : "Mesa compile/link failed";
            for (const std::string& m : c->driver_messages) {
                why += "; " + m;
            }
            rows.push_back({c->id, "FAILED", why});
            css.push_back("bad");
        }
        s.blocks.emplace_back(Heading{"Failed configurations", ""});
        s.blocks.emplace_back(TableOf({"configuration", "status", "why"}, rows, css));
    }
    if (!model.validation.disagreements.empty()) {
        std::vector<std::vector<std::string>> rows;
        for (const VerdictDisagreementRow& d : model.validation.disagreements) {
            rows.push_back({d.variant, d.glslang_valid ? "valid" : "invalid",
                            d.mesa_valid ? "valid" : "invalid"});
        }
        s.blocks.emplace_back(Heading{"glslang / Mesa disagreements", ""});
        s.blocks.emplace_back(TableOf({"variant", "glslang", "Mesa"}, rows));
    }
    if (!model.validation.pruned_by_rule.empty()) {
        s.blocks.emplace_back(Heading{"Pruned combinations per rule", ""});
        s.blocks.emplace_back(
                Note("Counted by the first rule each combination breaks; `tidepool "
                     "expand --pruned` lists them."));
        s.blocks.emplace_back(TableOf(kPrunedRuleHeader, PrunedRuleTable(model)));
    }
    return s;
}

doc::Section ImagesSection(const ReportModel& model, const std::vector<PanelFiles>& files,
                           const std::vector<std::array<std::string, 3>>& data_uris) {
    doc::Section s{"5. Images",
                   "images",
                   "Images",
                   {Note("Each key configuration beside the reference, and their difference "
                         "(black = identical, red → yellow → white = up to 32/255 and more). "
                         "Click an image for the full-size file (when the report folder is "
                         "intact).")}};
    for (std::size_t i = 0; i < model.panels.size(); ++i) {
        s.blocks.emplace_back(Panel(model.panels[i], files[i], data_uris[i]));
    }
    return s;
}

doc::Section MethodSection(const ReportModel& model, const Tables& t) {
    const Paragraph split{
            ParagraphStyle::kBody,
            {{Span::Kind::kText,
              "Split-half reliability: every comparison computed again from the pairs where the "
              "baseline went first and from those where the candidate went first. Largest "
              "disagreement: "},
             {Span::Kind::kStrong,
              Fixed(model.largest_split_half_disagreement, 1, " percentage points")},
             {Span::Kind::kText,
              fmt::format(" (row {}). A verdict is only as firm as its interval; a finer "
                          "--resolution narrows it.",
                          model.largest_split_half_row)}}};
    return {"6. Method and noise",
            "method",
            "Method and noise",
            {Note(ClockText(model)), Body(TimingMethodText(model)), Body(HostStatesText(model)),
             TableOf({"#", "comparison", "as run [95%]", "pairs", "core shared [95%]", "pairs",
                      "stated interval"},
                     HostStatesTable(model)),
             TableOf(ClockNoiseHeader(), ClockNoiseTable(model)),
             TableOf({"setting", "value"}, t.method), split,
             TableOf({"#", "comparison", "all pairs", "candidate first", "baseline first",
                      "disagreement", "pairs"},
                     t.split),
             Note(RowDefinitionChanges())}};
}

doc::Section StabilitySection(const ReportModel& model) {
    doc::Section s{"7. Numerical stability", "stability", "Numerical stability", {}};
    if (!model.inputs->stability) {
        s.blocks.emplace_back(
                Note(model.inputs->stability_error.empty()
                             ? StabilityHowTo()
                             : model.inputs->stability_error + ". " + StabilityHowTo()));
        return s;
    }
    for (StabilityTable& table : StabilityTables(*model.inputs->stability)) {
        s.blocks.emplace_back(Heading{table.key, ""});
        if (table.rows.empty()) {
            s.blocks.emplace_back(Body("(none)"));
        } else {
            s.blocks.emplace_back(
                    TableOf(table.columns, std::move(table.rows), std::move(table.css)));
        }
    }
    return s;
}

doc::Section ScenesSection(const ReportModel& model) {
    doc::Section s{"8. Scenes", "scenes", "Scenes", {}};
    if (!model.inputs->plans) {
        s.blocks.emplace_back(Note(model.inputs->plans_error.empty()
                                           ? PlansHowTo()
                                           : model.inputs->plans_error + ". " + PlansHowTo()));
        return s;
    }
    const SceneTables scenes = BuildSceneTables(*model.inputs->plans);
    s.blocks.emplace_back(Note(ScenesIntro(*model.inputs->plans)));
    if (scenes.missed > 0) {
        s.blocks.emplace_back(
                Paragraph{ParagraphStyle::kWarning,
                          {{Span::Kind::kStrong,
                            fmt::format("{} scene(s) NOT met their target.", scenes.missed)}}});
    }
    s.blocks.emplace_back(TableOf(SceneSummaryHeader(), scenes.summary, scenes.summary_css));
    for (const auto& [scene, rows] : scenes.effects) {
        s.blocks.emplace_back(Heading{scene, ""});
        if (rows.empty()) {
            s.blocks.emplace_back(Body("No effect was offered for dropping."));
        } else {
            s.blocks.emplace_back(TableOf(SceneEffectHeader(), rows));
        }
    }
    return s;
}

doc::Section ReflectionsSection(const ReportModel& model, const Tables& t,
                                const std::vector<PanelFiles>& files,
                                const std::vector<std::array<std::string, 3>>& data_uris) {
    doc::Section s{
            "9. Reflection techniques",
            "reflections",
            "Reflection techniques",
            {Note(ReflectionsIntro(model)),
             TableOf(t.reflections_header, t.reflections, t.reflections_css),
             Heading{"Where the reflection breaks: full effect beside planar reflection", ""},
             Note(ReflectionPanelsIntro(model))}};
    for (std::size_t j = 0; j < model.reflection_panels.size(); ++j) {
        const std::size_t i = ReflectionPanelOffset(model) + j;
        s.blocks.emplace_back(Panel(model.reflection_panels[j], files[i], data_uris[i]));
    }
    s.blocks.emplace_back(Heading{"Depth optics", "depth-optics"});
    s.blocks.emplace_back(Note(OpticsIntro()));
    s.blocks.emplace_back(TableOf(t.optics_header, t.optics, t.optics_css));
    return s;
}

}  // namespace

std::size_t ReflectionPanelOffset(const ReportModel& model) {
    return model.panels.size();
}

doc::Document BuildReportDocument(const ReportModel& model, const std::vector<PanelFiles>& files,
                                  const std::vector<std::array<std::string, 3>>& data_uris) {
    doc::Document document;
    document.title = "tidepool report: " + model.options.name;
    document.byline = {
            ParagraphStyle::kNote,
            {{Span::Kind::kText, "Generated " + model.options.generated_utc + " from "},
             {Span::Kind::kCode, model.inputs->manifest_path.string()},
             {Span::Kind::kText, " and "},
             {Span::Kind::kCode, model.inputs->results_path.string()},
             {Span::Kind::kText, ". Figures labelled "},
             {Span::Kind::kStrong, "whitepaper"},
             {Span::Kind::kText,
              " are quoted from Imagination's \"Shader Based Water Effects\" (measured on a "
              "PowerVR SGX-class GPU); everything else was measured here on Mesa llvmpipe."}}};
    if (model.failed_configurations > 0) {
        document.lead.emplace_back(Paragraph{
                ParagraphStyle::kWarning,
                {{Span::Kind::kStrong,
                  fmt::format("{} configuration(s) FAILED", model.failed_configurations)},
                 {Span::Kind::kText, " to compile or render; they are shown as failed below."}}});
    }
    document.lead.emplace_back(
            Paragraph{ParagraphStyle::kLead, doc::SpansWithCode(AtAGlance(model))});
    const Tables tables = BuildTables(model);
    document.sections = {WhitepaperSection(model, tables),
                         AccuracySection(model, tables),
                         StaticCostSection(model, tables),
                         ValidationSection(model),
                         ImagesSection(model, files, data_uris),
                         MethodSection(model, tables),
                         StabilitySection(model),
                         ScenesSection(model),
                         ReflectionsSection(model, tables, files, data_uris)};
    return document;
}

}  // namespace tidepool::report
