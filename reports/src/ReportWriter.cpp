#include "tidepool/report/ReportWriter.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/report/ReportCharts.h"
#include "tidepool/report/WhitepaperTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <sstream>

#include "ReportText.h"
#include <fmt/format.h>

namespace tidepool::report {
namespace {

using base::kVisibleDifferenceThreshold;
using base::RgbaImage;

nlohmann::json Num(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// A Markdown table cell: pipes would end the cell, newlines the row.
std::string Cell(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '|') {
            out += "\\|";
        } else if (c == '\n') {
            out += ' ';
        } else {
            out += c;
        }
    }
    return out;
}

std::string ConfigurationLabel(const ComparisonSide& side) {
    if (side.configuration == nullptr) {
        return fmt::format("{} (missing)", side.preset);
    }
    return fmt::format("{}{}", side.configuration->id, side.configuration->ok ? "" : " FAILED");
}

std::string FigureKindName(FigureKind kind) {
    switch (kind) {
        case FigureKind::kPercent:
            return "percent";
        case FigureKind::kNegligible:
            return "negligible";
        case FigureKind::kDirection:
            return "direction-only";
    }
    return "percent";
}

std::string Base64(const std::string& bytes) {
    static constexpr char kAlphabet[] =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const auto n = (static_cast<unsigned>(static_cast<unsigned char>(bytes[i])) << 16) |
                       (static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 1])) << 8) |
                       static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 2]));
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += kAlphabet[(n >> 6) & 63];
        out += kAlphabet[n & 63];
    }
    if (i < bytes.size()) {
        unsigned n = static_cast<unsigned>(static_cast<unsigned char>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) {
            n |= static_cast<unsigned>(static_cast<unsigned char>(bytes[i + 1])) << 8;
        }
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string ReadBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

// Box-filters `image` down by an integer `factor` (1 returns it unchanged).
RgbaImage Downscale(const RgbaImage& image, int factor) {
    if (factor <= 1 || image.width < factor || image.height < factor) {
        return image;
    }
    RgbaImage out;
    out.width = image.width / factor;
    out.height = image.height / factor;
    out.pixels.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) *
                      4);
    const int area = factor * factor;
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            for (int channel = 0; channel < 4; ++channel) {
                int sum = 0;
                for (int dy = 0; dy < factor; ++dy) {
                    for (int dx = 0; dx < factor; ++dx) {
                        const auto index = (static_cast<std::size_t>(y * factor + dy) *
                                                    static_cast<std::size_t>(image.width) +
                                            static_cast<std::size_t>(x * factor + dx)) *
                                                   4 +
                                           static_cast<std::size_t>(channel);
                        sum += image.pixels[index];
                    }
                }
                out.pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                            static_cast<std::size_t>(x)) *
                                   4 +
                           static_cast<std::size_t>(channel)] =
                        static_cast<std::uint8_t>((sum + area / 2) / area);
            }
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Environment and settings in display order.

std::vector<std::pair<std::string, std::string>> MethodFacts(const ReportModel& model) {
    const nlohmann::json& results = model.inputs->results;
    const nlohmann::json env = results.value("environment", nlohmann::json::object());
    const nlohmann::json settings = results.value("settings", nlohmann::json::object());
    const auto timing_entry = results.find("timing");
    const nlohmann::json timing = timing_entry != results.end() && timing_entry->is_object()
                                          ? *timing_entry
                                          : nlohmann::json::object();
    auto text = [](const nlohmann::json& object, const char* key) -> std::string {
        auto it = object.find(key);
        if (it == object.end() || it->is_null()) {
            return "–";
        }
        if (it->is_number_float()) {
            return fmt::format("{:.1f}", it->get<double>());
        }
        return it->is_string() ? it->get<std::string>() : it->dump();
    };
    std::vector<std::pair<std::string, std::string>> facts = {
            {"CPU", text(env, "cpu_model")},
            {"Renderer", text(env, "gl_renderer")},
            {"GL version", text(env, "gl_version")},
            {"Mesa version", text(env, "mesa_version")},
            {"Backend", text(env, "backend") + " (" + text(env, "context_api") + ")"},
            {"LP_NUM_THREADS", text(env, "lp_num_threads")},
            {"Build", text(env, "build_type")},
            {"Git revision", text(env, "git_revision")},
            {"Render command", text(env, "command")},
            {"Run started (UTC)", text(results, "started_utc")},
            {"Run wall time (s)", text(results, "wall_seconds")},
            {"Render size", text(settings, "width") + "x" + text(settings, "height")},
            {"Timing view", text(settings, "timing_view")},
            {"Warm-up frames", text(settings, "warmup_frames")},
            {"Coarse frames per configuration", text(settings, "coarse_frames")},
            {"Instrumented frames per compared configuration", text(settings, "pass_frames")},
            {"Rendering threads (workers)", text(settings, "workers")},
            {"Resolution asked of each comparison (± points)", text(timing, "resolution_points")},
            {"Pairs per comparison (min, max)",
             text(timing, "min_pairs") + ", " + text(timing, "max_pairs")},
            {"Estimator", text(timing, "estimator")},
            {"Timing method", text(settings, "timing_method")},
            {"Compared on", ClockName(model.clock) + " time: " + model.inputs->clock_reason},
            {"Animation time (s)", text(settings, "animation_time_s")},
            {"Config", text(settings, "config")},
    };
    return facts;
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
            "resolution it reached. A comparison whose interval ends within 1.5 standard errors "
            "of a verdict's boundary (1.5 points either side of no change) keeps taking pairs "
            "until it clears it or reaches half the resolution: stopping there would give a "
            "direction in one run and none in the next. Configurations that no comparison names "
            "get a few coarse "
            "frames each, enough for the accuracy-versus-time chart. Why this method: on a "
            "shared 2-core machine about half of a frame's time variance is slow drift that "
            "adjacent frames share, which pairing milliseconds apart cancels and pairing seconds "
            "apart (rounds over the matrix, as before) does not; rendering on the calling "
            "thread (LP_NUM_THREADS=0) and timing that thread's CPU clock takes the scheduling "
            "of llvmpipe's worker threads and of other processes out of the figure; the rank "
            "estimator ignores the odd disturbed frame. Throughput comes back from several "
            "rendering threads, each with its own GL context, both sides of a comparison always "
            "on one thread. The table below shows, for every comparison of this run, how noisy "
            "its pairs were on the compared clock and on the wall clock recorded beside it. A "
            "deterministic instruction count (callgrind) was not used: it would time a frame "
            "tens of times slower, and the intervals above already reach the resolution.",
            model.inputs->clock_name.empty() ? std::string("unknown: older results")
                                             : model.inputs->clock_name,
            std::isfinite(model.inputs->resolution_points)
                    ? fmt::format("{:.1f}", model.inputs->resolution_points)
                    : std::string("–"));
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

// The columns of each stability table, in display order.
const std::vector<std::pair<std::string, std::vector<std::string>>>& StabilityTables() {
    static const std::vector<std::pair<std::string, std::vector<std::string>>> tables = {
            {"cases",
             {"name", "description", "kind", "variants_checked", "nan_count", "inf_count",
              "max_error", "bound", "passed", "fix"}},
            {"precision",
             {"expression", "max_abs_error_float", "max_abs_error_fp16", "max_rel_error_fp16",
              "loses_precision", "note"}},
            {"guards", {"guard", "max_channel_diff_normal_views", "tolerance"}},
    };
    return tables;
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

// A JSON number as text with `digits` decimals, "–" when absent or not a number.
std::string JsonFixed(const nlohmann::json& object, const char* key, int digits,
                      std::string_view unit = "") {
    auto it = object.find(key);
    return it != object.end() && it->is_number() ? Fixed(it->get<double>(), digits, unit)
                                                 : std::string("–");
}

std::string JsonSigned(const nlohmann::json& object, const char* key, int digits,
                       std::string_view unit = "") {
    auto it = object.find(key);
    return it != object.end() && it->is_number() ? Signed(it->get<double>(), digits, unit)
                                                 : std::string("–");
}

std::string JsonText(const nlohmann::json& object, const char* key) {
    auto it = object.find(key);
    if (it == object.end() || it->is_null()) {
        return "–";
    }
    return it->is_string() ? it->get<std::string>() : it->dump();
}

// The Scenes section's tables, read from plans.json (CheckPlans vetted the shape).
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

SceneTables BuildSceneTables(const nlohmann::json& plans) {
    SceneTables t;
    const nlohmann::json empty = nlohmann::json::object();
    for (const nlohmann::json& plan : plans.value("plans", nlohmann::json::array())) {
        const std::string scene = JsonText(plan, "scene");
        const nlohmann::json& chosen =
                plan.contains("chosen") && plan["chosen"].is_object() ? plan["chosen"] : empty;
        const nlohmann::json& full =
                plan.contains("full") && plan["full"].is_object() ? plan["full"] : empty;
        const nlohmann::json& error =
                plan.contains("error") && plan["error"].is_object() ? plan["error"] : empty;
        std::string target;
        if (auto it = plan.find("target"); it != plan.end() && it->is_object()) {
            for (const auto& [key, value] : it->items()) {
                target += (target.empty() ? "" : ", ") + key + " " + JsonCell(value);
            }
        }
        const bool met = plan.value("met", false);
        t.missed += met ? 0 : 1;
        // 99 dB is how plans.json writes "identical" (docs/SCENES.md).
        const std::string psnr = error.contains("psnr_db") && error["psnr_db"].is_number() &&
                                                 error["psnr_db"].get<double>() >= 99.0
                                         ? std::string("identical")
                                         : JsonFixed(error, "psnr_db", 1, " dB");
        std::string visible = "–";
        if (error.contains("share_visible") && error["share_visible"].is_number()) {
            visible = Fixed(error["share_visible"].get<double>() * 100, 1, "%");
        }
        std::string errors;
        if (auto it = plan.find("errors"); it != plan.end() && it->is_array() && !it->empty()) {
            errors = " (" + JsonCell(*it) + ")";
        }
        t.summary.push_back(
                {scene, JsonText(chosen, "id") + errors, JsonText(full, "id"),
                 JsonFixed(plan, "time_ms_chosen", 2) + " / " + JsonFixed(plan, "time_ms_full", 2),
                 JsonSigned(plan, "time_change_percent", 0, "%"),
                 psnr + ", SSIM " + JsonFixed(error, "ssim", 3) + ", " + visible,
                 target.empty() ? "–" : target, met ? "met" : "NOT met",
                 JsonText(plan, "passes_saved") + " / " + JsonText(plan, "draws_saved") + " / " +
                         JsonText(plan, "pixels_saved")});
        t.summary_css.push_back(met ? "" : "bad");
        std::vector<std::vector<std::string>> effects;
        for (const auto& [key, decision] :
             {std::pair<const char*, const char*>{"dropped", "dropped"}, {"kept", "kept"}}) {
            for (const nlohmann::json& e : plan.value(key, nlohmann::json::array())) {
                if (!e.is_object()) {
                    continue;
                }
                const bool identical = e.contains("psnr_change_db") &&
                                       e["psnr_change_db"].is_number() &&
                                       e["psnr_change_db"].get<double>() >= 99.0;
                effects.push_back({JsonText(e, "effect"), decision,
                                   identical ? std::string("identical")
                                             : JsonFixed(e, "psnr_change_db", 1, " dB"),
                                   JsonSigned(e, "time_change_percent", 0, "%"),
                                   JsonText(e, "reason")});
            }
        }
        t.effects.emplace_back(scene, std::move(effects));
    }
    return t;
}

std::string ScenesIntro(const nlohmann::json& plans) {
    std::string size = "–";
    if (auto it = plans.find("size"); it != plans.end() && it->is_array() && it->size() == 2) {
        size = (*it)[0].dump() + "x" + (*it)[1].dump();
    }
    return fmt::format(
            "Per scene (scenes/*.yaml), the cheapest configuration whose image meets the scene's "
            "target against the full-effect configuration (docs/SCENES.md), from `tidepool plan` "
            "at {} with {} paired rounds of {} frames. Times are the planner's own medians at "
            "that size, not the whitepaper run's; the time change is the median of per-round "
            "ratios (so it can differ from the ratio of the two medians), negative = faster. "
            "\"PSNR alone\" and \"time change alone\" are those of the candidate that drops "
            "only that effect.",
            size, JsonText(plans, "rounds"), JsonText(plans, "frames_per_round"));
}

std::string VerdictCss(Verdict verdict) {
    switch (verdict) {
        case Verdict::kSameDirectionAndMagnitude:
            return "good";
        case Verdict::kNegligibleAsClaimed:
            return "good";
        case Verdict::kSameDirectionDifferentMagnitude:
            return "fair";
        case Verdict::kSameDirectionOnly:
            return "fair";
        case Verdict::kOpposite:
            return "bad";
        case Verdict::kBelowResolution:
            return "unknown";
        case Verdict::kFailed:
            return "bad";
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

// Relative file names of a panel's images.
struct PanelFiles {
    std::string image;
    std::string reference;
    std::string heat;
};

std::string PanelStem(const ImagePanel& panel) {
    std::string stem = panel.configuration != nullptr && !panel.configuration->presets.empty()
                               ? panel.configuration->presets.front()
                               : std::string("configuration");
    for (char& c : stem) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') {
            c = '_';
        }
    }
    return stem;
}

// The Reflection techniques section's panels follow the image section's in every per-panel
// list (files, data: URIs), so panel j of the section is at this offset plus j.
std::size_t ReflectionPanelOffset(const ReportModel& model) {
    return model.panels.size();
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

// ---------------------------------------------------------------------------------------------
// Markdown and HTML share this walk: each section is emitted by both writers from one model.

struct Page {
    const ReportModel& model;
    const std::vector<PanelFiles>& files;
    const std::vector<std::array<std::string, 3>>* uris;  // HTML only: data: URIs per panel
};

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
            "magnitude when the interval overlaps half to twice the whitepaper's figure (factor "
            "{0:.0f}), different magnitude when it lies wholly outside. Row 6's \"<1%\" is "
            "negligible as claimed when the whole interval lies within ±{0:.0f}%. Rows 8-11 "
            "quote no number, so only the direction is compared. Why relative: a fixed "
            "tolerance in points called a fifth of a figure \"the same magnitude\". The halves of "
            "the pairs (baseline first, candidate first) are compared too, and a disagreement in "
            "sign is said in the reason.",
            kMagnitudeFactor, kDirectionMarginPoints);
}

}  // namespace

std::string WhitepaperTableText(const ReportModel& model) {
    std::string out = fmt::format("compared on {} time\n", ClockName(model.clock));
    out += fmt::format("{:>2}  {:<26} {:<26} {:>20} {:>10} {:>20}  {}\n", "#", "baseline",
                       "candidate", "whitepaper", "measured", "95% CI", "verdict");
    for (const RowComparison& r : model.rows) {
        std::string figure = r.row.kind == FigureKind::kPercent
                                     ? Signed(r.row.whitepaper_percent, 1, "%")
                             : r.row.kind == FigureKind::kNegligible
                                     ? std::string("<1% slower")
                                     : "qualitative, " + DirectionText(r.row.expected_sign);
        out += fmt::format("{:>2}  {:<26} {:<26} {:>20} {:>10} {:>20}  {}\n", r.row.number,
                           r.baseline.preset, r.candidate.preset, figure,
                           Signed(r.change_percent, 1, "%"), IntervalText(r.change_ci, 1, "%"),
                           VerdictName(r.verdict));
    }
    return out;
}

nlohmann::json ReportToJson(const ReportModel& model) {
    nlohmann::json json;
    json["schema"] = kReportSchema;
    json["version"] = kReportSchemaVersion;
    json["name"] = model.options.name;
    json["generated_utc"] = model.options.generated_utc;
    json["inputs"] = {
            {"manifest", model.inputs->manifest_path.string()},
            {"results", model.inputs->results_path.string()},
            {"stability", model.inputs->stability
                                  ? nlohmann::json(model.inputs->stability_path.string())
                                  : nlohmann::json(nullptr)},
            {"plans", model.inputs->plans ? nlohmann::json(model.inputs->plans_path.string())
                                          : nlohmann::json(nullptr)}};
    json["method"] = {
            {"clock", TimingClockName(model.clock)},
            {"clock_reason", model.inputs->clock_reason},
            {"clock_name", model.inputs->clock_name},
            {"magnitude_factor", kMagnitudeFactor},
            {"resolution_points", Num(model.inputs->resolution_points)},
            {"confidence_level", kConfidenceLevel},
            {"estimator",
             "Hodges-Lehmann estimate of per-pair log frame-time ratios, "
             "Wilcoxon signed-rank interval"},
            {"visible_difference_threshold", kVisibleDifferenceThreshold},
            {"reference_preset", kReferencePreset},
            {"largest_split_half_disagreement_percent_points",
             Num(model.largest_split_half_disagreement)},
            {"largest_split_half_row", model.largest_split_half_row},
            {"environment", model.inputs->results.value("environment", nlohmann::json::object())},
            {"settings", model.inputs->results.value("settings", nlohmann::json::object())}};
    nlohmann::json noise = nlohmann::json::array();
    for (const ClockNoiseRow& r : model.clock_noise) {
        noise.push_back({{"label", r.label},
                         {"pairs", r.pairs},
                         {"decision", r.decision},
                         {"half_width_points", Num(r.half_width_points)},
                         {"pair_sd_clock_percent", Num(r.pair_sd_clock_percent)},
                         {"pair_sd_wall_percent", Num(r.pair_sd_wall_percent)}});
    }
    json["method"]["clock_noise"] = std::move(noise);
    auto side = [&model](const ComparisonSide& s) {
        nlohmann::json j = {{"preset", s.preset}};
        if (s.configuration != nullptr) {
            j["configuration"] = s.configuration->id;
            j["passes"] = {{"reflection_size", s.configuration->reflection_size},
                           {"low_res_water", s.configuration->low_res_water},
                           {"clip", s.configuration->clip},
                           {"culling", s.configuration->culling}};
            j["ok"] = s.configuration->ok;
            j["median_ms"] = Num(s.configuration->MedianOn(model.clock));
            j["median_wall_ms"] = Num(s.configuration->median_ms);
            j["median_cpu_ms"] = Num(s.configuration->cpu_median_ms);
        } else {
            j["configuration"] = nullptr;
            j["ok"] = false;
        }
        return j;
    };
    nlohmann::json rows = nlohmann::json::array();
    for (const RowComparison& r : model.rows) {
        rows.push_back(
                {{"number", r.row.number},
                 {"change", r.row.change},
                 {"whitepaper_figure", r.row.whitepaper_text},
                 {"whitepaper_percent", Num(r.row.whitepaper_percent)},
                 {"figure_kind", FigureKindName(r.row.kind)},
                 {"expected_direction", DirectionText(r.row.expected_sign)},
                 {"baseline", side(r.baseline)},
                 {"candidate", side(r.candidate)},
                 {"frame_time_ratio", Num(r.ratio.ratio)},
                 {"frame_time_ratio_ci", {Num(r.ratio.ci.low), Num(r.ratio.ci.high)}},
                 {"pairs", r.ratio.pairs},
                 {"resolution_points", Num(r.resolution_points)},
                 {"pairs_source", r.pairs_source},
                 {"measured_why", r.measured_why},
                 {"clock", TimingClockName(model.clock)},
                 {"measured_percent", Num(r.change_percent)},
                 {"measured_percent_ci", {Num(r.change_ci.low), Num(r.change_ci.high)}},
                 {"verdict", VerdictName(r.verdict)},
                 {"firm", IsFirmVerdict(r.verdict, r.row.kind)},
                 {"verdict_reason", r.verdict_reason},
                 {"llvmpipe_note", r.row.llvmpipe_note},
                 {"split_half",
                  {{"odd_rounds_percent", Num(r.odd_change_percent)},
                   {"even_rounds_percent", Num(r.even_change_percent)},
                   {"disagreement_percent_points", Num(r.split.disagreement_percent_points)}}},
                 {"accuracy_cost",
                  {{"time_change_ms", Num(r.time_change_ms)},
                   {"ssim_loss_change", Num(r.ssim_loss_change)},
                   {"psnr_change_db", Num(r.psnr_change_db)}}}});
    }
    json["whitepaper_rows"] = rows;
    nlohmann::json accuracy = nlohmann::json::array();
    nlohmann::json frontier = nlohmann::json::array();
    for (const AccuracyEntry& e : model.accuracy) {
        const MeasuredConfiguration& c = *e.configuration;
        accuracy.push_back({{"configuration", c.id},
                            {"variant", c.variant},
                            {"presets", c.presets},
                            {"passes", c.PassLabel()},
                            {"ok", c.ok},
                            {"measured", e.measured},
                            {"median_ms", Num(e.median_ms)},
                            {"median_wall_ms", Num(c.median_ms)},
                            {"median_wall_ci_ms", {Num(c.ci_low_ms), Num(c.ci_high_ms)}},
                            {"median_cpu_ms", Num(c.cpu_median_ms)},
                            {"median_cpu_ci_ms", {Num(c.cpu_ci_low_ms), Num(c.cpu_ci_high_ms)}},
                            {"psnr_db", Num(e.psnr_db)},
                            {"identical_to_reference", std::isinf(e.psnr_db)},
                            {"ssim", Num(e.ssim)},
                            {"ssim_loss", Num(e.measured ? e.SsimLoss() : std::nan(""))},
                            {"share_visible", Num(e.share_visible)},
                            {"views_compared", e.views_compared},
                            {"on_frontier", e.on_frontier},
                            {"reference", e.is_reference},
                            {"note", e.note}});
    }
    for (std::size_t i : model.frontier) {
        frontier.push_back(model.accuracy[i].configuration->id);
    }
    json["accuracy"] = accuracy;
    json["pareto_frontier"] = frontier;
    nlohmann::json static_entries = nlohmann::json::array();
    for (const StaticCostEntry& e : model.static_cost.entries) {
        static_entries.push_back({{"configuration", e.configuration->id},
                                  {"vertex_ops", e.vertex_ops},
                                  {"fragment_ops", e.fragment_ops},
                                  {"total_ops", e.total_ops},
                                  {"median_ms", Num(e.median_ms)},
                                  {"ops_rank", e.ops_rank},
                                  {"time_rank", e.time_rank}});
    }
    nlohmann::json misleading = nlohmann::json::array();
    for (std::size_t i : model.static_cost.misleading) {
        misleading.push_back(model.static_cost.entries[i].configuration->id);
    }
    json["static_cost"] = {{"spearman_rho", Num(model.static_cost.spearman_rho)},
                           {"note", model.static_cost.note},
                           {"entries", static_entries},
                           {"most_misleading", misleading}};
    nlohmann::json failed = nlohmann::json::array();
    for (const MeasuredConfiguration* c : model.validation.failed) {
        failed.push_back({{"configuration", c->id},
                          {"driver_valid", c->driver_valid},
                          {"gl_error", c->gl_error},
                          {"driver_diagnostics", c->driver_messages}});
    }
    nlohmann::json disagreements = nlohmann::json::array();
    for (const VerdictDisagreementRow& d : model.validation.disagreements) {
        disagreements.push_back({{"variant", d.variant},
                                 {"glslang_valid", d.glslang_valid},
                                 {"mesa_valid", d.mesa_valid}});
    }
    nlohmann::json pruned_by_rule = nlohmann::json::array();
    for (const PrunedRuleRow& row : model.validation.pruned_by_rule) {
        pruned_by_rule.push_back({{"program", row.program},
                                  {"rule", row.rule},
                                  {"file", row.file},
                                  {"line", row.line},
                                  {"count", row.count}});
    }
    json["validation"] = {{"counts", model.validation.counts},
                          {"glslang_invalid", model.validation.glslang_invalid},
                          {"pruned_by_rule", pruned_by_rule},
                          {"configurations", model.validation.configurations},
                          {"failed_configurations", failed},
                          {"disagreements", disagreements},
                          {"run_diagnostics", model.validation.run_diagnostics}};
    nlohmann::json images = nlohmann::json::array();
    for (const ImagePanel& p : model.panels) {
        images.push_back({{"title", p.title},
                          {"configuration", PanelId(p)},
                          {"view", p.view},
                          {"psnr_db", Num(p.psnr_db)},
                          {"ssim", Num(p.ssim)},
                          {"share_visible", Num(p.share_visible)},
                          {"note", p.note}});
    }
    json["images"] = images;
    auto technique = [&model, &side](const TechniqueComparison& t) {
        nlohmann::json base = side(t.baseline);
        base["pass_names"] = t.baseline_passes;
        base["draw_calls"] = t.baseline_draw_calls ? nlohmann::json(*t.baseline_draw_calls)
                                                   : nlohmann::json(nullptr);
        nlohmann::json cand = side(t.candidate);
        cand["pass_names"] = t.candidate_passes;
        cand["draw_calls"] = t.candidate_draw_calls ? nlohmann::json(*t.candidate_draw_calls)
                                                    : nlohmann::json(nullptr);
        nlohmann::json per_view = nlohmann::json::array();
        for (const ViewError& v : t.per_view) {
            per_view.push_back({{"view", v.view},
                                {"psnr_db", Num(v.psnr_db)},
                                {"identical", std::isinf(v.psnr_db)},
                                {"ssim", Num(v.ssim)},
                                {"share_visible", Num(v.share_visible)}});
        }
        return nlohmann::json{
                {"kind", TechniqueKindName(t.kind)},
                {"technique", t.technique},
                {"context", t.context},
                {"baseline", base},
                {"candidate", cand},
                {"passes_dropped", t.passes_dropped},
                {"clock", TimingClockName(model.clock)},
                {"baseline_median_ms", Num(t.baseline_median_ms)},
                {"candidate_median_ms", Num(t.candidate_median_ms)},
                {"frame_time_ratio", Num(t.ratio.ratio)},
                {"frame_time_ratio_ci", {Num(t.ratio.ci.low), Num(t.ratio.ci.high)}},
                {"pairs", t.ratio.pairs},
                {"measured_percent", Num(t.change_percent)},
                {"measured_percent_ci", {Num(t.change_ci.low), Num(t.change_ci.high)}},
                {"direction", t.direction > 0   ? "faster"
                              : t.direction < 0 ? "slower"
                                                : "no-clear-change"},
                {"error",
                 {{"psnr_db", Num(t.psnr_db)},
                  {"identical", t.HasError() && std::isinf(t.psnr_db)},
                  {"ssim", Num(t.ssim)},
                  {"share_visible", Num(t.share_visible)},
                  {"views_compared", t.views_compared},
                  {"per_view", per_view},
                  {"worst_view",
                   t.worst_view.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.worst_view)},
                  {"worst_psnr_db", Num(t.worst_psnr_db)}}},
                {"reading", t.reading},
                {"note", t.note}};
    };
    nlohmann::json reflections = nlohmann::json::array();
    for (const TechniqueComparison& t : model.reflections) {
        reflections.push_back(technique(t));
    }
    nlohmann::json reflection_images = nlohmann::json::array();
    for (const ImagePanel& p : model.reflection_panels) {
        reflection_images.push_back(
                {{"title", p.title},
                 {"configuration", p.configuration != nullptr ? nlohmann::json(p.configuration->id)
                                                              : nlohmann::json(nullptr)},
                 {"compared_with", p.reference_preset},
                 {"view", p.view},
                 {"psnr_db", Num(p.psnr_db)},
                 {"ssim", Num(p.ssim)},
                 {"share_visible", Num(p.share_visible)},
                 {"note", p.note}});
    }
    json["reflection_techniques"] = {{"baseline", "planar reflection"},
                                     {"timing_view", model.inputs->timing_view},
                                     {"comparisons", reflections},
                                     {"images", reflection_images}};
    nlohmann::json optics = nlohmann::json::array();
    for (const TechniqueComparison& t : model.optics) {
        optics.push_back(technique(t));
    }
    json["depth_optics"] = {{"baseline", "full"}, {"comparisons", optics}};
    if (model.inputs->stability) {
        json["stability"] = *model.inputs->stability;
    } else {
        json["stability"] = {{"present", false},
                             {"error", model.inputs->stability_error},
                             {"how_to_produce", StabilityHowTo()}};
    }
    if (model.inputs->plans) {
        // The scenes as the section shows them; the full plans (candidates) stay in plans.json.
        nlohmann::json scenes = nlohmann::json::array();
        for (const nlohmann::json& plan :
             model.inputs->plans->value("plans", nlohmann::json::array())) {
            nlohmann::json scene = nlohmann::json::object();
            for (const char* key :
                 {"scene", "description", "target", "met", "chosen", "full", "time_ms_chosen",
                  "time_ms_full", "time_change_percent", "error", "dropped", "kept", "passes_saved",
                  "draws_saved", "pixels_saved", "errors"}) {
                if (plan.contains(key)) {
                    scene[key] = plan[key];
                }
            }
            scenes.push_back(std::move(scene));
        }
        json["scenes"] = {{"present", true},
                          {"size", model.inputs->plans->value("size", nlohmann::json())},
                          {"rounds", model.inputs->plans->value("rounds", nlohmann::json())},
                          {"frames_per_round",
                           model.inputs->plans->value("frames_per_round", nlohmann::json())},
                          {"plans", scenes}};
    } else {
        json["scenes"] = {{"present", false},
                          {"error", model.inputs->plans_error},
                          {"how_to_produce", PlansHowTo()}};
    }
    return json;
}

namespace {

// ---------------------------------------------------------------------------------------------
// Markdown

std::string MarkdownTable(const std::vector<std::string>& header,
                          const std::vector<std::vector<std::string>>& rows) {
    std::string out = "|";
    for (const std::string& h : header) {
        out.append(" ").append(Cell(h)).append(" |");
    }
    out += "\n|";
    for (std::size_t i = 0; i < header.size(); ++i) {
        out += "---|";
    }
    out += "\n";
    for (const auto& row : rows) {
        out += "|";
        for (const std::string& c : row) {
            out.append(" ").append(Cell(c)).append(" |");
        }
        out += "\n";
    }
    return out + "\n";
}

std::string HtmlTable(const std::vector<std::string>& header,
                      const std::vector<std::vector<std::string>>& rows,
                      const std::vector<std::string>& row_classes = {}) {
    std::string out = "<table class=\"wide\"><thead><tr>";
    for (const std::string& h : header) {
        out += "<th>" + HtmlEscaped(h) + "</th>";
    }
    out += "</tr></thead><tbody>";
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::string css = r < row_classes.size() ? row_classes[r] : "";
        out += css.empty() ? "<tr>" : "<tr class=\"" + css + "\">";
        for (const std::string& c : rows[r]) {
            // Variant ids are long comma-joined define lists: let them wrap after a comma.
            std::string cell = HtmlEscaped(c);
            for (std::size_t at = cell.find(','); at != std::string::npos;
                 at = cell.find(',', at + 6)) {
                cell.insert(at + 1, "<wbr>");
            }
            out += "<td>" + cell + "</td>";
        }
        out += "</tr>";
    }
    return out + "</tbody></table>\n";
}

// The tables of the report, shared by both formats.
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
    const nlohmann::json& c = model.validation.counts;
    auto n = [&](const char* key) { return c.contains(key) ? c[key].dump() : std::string("–"); };
    return fmt::format(
            "{} variants ({} pruned combinations); {} stage slots compiled as {} distinct stage "
            "programs ({} slots shared); {} links; glslang rejected {}. Mesa: {} configurations "
            "rendered, {} failed; glslang and Mesa disagree on {} variant(s).",
            n("variants"), n("pruned"), n("stage_slots"), n("stage_programs"),
            n("shared_stage_slots"), n("links"), model.validation.glslang_invalid.size(),
            model.validation.configurations, model.validation.failed.size(),
            model.validation.disagreements.size());
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
    for (const RowComparison& r : model.rows) {
        ++counts[r.verdict];
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
            "direction only, {} go the opposite way, {} are below the resolution reached and "
            "{} failed. {} of {} configurations are on the time/accuracy Pareto frontier{}. The "
            "static operation count ranks configurations by time with Spearman rho {}.{}",
            counts[Verdict::kSameDirectionAndMagnitude] + counts[Verdict::kNegligibleAsClaimed],
            counts[Verdict::kSameDirectionOnly] + counts[Verdict::kSameDirectionDifferentMagnitude],
            counts[Verdict::kOpposite], counts[Verdict::kBelowResolution], counts[Verdict::kFailed],
            model.frontier.size(), model.accuracy.size(),
            frontier.empty() ? "" : " (presets among them: " + frontier + ")",
            Fixed(model.static_cost.spearman_rho, 2),
            model.failed_configurations > 0
                    ? fmt::format(" {} configuration(s) FAILED.", model.failed_configurations)
                    : std::string());
}

// One image panel as Markdown: heading, figures, and the three images side by side.
std::string PanelMarkdown(const ImagePanel& p, const PanelFiles& files) {
    std::string md = fmt::format("### {} — view {}\n\n`{}`", p.title, p.view, PanelId(p));
    if (!p.note.empty()) {
        return md + fmt::format(": **{}**\n\n", p.note);
    }
    md += fmt::format(" — PSNR {} dB, SSIM {}, {} of pixels visibly different\n\n",
                      std::isinf(p.psnr_db) ? "inf" : Fixed(p.psnr_db, 1), Fixed(p.ssim, 4),
                      Fixed(p.share_visible * 100, 2, "%"));
    md += fmt::format(
            "| this configuration | {} | difference |\n|---|---|---|\n"
            "| ![]({}) | ![]({}) | ![]({}) |\n\n",
            Cell(p.reference_caption), files.image, files.reference, files.heat);
    return md;
}

std::string Markdown(const ReportModel& model, const Tables& t,
                     const std::vector<PanelFiles>& files) {
    std::string md = fmt::format("# tidepool report: {}\n\n", model.options.name);
    md += fmt::format(
            "Generated {} from `{}` and `{}`. Figures labelled \"whitepaper\" are quoted "
            "from Imagination's \"Shader Based Water Effects\" (measured on a PowerVR "
            "SGX-class GPU); everything else was measured here on Mesa llvmpipe.\n\n",
            model.options.generated_utc, model.inputs->manifest_path.string(),
            model.inputs->results_path.string());
    if (model.failed_configurations > 0) {
        md += fmt::format(
                "**{} configuration(s) FAILED** to compile or render; they are shown as "
                "failed below.\n\n",
                model.failed_configurations);
    }
    md += AtAGlance(model) + "\n\n";
    md += "## 1. The whitepaper's cost table, measured\n\n" + GlossaryText() + "\n\n" +
          VerdictRuleText(model) + "\n\n![whitepaper chart](charts/whitepaper.svg)\n\n";
    md += MarkdownTable(t.whitepaper_header, t.whitepaper);
    md += "## 2. What accuracy costs in time\n\n" + AccuracyIntro() +
          "\n\n![accuracy vs time](charts/accuracy.svg)\n\n### Pareto frontier\n\n";
    md += MarkdownTable(t.frontier_header, t.frontier);
    md += "### Each whitepaper optimisation: time saved, error added\n\n";
    md += MarkdownTable({"#", "change", "baseline → candidate", "Δ median frame time",
                         "performance change", "Δ(1-SSIM)", "Δ PSNR"},
                        t.optimisation);
    md += "### Every configuration\n\n" + MarkdownTable(t.accuracy_header, t.accuracy);
    md += "## 3. Static cost versus measured time\n\n";
    md += fmt::format(
            "The compiler's static operation count (vertex + fragment `total_ops` of the "
            "water variant, from the manifest) beside the measured median frame time, "
            "for configurations with default pass options. Spearman rank correlation: "
            "**{}**{}. The count sees only the water shader, not the passes a feature "
            "adds (refraction renders the scene once more), nor that llvmpipe samples "
            "textures in software.\n\n![static cost vs time](charts/static_cost.svg)\n\n",
            Fixed(model.static_cost.spearman_rho, 3),
            model.static_cost.note.empty() ? "" : " (" + model.static_cost.note + ")");
    md += "### Where the static count misleads (largest rank disagreements)\n\n";
    md += MarkdownTable(t.misleading_header, t.misleading);
    md += "### All\n\n" + MarkdownTable(t.static_header, t.static_rows);
    md += "## 4. Validation summary\n\n" + ValidationLine(model) + "\n\n";
    if (!model.validation.failed.empty()) {
        std::vector<std::vector<std::string>> rows;
        for (const MeasuredConfiguration* c : model.validation.failed) {
            std::string why =
                    c->driver_valid ? "GL error " + c->gl_error : "Mesa compile/link failed";
            for (const std::string& m : c->driver_messages) {
                why += "; " + m;
            }
            rows.push_back({c->id, "FAILED", why});
        }
        md += MarkdownTable({"configuration", "status", "why"}, rows);
    }
    if (!model.validation.disagreements.empty()) {
        std::vector<std::vector<std::string>> rows;
        for (const VerdictDisagreementRow& d : model.validation.disagreements) {
            rows.push_back({d.variant, d.glslang_valid ? "valid" : "invalid",
                            d.mesa_valid ? "valid" : "invalid"});
        }
        md += MarkdownTable({"variant", "glslang", "Mesa"}, rows);
    }
    if (!model.validation.pruned_by_rule.empty()) {
        md += "Combinations pruned, counted by the first rule each breaks (`tidepool expand "
              "--pruned` lists them):\n\n" +
              MarkdownTable(kPrunedRuleHeader, PrunedRuleTable(model));
    }
    md += "## 5. Images\n\nEach key configuration beside the reference, and their difference "
          "(black = identical, red → yellow → white = up to 32/255 and more).\n\n";
    for (std::size_t i = 0; i < model.panels.size(); ++i) {
        md += PanelMarkdown(model.panels[i], files[i]);
    }
    md += "## 6. Method and noise\n\n" + ClockText(model) + "\n\n" + TimingMethodText(model) +
          "\n\n" + MarkdownTable(ClockNoiseHeader(), ClockNoiseTable(model)) +
          MarkdownTable({"setting", "value"}, t.method);
    md += fmt::format(
            "Split-half reliability: every comparison computed again from the pairs "
            "where the baseline went first and from those where the candidate went "
            "first. Largest disagreement: **{}** (row {}).\n\n",
            Fixed(model.largest_split_half_disagreement, 1, " percentage points"),
            model.largest_split_half_row);
    md += MarkdownTable({"#", "comparison", "all pairs", "candidate first", "baseline first",
                         "disagreement", "pairs"},
                        t.split);
    md += RowDefinitionChanges() + "\n\n";
    md += "## 7. Numerical stability\n\n";
    if (!model.inputs->stability) {
        md += (model.inputs->stability_error.empty()
                       ? StabilityHowTo()
                       : model.inputs->stability_error + ". " + StabilityHowTo()) +
              "\n";
    } else {
        for (const auto& [key, columns] : StabilityTables()) {
            const nlohmann::json& table =
                    model.inputs->stability->value(key, nlohmann::json::array());
            md += "### " + key + "\n\n";
            std::vector<std::vector<std::string>> rows;
            if (table.is_array()) {
                for (const nlohmann::json& item : table) {
                    std::vector<std::string> row;
                    for (const std::string& column : columns) {
                        row.push_back(item.is_object() && item.contains(column)
                                              ? JsonCell(item[column])
                                              : "–");
                    }
                    rows.push_back(std::move(row));
                }
            }
            md += rows.empty() ? "(none)\n\n" : MarkdownTable(columns, rows);
        }
    }
    md += "## 8. Scenes\n\n";
    if (!model.inputs->plans) {
        md += (model.inputs->plans_error.empty()
                       ? PlansHowTo()
                       : model.inputs->plans_error + ". " + PlansHowTo()) +
              "\n\n";
    } else {
        const SceneTables scenes = BuildSceneTables(*model.inputs->plans);
        md += ScenesIntro(*model.inputs->plans) + "\n\n";
        if (scenes.missed > 0) {
            md += fmt::format("**{} scene(s) NOT met their target.**\n\n", scenes.missed);
        }
        md += MarkdownTable(SceneSummaryHeader(), scenes.summary);
        for (const auto& [scene, rows] : scenes.effects) {
            md += "### " + scene + "\n\n" +
                  (rows.empty() ? std::string("No effect was offered for dropping.\n\n")
                                : MarkdownTable(SceneEffectHeader(), rows));
        }
    }
    md += "## 9. Reflection techniques\n\n" + ReflectionsIntro(model) + "\n\n";
    md += MarkdownTable(t.reflections_header, t.reflections);
    md += "### Where the reflection breaks: full effect beside planar reflection\n\n" +
          ReflectionPanelsIntro(model) + "\n\n";
    for (std::size_t j = 0; j < model.reflection_panels.size(); ++j) {
        md += PanelMarkdown(model.reflection_panels[j], files[ReflectionPanelOffset(model) + j]);
    }
    md += "### Depth optics\n\n" + OpticsIntro() + "\n\n";
    md += MarkdownTable(t.optics_header, t.optics);
    return md;
}

// ---------------------------------------------------------------------------------------------
// HTML

constexpr const char* kCss = R"css(
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:24px auto;max-width:1400px;padding:0 16px;color:#222;line-height:1.4}
h1{font-size:1.6em}h2{border-bottom:2px solid #ddd;padding-bottom:4px;margin-top:2em}
table{border-collapse:collapse;margin:8px 0 16px;font-size:13px}
th,td{border:1px solid #ccc;padding:4px 6px;vertical-align:top;text-align:left;overflow-wrap:break-word}
table.wide{width:100%}
th{background:#f2f4f4;position:sticky;top:0}
tr.good td:nth-child(7){background:#d5f5e3}tr.fair td:nth-child(7){background:#d6eaf8}
tr.bad td{background:#fadbd8}tr.unknown td:nth-child(7){background:#eaeded}
tr.frontier td{background:#fdf2e9}
.note{color:#555;font-size:13px}.warn{background:#fadbd8;padding:8px;border-left:4px solid #c0392b}
.panel{margin:0 0 18px 0}
.panel img{border:1px solid #999;width:100%;height:auto}
.panel figure{display:inline-block;width:32%;margin:0 1% 0 0;vertical-align:top}.panel figcaption{font-size:12px;color:#555}
code{font-size:12px;background:#f4f6f6;padding:1px 3px}
svg{max-width:100%;height:auto;border:1px solid #eee}
nav a{margin-right:12px}
)css";

// Sets data-images-loaded="loaded/total" on <body> once the page has loaded, so a headless
// browser test can check that every embedded image decoded.
constexpr const char* kImageCheckScript =
        "<script>window.addEventListener('load',function(){var i=document.images,n=0;"
        "for(var k=0;k<i.length;k++){if(i[k].complete&&i[k].naturalWidth>0)n++;}"
        "document.body.setAttribute('data-images-loaded',n+'/'+i.length);});</script>";

// Escapes `text` for HTML and shows `quoted` spans (Markdown inline code) as <code>.
std::string HtmlNote(std::string_view text) {
    const std::string escaped = HtmlEscaped(text);
    std::string out;
    bool open = false;
    for (char c : escaped) {
        if (c == '`') {
            out += open ? "</code>" : "<code>";
            open = !open;
        } else {
            out += c;
        }
    }
    return open ? out + "</code>" : out;
}

// One image panel as HTML: heading, figures, and the three embedded images linking to the files.
std::string PanelHtml(const ImagePanel& p, const PanelFiles& files,
                      const std::array<std::string, 3>& uri) {
    std::string h =
            fmt::format("<div class=\"panel\"><h3>{} <small>— view {}</small></h3><code>{}</code>",
                        HtmlEscaped(p.title), HtmlEscaped(p.view), HtmlEscaped(PanelId(p)));
    if (!p.note.empty()) {
        return h + "<p class=\"warn\">" + HtmlEscaped(p.note) + "</p></div>";
    }
    h += fmt::format("<p class=\"note\">PSNR {} dB, SSIM {}, {} of pixels visibly different</p>",
                     std::isinf(p.psnr_db) ? "inf" : Fixed(p.psnr_db, 1), Fixed(p.ssim, 4),
                     Fixed(p.share_visible * 100, 2, "%"));
    const std::array<std::string, 3> links = {files.image, files.reference, files.heat};
    const std::array<std::string, 3> captions = {"this configuration", p.reference_caption,
                                                 "difference"};
    for (std::size_t k = 0; k < 3; ++k) {
        h += fmt::format(
                "<figure><a href=\"{}\"><img src=\"{}\" alt=\"{} {}\"></a>"
                "<figcaption>{}</figcaption></figure>",
                HtmlEscaped(links[k]), uri[k], HtmlEscaped(p.title), HtmlEscaped(captions[k]),
                HtmlEscaped(captions[k]));
    }
    return h + "</div>";
}

std::string HtmlPage(const ReportModel& model, const Tables& t, const Page& page) {
    std::string h =
            "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">";
    h += fmt::format("<title>tidepool report: {}</title><style>{}</style>{}</head><body>",
                     HtmlEscaped(model.options.name), kCss, kImageCheckScript);
    h += fmt::format("<h1>tidepool report: {}</h1>", HtmlEscaped(model.options.name));
    h += fmt::format(
            "<p class=\"note\">Generated {} from <code>{}</code> and <code>{}</code>. "
            "Figures labelled <b>whitepaper</b> are quoted from Imagination's \"Shader "
            "Based Water Effects\" (measured on a PowerVR SGX-class GPU); everything "
            "else was measured here on Mesa llvmpipe.</p>",
            HtmlEscaped(model.options.generated_utc),
            HtmlEscaped(model.inputs->manifest_path.string()),
            HtmlEscaped(model.inputs->results_path.string()));
    h += "<nav><a href=\"#whitepaper\">Whitepaper table</a><a href=\"#accuracy\">Accuracy vs "
         "time</a><a href=\"#static\">Static cost</a><a href=\"#validation\">Validation</a><a "
         "href=\"#images\">Images</a><a href=\"#method\">Method and noise</a><a "
         "href=\"#stability\">Numerical stability</a><a href=\"#scenes\">Scenes</a><a "
         "href=\"#reflections\">Reflection techniques</a></nav>";
    if (model.failed_configurations > 0) {
        h += fmt::format(
                "<p class=\"warn\"><b>{} configuration(s) FAILED</b> to compile or "
                "render; they are shown as failed below.</p>",
                model.failed_configurations);
    }
    h += "<p><b>" + HtmlNote(AtAGlance(model)) + "</b></p>";
    h += "<h2 id=\"whitepaper\">1. The whitepaper's cost table, measured</h2>";
    h += "<p class=\"note\">" + HtmlNote(GlossaryText()) + "</p><p class=\"note\">" +
         HtmlNote(VerdictRuleText(model)) + "</p>";
    h += WhitepaperChartSvg(model);
    h += HtmlTable(t.whitepaper_header, t.whitepaper, t.whitepaper_css);

    h += "<h2 id=\"accuracy\">2. What accuracy costs in time</h2><p class=\"note\">" +
         HtmlNote(AccuracyIntro()) + "</p>";
    h += AccuracyChartSvg(model);
    h += "<h3>Pareto frontier</h3>" + HtmlTable(t.frontier_header, t.frontier);
    h += "<h3>Each whitepaper optimisation: time saved, error added</h3>" +
         HtmlTable({"#", "change", "baseline → candidate", "Δ median frame time",
                    "performance change", "Δ(1-SSIM)", "Δ PSNR"},
                   t.optimisation);
    h += "<details><summary>Every configuration</summary>" +
         HtmlTable(t.accuracy_header, t.accuracy, t.accuracy_css) + "</details>";

    h += "<h2 id=\"static\">3. Static cost versus measured time</h2>";
    h += fmt::format(
            "<p class=\"note\">The compiler's static operation count (vertex + fragment "
            "<code>total_ops</code> of the water variant, from the manifest) beside the "
            "measured median frame time, for configurations with default pass options. "
            "Spearman rank correlation: <b>{}</b>{}. Red points: the configurations "
            "where the count misleads most. The count sees only the water shader, not "
            "the passes a feature adds (refraction renders the scene once more), nor "
            "that llvmpipe samples textures in software.</p>",
            Fixed(model.static_cost.spearman_rho, 3),
            HtmlEscaped(model.static_cost.note.empty() ? "" : " (" + model.static_cost.note + ")"));
    h += StaticCostChartSvg(model);
    h += "<h3>Where the static count misleads (largest rank disagreements)</h3>" +
         HtmlTable(t.misleading_header, t.misleading);
    h += "<details><summary>All</summary>" + HtmlTable(t.static_header, t.static_rows) +
         "</details>";

    h += "<h2 id=\"validation\">4. Validation summary</h2><p>" +
         HtmlEscaped(ValidationLine(model)) + "</p>";
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
        h += "<h3>Failed configurations</h3>" +
             HtmlTable({"configuration", "status", "why"}, rows, css);
    }
    if (!model.validation.disagreements.empty()) {
        std::vector<std::vector<std::string>> rows;
        for (const VerdictDisagreementRow& d : model.validation.disagreements) {
            rows.push_back({d.variant, d.glslang_valid ? "valid" : "invalid",
                            d.mesa_valid ? "valid" : "invalid"});
        }
        h += "<h3>glslang / Mesa disagreements</h3>" +
             HtmlTable({"variant", "glslang", "Mesa"}, rows);
    }
    if (!model.validation.pruned_by_rule.empty()) {
        h += "<h3>Pruned combinations per rule</h3><p class=\"note\">Counted by the first rule "
             "each combination breaks; <code>tidepool expand --pruned</code> lists them.</p>" +
             HtmlTable(kPrunedRuleHeader, PrunedRuleTable(model));
    }

    h += "<h2 id=\"images\">5. Images</h2><p class=\"note\">Each key configuration beside the "
         "reference, and their difference (black = identical, red → yellow → white = up to "
         "32/255 and more). Click an image for the full-size file (when the report folder is "
         "intact).</p>";
    for (std::size_t i = 0; i < model.panels.size(); ++i) {
        h += PanelHtml(model.panels[i], page.files[i], (*page.uris)[i]);
    }

    h += "<h2 id=\"method\">6. Method and noise</h2><p class=\"note\">" +
         HtmlNote(ClockText(model)) + "</p><p>" + HtmlEscaped(TimingMethodText(model)) + "</p>" +
         HtmlTable(ClockNoiseHeader(), ClockNoiseTable(model)) +
         HtmlTable({"setting", "value"}, t.method);
    h += fmt::format(
            "<p>Split-half reliability: every comparison computed again from the pairs "
            "where the baseline went first and from those where the candidate went "
            "first. Largest disagreement: <b>{}</b> (row {}). A verdict is only as firm "
            "as its interval; a finer --resolution narrows it.</p>",
            Fixed(model.largest_split_half_disagreement, 1, " percentage points"),
            model.largest_split_half_row);
    h += HtmlTable({"#", "comparison", "all pairs", "candidate first", "baseline first",
                    "disagreement", "pairs"},
                   t.split);
    h += "<p class=\"note\">" + HtmlNote(RowDefinitionChanges()) + "</p>";

    h += "<h2 id=\"stability\">7. Numerical stability</h2>";
    if (!model.inputs->stability) {
        h += "<p class=\"note\">" +
             HtmlNote(model.inputs->stability_error.empty()
                              ? StabilityHowTo()
                              : model.inputs->stability_error + ". " + StabilityHowTo()) +
             "</p>";
    } else {
        for (const auto& [key, columns] : StabilityTables()) {
            const nlohmann::json& table =
                    model.inputs->stability->value(key, nlohmann::json::array());
            std::vector<std::vector<std::string>> rows;
            std::vector<std::string> css;
            if (table.is_array()) {
                for (const nlohmann::json& item : table) {
                    std::vector<std::string> row;
                    for (const std::string& column : columns) {
                        row.push_back(item.is_object() && item.contains(column)
                                              ? JsonCell(item[column])
                                              : "–");
                    }
                    css.push_back(item.is_object() && item.value("passed", true) == false ? "bad"
                                                                                          : "");
                    rows.push_back(std::move(row));
                }
            }
            h += "<h3>" + HtmlEscaped(key) + "</h3>" +
                 (rows.empty() ? std::string("<p>(none)</p>") : HtmlTable(columns, rows, css));
        }
    }
    h += "<h2 id=\"scenes\">8. Scenes</h2>";
    if (!model.inputs->plans) {
        h += "<p class=\"note\">" +
             HtmlNote(model.inputs->plans_error.empty()
                              ? PlansHowTo()
                              : model.inputs->plans_error + ". " + PlansHowTo()) +
             "</p>";
    } else {
        const SceneTables scenes = BuildSceneTables(*model.inputs->plans);
        h += "<p class=\"note\">" + HtmlNote(ScenesIntro(*model.inputs->plans)) + "</p>";
        if (scenes.missed > 0) {
            h += fmt::format("<p class=\"warn\"><b>{} scene(s) NOT met their target.</b></p>",
                             scenes.missed);
        }
        h += HtmlTable(SceneSummaryHeader(), scenes.summary, scenes.summary_css);
        for (const auto& [scene, rows] : scenes.effects) {
            h += "<h3>" + HtmlEscaped(scene) + "</h3>" +
                 (rows.empty() ? std::string("<p>No effect was offered for dropping.</p>")
                               : HtmlTable(SceneEffectHeader(), rows));
        }
    }
    h += "<h2 id=\"reflections\">9. Reflection techniques</h2><p class=\"note\">" +
         HtmlNote(ReflectionsIntro(model)) + "</p>";
    h += HtmlTable(t.reflections_header, t.reflections, t.reflections_css);
    h += "<h3>Where the reflection breaks: full effect beside planar reflection</h3>"
         "<p class=\"note\">" +
         HtmlNote(ReflectionPanelsIntro(model)) + "</p>";
    for (std::size_t j = 0; j < model.reflection_panels.size(); ++j) {
        const std::size_t i = ReflectionPanelOffset(model) + j;
        h += PanelHtml(model.reflection_panels[j], page.files[i], (*page.uris)[i]);
    }
    h += "<h3 id=\"depth-optics\">Depth optics</h3><p class=\"note\">" + HtmlNote(OpticsIntro()) +
         "</p>" + HtmlTable(t.optics_header, t.optics, t.optics_css);
    h += "</body></html>\n";
    return h;
}

}  // namespace

namespace {
WrittenReport WriteReportUnchecked(const ReportModel& model, const std::filesystem::path& out_dir);
}  // namespace

WrittenReport WriteReport(const ReportModel& model, const std::filesystem::path& out_dir) {
    // The writers read a few settings straight from results.json; one of an unexpected type is
    // an error naming the file, never an abort (nothing is published then).
    try {
        return WriteReportUnchecked(model, out_dir);
    } catch (const nlohmann::json::exception& e) {
        WrittenReport written;
        written.error = fmt::format("{}: a field has an unexpected type: {}",
                                    model.inputs->results_path.string(), e.what());
        return written;
    }
}

namespace {
WrittenReport WriteReportUnchecked(const ReportModel& model, const std::filesystem::path& out_dir) {
    WrittenReport written;
    written.folder = out_dir / model.options.name;
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec) {
        written.error = fmt::format("{}: cannot create: {}", out_dir.string(), ec.message());
        return written;
    }
    base::PublishError begin;
    const std::unique_ptr<base::FolderPublisher> publisher =
            base::FolderPublisher::Begin(written.folder, "tidepool report", &begin);
    if (!publisher) {
        written.error = begin.message;
        written.refused = begin.failure == base::PublishFailure::kRefused;
        return written;
    }
    const std::filesystem::path& staging = publisher->Staging();
    // The publisher removes its staging folder when it goes out of scope unpublished.
    auto fail = [&](std::string message) {
        written.error = std::move(message);
        return written;
    };
    auto write = [&](const std::string& relative, std::string_view content) {
        const std::string error = base::WriteFileAtomically(staging / relative, content);
        if (error.empty()) {
            written.files.emplace_back(relative);
        }
        return error;
    };

    // Every panel in one list, the Images section's first and the Reflection techniques
    // section's after them (ReflectionPanelOffset), so files[i] and uris[i] belong to panel i.
    std::vector<const ImagePanel*> panels;
    for (const ImagePanel& p : model.panels) {
        panels.push_back(&p);
    }
    for (const ImagePanel& p : model.reflection_panels) {
        panels.push_back(&p);
    }

    // Full-size PNGs beside report.md; each compared-with image (the reference, or the planar
    // configuration a reflection technique replaces) once per view.
    std::vector<PanelFiles> files(panels.size());
    std::map<std::string, std::string> reference_files;
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const ImagePanel& p = *panels[i];
        if (!p.note.empty()) {
            continue;
        }
        const bool technique = i >= ReflectionPanelOffset(model);
        const std::string stem = (technique ? "reflection-" : "") + PanelStem(p) + "-" + p.view;
        files[i].image = "images/" + stem + ".png";
        files[i].heat = "images/" + stem + "-diff.png";
        const std::string key = p.reference_preset + "/" + p.view;
        if (reference_files.count(key) == 0) {
            reference_files[key] =
                    p.reference_preset == kReferencePreset
                            ? "images/reference-" + p.view + ".png"
                            : "images/planar-" + p.reference_preset + "-" + p.view + ".png";
            if (std::string e =
                        base::WritePngAtomically(staging / reference_files[key], p.reference);
                !e.empty()) {
                return fail(e);
            }
            written.files.emplace_back(reference_files[key]);
        }
        files[i].reference = reference_files[key];
        for (const auto& [relative, image] :
             {std::pair{files[i].image, &p.image}, std::pair{files[i].heat, &p.heat_map}}) {
            if (std::string e = base::WritePngAtomically(staging / relative, *image); !e.empty()) {
                return fail(e);
            }
            written.files.emplace_back(relative);
        }
    }

    // Embedded copies for index.html, downscaled until they fit the budget. Encoded in memory,
    // the panels spread over the cores.
    std::vector<std::array<std::string, 3>> uris(panels.size());
    for (int factor = 1; factor <= 8; ++factor) {
        std::vector<std::future<std::string>> jobs;
        std::atomic<std::uintmax_t> total{0};
        for (std::size_t i = 0; i < panels.size(); ++i) {
            const ImagePanel& p = *panels[i];
            if (!p.note.empty()) {
                continue;
            }
            jobs.push_back(std::async(std::launch::async, [&, i, factor]() -> std::string {
                const ImagePanel& panel = *panels[i];
                const std::array<const RgbaImage*, 3> images = {&panel.image, &panel.reference,
                                                                &panel.heat_map};
                const std::array<const std::string*, 3> full_size = {
                        &files[i].image, &files[i].reference, &files[i].heat};
                for (std::size_t k = 0; k < 3; ++k) {
                    std::string bytes;
                    if (factor == 1) {
                        bytes = ReadBytes(staging / *full_size[k]);  // already encoded above
                    } else if (std::string e =
                                       base::EncodePng(Downscale(*images[k], factor), &bytes);
                               !e.empty()) {
                        return e;
                    }
                    total += bytes.size();
                    uris[i][k] = "data:image/png;base64," + Base64(bytes);
                }
                return "";
            }));
        }
        std::string error;
        for (std::future<std::string>& job : jobs) {
            if (std::string e = job.get(); !e.empty() && error.empty()) {
                error = e;
            }
        }
        if (!error.empty()) {
            return fail(error);
        }
        written.image_downscale = factor;
        if (total <= kHtmlImageBudgetBytes) {
            break;
        }
    }

    const Tables tables = BuildTables(model);
    const Page page{model, files, &uris};
    const std::string html = HtmlPage(model, tables, page);
    written.html_bytes = html.size();
    for (const auto& [relative, content] :
         {std::pair<std::string, std::string>{"index.html", html},
          {"report.md", Markdown(model, tables, files)},
          {"data.json", tidepool::JsonText(ReportToJson(model), 2) + "\n"},
          {"charts/whitepaper.svg", WhitepaperChartSvg(model)},
          {"charts/accuracy.svg", AccuracyChartSvg(model)},
          {"charts/static_cost.svg", StaticCostChartSvg(model)}}) {
        if (std::string e = write(relative, content); !e.empty()) {
            return fail(e);
        }
    }
    if (base::PublishError e = publisher->Publish(); e.Failed()) {
        written.error = e.message;
        written.refused = e.failure == base::PublishFailure::kRefused;
        return written;
    }
    return written;
}

}  // namespace

}  // namespace tidepool::report
