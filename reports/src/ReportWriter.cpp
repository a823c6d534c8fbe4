#include "tidepool/report/ReportWriter.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/report/WhitepaperTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <sstream>

#include "ReportDocumentBuilder.h"
#include "ReportText.h"
#include <fmt/format.h>

namespace tidepool::report {
namespace {

using base::kVisibleDifferenceThreshold;
using base::RgbaImage;

nlohmann::json Num(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
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

// `name` as part of a file name in images/: anything but letters, digits, '_' and '-' becomes
// '_', so no name from the inputs can climb out of the report's folder.
std::string FileNamePart(std::string name) {
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') {
            c = '_';
        }
    }
    return name;
}

std::string PanelStem(const ImagePanel& panel) {
    return FileNamePart(panel.configuration != nullptr && !panel.configuration->presets.empty()
                                ? panel.configuration->presets.front()
                                : std::string("configuration"));
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
    json["method"] = {{"clock", TimingClockName(model.clock)},
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
                      {"environment", stagefiles::ToJson(model.inputs->results.environment)},
                      {"settings", stagefiles::ToJson(model.inputs->results.settings)}};
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
                 {"as_run_percent_ci",
                  {Num(PerformanceChangePercent(r.ratio.as_run_ci.high)),
                   Num(PerformanceChangePercent(r.ratio.as_run_ci.low))}},
                 {"contended_percent", Num(PerformanceChangePercent(r.ratio.contended_ratio))},
                 {"contended_percent_ci",
                  {Num(PerformanceChangePercent(r.ratio.contended_ci.high)),
                   Num(PerformanceChangePercent(r.ratio.contended_ci.low))}},
                 {"contended_pairs", r.ratio.contended_pairs},
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
    json["validation"] = {{"counts", stagefiles::ToJson(model.validation.counts)},
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
        json["stability"] = stagefiles::ToJson(*model.inputs->stability);
    } else {
        json["stability"] = {{"present", false},
                             {"error", model.inputs->stability_error},
                             {"how_to_produce", StabilityHowTo()}};
    }
    if (model.inputs->plans) {
        // The scenes as the section shows them; the full plans (candidates) stay in plans.json.
        nlohmann::json scenes = nlohmann::json::array();
        for (const stagefiles::PlannedScene& planned : model.inputs->plans->plans) {
            const nlohmann::json plan = stagefiles::ToJson(planned);
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
        // plans.json has never carried rounds or frames per round (the planner times pair by
        // pair, plans.json's `timing`): both stay null, so data.json keeps its keys.
        json["scenes"] = {{"present", true},
                          {"size", model.inputs->plans->size},
                          {"rounds", nullptr},
                          {"frames_per_round", nullptr},
                          {"plans", scenes}};
    } else {
        json["scenes"] = {{"present", false},
                          {"error", model.inputs->plans_error},
                          {"how_to_produce", PlansHowTo()}};
    }
    return json;
}

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
    if (const base::PublishError check = base::CheckFolderPath(out_dir); check.Failed()) {
        written.error = check.message;
        written.refused = true;
        return written;
    }
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
        std::string error = base::WriteFileAtomically(staging / relative, content);
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
        const std::string view = FileNamePart(p.view);
        const std::string stem = (technique ? "reflection-" : "") + PanelStem(p) + "-" + view;
        files[i].image = "images/" + stem + ".png";
        files[i].heat = "images/" + stem + "-diff.png";
        const std::string key = p.reference_preset + "/" + p.view;
        if (reference_files.count(key) == 0) {
            reference_files[key] = p.reference_preset == kReferencePreset
                                           ? "images/reference-" + view + ".png"
                                           : "images/planar-" + FileNamePart(p.reference_preset) +
                                                     "-" + view + ".png";
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

    const doc::Document document = BuildReportDocument(model, files, uris);
    const std::string html = doc::HtmlPage(document);
    written.html_bytes = html.size();
    std::vector<std::pair<std::string, std::string>> outputs = {
            {"index.html", html},
            {"report.md", doc::MarkdownPage(document)},
            {"data.json", tidepool::JsonText(ReportToJson(model), 2) + "\n"}};
    for (const doc::Figure* figure : doc::Figures(document)) {
        outputs.emplace_back(figure->file, figure->svg);
    }
    for (const auto& [relative, content] : outputs) {
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
