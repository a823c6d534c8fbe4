// The render run: compile, images, warm-up, interleaved timing rounds, results.json.
#include "tidepool/runner/Results.h"

#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/stagefiles/StageFile.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "RenderProgress.h"
#include <fmt/format.h>

namespace tidepool::runner {
namespace {

using base::EstimatePaired;
using base::PairedEstimate;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration duration) {
    return std::chrono::duration<double>(duration).count();
}

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

nlohmann::json DiagnosticJson(const Diagnostic& d) {
    return {{"severity", SeverityName(d.severity)},
            {"file", d.file},
            {"line", d.line},
            {"column", d.column},
            {"message", d.message},
            {"variant", d.variant},
            {"text", FormatDiagnostic(d)}};
}

nlohmann::json StatisticsJson(const base::SampleStatistics& s) {
    return {{"count", s.count},
            {"min_ms", s.min},
            {"max_ms", s.max},
            {"mean_ms", s.mean},
            {"median_ms", s.median},
            {"q1_ms", s.q1},
            {"q3_ms", s.q3},
            {"iqr_ms", s.iqr},
            {"ci_low_ms", s.ci_low},
            {"ci_high_ms", s.ci_high},
            {"ci_coverage", s.ci_coverage},
            {"ci_method", "order statistics of the median, binomial(n, 0.5) coverage"}};
}

}  // namespace

bool RunResults::AllOk() const {
    return std::all_of(configurations.begin(), configurations.end(),
                       [](const ConfigurationResult& c) { return c.Ok(); });
}

namespace {

// The reference configuration's images, by view, with their SSIM moments; filled by the
// thread that renders the reference, read by every thread after.
class ReferenceImages {
public:
    void Keep(const std::string& view, const base::RgbaImage& image) {
        auto kept = std::make_shared<const Kept>(image);
        std::lock_guard<std::mutex> lock(mutex_);
        views_[view] = std::move(kept);
    }

    // `image` against the reference's at `view`, the way the report measures accuracy;
    // nothing when the reference has no image there (yet) or the sizes differ.
    std::optional<base::ImageAccuracy> Compare(const std::string& view,
                                               const base::RgbaImage& image) const {
        std::shared_ptr<const Kept> kept;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            auto found = views_.find(view);
            if (found == views_.end()) {
                return std::nullopt;
            }
            kept = found->second;
        }
        if (kept->image.width != image.width || kept->image.height != image.height) {
            return std::nullopt;
        }
        return base::MeasureAccuracy(image, kept->image, kept->ssim);
    }

private:
    struct Kept {
        explicit Kept(const base::RgbaImage& from) : image(from), ssim(image) {}
        base::RgbaImage image;
        base::SsimReference ssim;
    };
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const Kept>> views_;
};

// One rendering thread's context, renderer and timer, and what it has compiled.
struct RenderWorker {
    std::unique_ptr<WaterRenderer> renderer;
    std::unique_ptr<FrameTimer> timer;
    std::map<std::size_t, DriverVerdict> prepared;  // by configuration index
};

constexpr long kInitialPairGuess = 60;  // until a comparison's first look says otherwise

}  // namespace

RunResults RunRender(GlContext& context, const VariantConfig& config, const RunOptions& options,
                     const ProgressCallback& progress) {
    RunResults results;
    results.gl = context.Environment();
    results.host = options.host;
    results.options = options;
    results.started_utc = UtcNow();
    results.clock = ChooseFrameClock(results.gl.renderer, options.host.lp_num_threads,
                                     results.gl.timer_query);
    const Clock::time_point start = Clock::now();

    const CameraView* timing_view = nullptr;
    for (const CameraView& view : options.views) {
        if (options.timing_view.empty() || view.name == options.timing_view) {
            timing_view = &view;
            break;
        }
    }
    for (const RenderConfiguration& configuration : options.configurations) {
        ConfigurationResult result;
        result.configuration = configuration;
        results.configurations.push_back(std::move(result));
    }
    for (const TimedComparison& c : options.comparisons) {
        ComparisonResult r;
        r.comparison = c;
        if (c.baseline >= options.configurations.size() ||
            c.candidate >= options.configurations.size()) {
            r.error = "the comparison names a configuration the run does not have";
        }
        results.comparisons.push_back(std::move(r));
    }

    // glslang's verdict on the same variants, to list where the two compilers disagree.
    std::map<std::string, bool> glslang;
    if (options.compare_with_glslang) {
        std::vector<Variant> variants;
        std::set<std::string> seen;
        for (const ConfigurationResult& r : results.configurations) {
            if (seen.insert(r.configuration.variant.Id()).second) {
                variants.push_back(r.configuration.variant);
            }
        }
        const ValidationReport report = ValidateVariants(
                config, variants, ValidationOptions{},
                options.validated != nullptr ? *options.validated : ValidationReport{});
        for (const VariantVerdict& v : report.verdicts) {
            glslang[v.variant.Id()] = v.valid;
        }
    }

    ProgressMeter meter(progress, start);
    const long per_configuration = static_cast<long>(options.views.size()) + options.coarse_frames;
    meter.AddExpected(ProgressMeter::kImage,
                      per_configuration * static_cast<long>(options.configurations.size()));
    meter.AddComparisons(results.comparisons.size(), 2 * kInitialPairGuess);

    // The reference configuration renders first, so that every later image is compared with
    // it while in memory.
    std::optional<std::size_t> reference;
    for (std::size_t i = 0; i < options.configurations.size() && !reference; ++i) {
        const std::vector<std::string>& presets = options.configurations[i].presets;
        if (std::find(presets.begin(), presets.end(), options.reference_preset) != presets.end()) {
            reference = i;
        }
    }
    ReferenceImages references;
    const std::vector<WorkUnit> units =
            RenderWorkOrder(results.comparisons.size(), results.configurations.size(), reference);
    std::atomic<std::size_t> next_unit{0};
    std::mutex results_mutex;  // diagnostics and write errors, appended from every thread
    std::vector<std::atomic<bool>> pass_timed(results.configurations.size());

    // Compiles configuration `i` in `w`'s context once; with `warm`, renders warm-up frames too
    // (llvmpipe compiles shader variants on first draw, which must not land in a timed frame).
    // A configuration's own unit needs none: its images, every view once, come before its
    // timed frames and warm it.
    auto prepare = [&](RenderWorker& w, std::size_t i, bool warm) -> const DriverVerdict& {
        auto found = w.prepared.find(i);
        if (found != w.prepared.end()) {
            return found->second;
        }
        const RenderConfiguration& c = options.configurations[i];
        DriverVerdict verdict = w.renderer->Prepare(c);
        if (warm && verdict.valid && timing_view != nullptr) {
            for (int f = 0; f < options.warmup_frames; ++f) {
                w.renderer->RenderFrame(c, *timing_view);
                w.renderer->Finish();
            }
        }
        return w.prepared.emplace(i, std::move(verdict)).first->second;
    };

    auto time_passes = [&](RenderWorker& w, std::size_t i) {
        if (pass_timed[i].exchange(true) || timing_view == nullptr) {
            return;
        }
        std::map<std::string, std::vector<double>> per_pass;
        for (int f = 0; f < options.pass_frames; ++f) {
            for (const auto& [pass, ms] :
                 w.timer->TimePasses(options.configurations[i], *timing_view)) {
                per_pass[pass].push_back(ms);
            }
        }
        ConfigurationResult& r = results.configurations[i];
        for (auto& [pass, samples] : per_pass) {
            const double median = base::Median(samples);
            if (pass == "frame") {
                r.instrumented_frame_ms = median;
            } else {
                r.pass_ms[pass] = median;
            }
        }
    };

    auto run_configuration = [&](RenderWorker& w, std::size_t i) {
        ConfigurationResult& r = results.configurations[i];
        r.verdict = prepare(w, i, false);
        if (!r.verdict.valid) {
            meter.Step(ProgressMeter::kImage, r.configuration.id, per_configuration);
            return;
        }
        for (const CameraView& view : options.views) {
            ViewResult view_result;
            view_result.view = view.name;
            view_result.frame = w.renderer->RenderFrame(r.configuration, view);
            w.renderer->Finish();
            if (!view_result.frame.gl_error.empty() && r.gl_error.empty()) {
                r.gl_error = fmt::format("{} (view {})", view_result.frame.gl_error, view.name);
            }
            const base::RgbaImage image = w.renderer->ReadImage();
            if (reference && i == *reference) {
                references.Keep(view.name, image);
            }
            view_result.accuracy = references.Compare(view.name, image);
            if (options.write_images) {
                const std::string name = fmt::format(
                        "images/{}-{}.png", SanitiseFileName(r.configuration.id), view.name);
                const std::string write_error =
                        base::WritePngAtomically(options.out_dir / name, image);
                if (write_error.empty()) {
                    view_result.image_path = name;
                } else {
                    std::lock_guard<std::mutex> lock(results_mutex);
                    results.write_errors.push_back(write_error);
                }
            }
            if (&view == timing_view) {
                r.passes = view_result.frame.passes;
                r.draw_calls = view_result.frame.draw_calls;
            }
            r.views.push_back(std::move(view_result));
            meter.Step(ProgressMeter::kImage, r.configuration.id, 1);
        }
        if (timing_view == nullptr) {
            meter.Step(ProgressMeter::kImage, r.configuration.id, options.coarse_frames);
            return;
        }
        std::vector<double> plan_ms;
        for (int f = 0; f < options.coarse_frames; ++f) {
            FrameReport frame;
            const FrameTime t = w.timer->Time(r.configuration, *timing_view, &frame);
            r.samples_ms.push_back({t.wall_ms});
            r.cpu_samples_ms.push_back({t.ms});
            plan_ms.push_back(frame.plan_seconds * 1000.0);
            if (!frame.gl_error.empty() && r.gl_error.empty()) {
                r.gl_error = frame.gl_error;
            }
            meter.Step(ProgressMeter::kImage, r.configuration.id, 1);
        }
        r.plan_ms_median = base::Median(plan_ms);
    };

    auto run_comparison = [&](RenderWorker& w, std::size_t k) {
        ComparisonResult& out = results.comparisons[k];
        const TimedComparison& c = out.comparison;
        if (out.error.empty() && timing_view == nullptr) {
            out.error = "no timing view";
        }
        if (out.error.empty()) {
            for (std::size_t i : {c.baseline, c.candidate}) {
                if (!prepare(w, i, true).valid) {
                    out.error = fmt::format("configuration {} did not compile in Mesa",
                                            options.configurations[i].id);
                    break;
                }
            }
        }
        if (!out.error.empty()) {
            meter.ComparisonExpects(k, 0, true);
            return;
        }
        const RenderConfiguration& baseline = options.configurations[c.baseline];
        const RenderConfiguration& candidate = options.configurations[c.candidate];
        long done = 0;
        out.timing = TimeComparison(
                [&](bool is_candidate) {
                    return w.timer->Time(is_candidate ? candidate : baseline, *timing_view);
                },
                options.rule,
                [&](const ComparisonTiming& so_far) {
                    // Frames this look took, and a new guess of the pairs the interval needs.
                    const long frames = 2L * static_cast<long>(so_far.samples.baseline_ms.size());
                    meter.Step(ProgressMeter::kComparison, c.label, frames - done);
                    done = frames;
                    const long needed = base::PairsExpectedAtStop(so_far.estimate, options.rule,
                                                                  kInitialPairGuess);
                    const bool finished = so_far.decision != base::StopDecision::kContinue;
                    meter.ComparisonExpects(k, finished ? frames : 2 * needed, finished);
                });
        time_passes(w, c.baseline);
        time_passes(w, c.candidate);
        meter.Step(ProgressMeter::kComparison, c.label, 0);  // the per-pass frames' time too
    };

    // A rendering thread: its own context (but the calling thread's), renderer and timer; takes
    // units from the queue until it is empty.
    auto run_worker = [&](RenderWorker& w, GlContext& gl_context) {
        std::string error;
        w.renderer = WaterRenderer::Create(gl_context, config, options.settings, &error);
        if (!w.renderer) {
            std::lock_guard<std::mutex> lock(results_mutex);
            results.diagnostics.push_back(
                    MakeError("", 0, 0, "cannot set up the renderer: " + error));
            return;
        }
        w.timer = std::make_unique<FrameTimer>(*w.renderer, results.clock.clock);
        for (std::size_t u = next_unit++; u < units.size(); u = next_unit++) {
            if (units[u].comparison) {
                run_comparison(w, units[u].index);
            } else {
                run_configuration(w, units[u].index);
            }
        }
    };

    std::atomic<bool> rendered{false};
    results.workers =
            RunOnRenderingThreads(context, options.make_context, std::max(1, options.workers),
                                  [&](GlContext& gl_context) {
                                      RenderWorker w;
                                      run_worker(w, gl_context);
                                      if (w.renderer) {
                                          rendered = true;
                                      }
                                  });
    if (!rendered) {
        return results;  // the diagnostics say why
    }

    for (ConfigurationResult& r : results.configurations) {
        for (const Diagnostic& d : r.verdict.diagnostics) {
            results.diagnostics.push_back(d);
        }
        std::vector<double> all;
        for (const std::vector<double>& round : r.samples_ms) {
            all.insert(all.end(), round.begin(), round.end());
        }
        r.statistics = base::ComputeSampleStatistics(all);
        std::vector<double> all_clock;
        for (const std::vector<double>& round : r.cpu_samples_ms) {
            all_clock.insert(all_clock.end(), round.begin(), round.end());
        }
        r.cpu_statistics = base::ComputeSampleStatistics(all_clock);
        const std::string id = r.configuration.variant.Id();
        if (auto found = glslang.find(id); found != glslang.end()) {
            r.glslang_valid = found->second;
            // Only the variant's own program counts: a helper program's failure is not its fault.
            const bool mesa_valid = r.verdict.linked;
            const bool listed =
                    std::any_of(results.disagreements.begin(), results.disagreements.end(),
                                [&](const VerdictDisagreement& d) { return d.variant == id; });
            if (found->second != mesa_valid && !listed) {
                results.disagreements.push_back(VerdictDisagreement{id, found->second, mesa_valid});
            }
        }
        if (!r.gl_error.empty()) {
            results.diagnostics.push_back(Diagnostic{Severity::kError, "", 0, 0,
                                                     "GL error while rendering: " + r.gl_error,
                                                     r.configuration.id});
        }
    }
    results.wall_seconds = Seconds(Clock::now() - start);
    return results;
}

nlohmann::json ResultsToJson(const RunResults& results) {
    const RunOptions& o = results.options;
    const RenderSettings& s = o.settings;
    nlohmann::json json;
    json["schema"] = kResultsSchema;
    json[stagefiles::kVersionKey] = kResultsSchemaVersion;
    json["started_utc"] = results.started_utc;
    json["wall_seconds"] = results.wall_seconds;
    json["environment"] = {
            {"backend", results.gl.backend},
            {"context_api", results.gl.context_api},
            {"gl_renderer", results.gl.renderer},
            {"gl_version", results.gl.version},
            {"glsl_version", results.gl.shading_language},
            {"mesa_version", results.gl.mesa_version},
            {"float_render_target", results.gl.float_render_target},
            {"timer_query", results.gl.timer_query},
            {"cpu_model", results.host.cpu_model},
            {"lp_num_threads", results.host.lp_num_threads},
            {"build_type", results.host.build_type},
            {"git_revision", results.host.git_revision},
            {"command", results.host.command},
    };
    nlohmann::json views = nlohmann::json::array();
    for (const CameraView& v : o.views) {
        views.push_back({{"name", v.name},
                         {"eye", {v.eye.x, v.eye.y, v.eye.z}},
                         {"target", {v.target.x, v.target.y, v.target.z}},
                         {"fov_y_radians", v.fov_y_radians},
                         {"near", v.near_plane},
                         {"far", v.far_plane}});
    }
    json["settings"] = {
            {"config", o.config_path},
            {"width", s.width},
            {"height", s.height},
            {"views", views},
            {"timing_view",
             o.timing_view.empty() && !o.views.empty() ? o.views.front().name : o.timing_view},
            {"warmup_frames", o.warmup_frames},
            {"coarse_frames", o.coarse_frames},
            {"pass_frames", o.pass_frames},
            {"workers", results.workers},
            {"timing_method",
             "every frame timed on `timing.clock` around submission + glFinish (wall clock beside "
             "it); each configuration gets coarse_frames frames on its own; each comparison is "
             "timed in pairs of frames rendered back to back on one thread, the side going first "
             "alternating, until the 95% Wilcoxon interval of the Hodges-Lehmann ratio is as "
             "narrow "
             "as timing.resolution_points or timing.max_pairs is reached"},
            {"animation_time_s", s.animation_time},
            {"clip_plane_offset", s.clip_plane_offset},
            {"wave_distortion", s.wave_distortion},
            {"bump_scale",
             {{s.bump_scale0.x, s.bump_scale0.y}, {s.bump_scale1.x, s.bump_scale1.y}}},
            {"bump_velocity",
             {{s.bump_velocity0.x, s.bump_velocity0.y}, {s.bump_velocity1.x, s.bump_velocity1.y}}},
            {"fog_colour", {s.fog_colour.r, s.fog_colour.g, s.fog_colour.b}},
            {"rcp_max_fog_distance", s.rcp_max_fog_distance},
            {"underwater_colour",
             {s.underwater_colour.r, s.underwater_colour.g, s.underwater_colour.b}},
            {"rcp_max_fog_depth", s.rcp_max_fog_depth},
            {"water_colour",
             {s.water_colour.r, s.water_colour.g, s.water_colour.b, s.water_colour.a}},
            {"low_res_water_size", s.low_res_water_size},
            {"sky_size", s.sky_size},
            {"normal_map_size", s.normal_map_size},
            {"normalisation_cube_size", s.normalisation_cube_size},
            {"max_water_depth", s.max_water_depth},
            {"extinction",
             {{"extinction",
               {s.extinction.extinction.r, s.extinction.extinction.g, s.extinction.extinction.b}},
              {"visibility", s.extinction.visibility},
              {"surface_colour",
               {s.extinction.surface_colour.r, s.extinction.surface_colour.g,
                s.extinction.surface_colour.b}},
              {"depth_colour",
               {s.extinction.depth_colour.r, s.extinction.depth_colour.g,
                s.extinction.depth_colour.b}}}},
            {"foam_depth", {s.foam_depth.x, s.foam_depth.y}},
            {"shore_hardness", s.shore_hardness},
            {"shininess", s.shininess},
            {"fourier",
             {{"coefficients", s.fourier.coefficients},
              {"directions", s.fourier.directions},
              {"march_distance", s.fourier.march_distance},
              {"integration_samples", s.fourier.integration_samples},
              {"grid_spacing", s.fourier.grid_spacing},
              {"grid_margin", s.fourier.grid_margin}}},
    };
    nlohmann::json configurations = nlohmann::json::array();
    for (const ConfigurationResult& r : results.configurations) {
        const RenderConfiguration& c = r.configuration;
        nlohmann::json diagnostics = nlohmann::json::array();
        for (const Diagnostic& d : r.verdict.diagnostics) {
            diagnostics.push_back(DiagnosticJson(d));
        }
        nlohmann::json view_results = nlohmann::json::array();
        for (const ViewResult& v : r.views) {
            nlohmann::json view = {{"view", v.view},
                                   {"image", v.image_path},
                                   {"passes", v.frame.passes},
                                   {"pass_names", v.frame.pass_names},
                                   {"draw_calls", v.frame.draw_calls},
                                   {"oblique_fallback", v.frame.oblique_fallback},
                                   {"gl_error", v.frame.gl_error}};
            if (v.accuracy) {
                // An identical image's PSNR is infinite, which JSON writes as null.
                view["accuracy"] = {{"psnr_db", v.accuracy->psnr_db},
                                    {"ssim", v.accuracy->ssim},
                                    {"share_visible", v.accuracy->share_visible}};
            }
            view_results.push_back(std::move(view));
        }
        nlohmann::json entry = {
                {"id", c.id},
                {"variant", c.variant.Id()},
                {"program", c.variant.program},
                {"defines", c.variant.defines},
                {"effects", c.effects},
                {"uniform_bools", c.UsesUniformBools()},
                {"presets", c.presets},
                {"passes",
                 {{"reflection_size", ReflectionSize(c.passes, s.width, s.height)},
                  {"refraction_size", RefractionSize(c.passes, s.width, s.height)},
                  {"low_res_water", c.passes.low_res_water},
                  {"depth_fog", c.passes.depth_fog},
                  {"clip", c.passes.clip},
                  {"culling", c.passes.culling}}},
                {"driver",
                 {{"valid", r.verdict.valid},
                  {"vertex_compiled", r.verdict.vertex_compiled},
                  {"fragment_compiled", r.verdict.fragment_compiled},
                  {"linked", r.verdict.linked},
                  {"vertex_log", r.verdict.vertex_log},
                  {"fragment_log", r.verdict.fragment_log},
                  {"link_log", r.verdict.link_log},
                  {"diagnostics", diagnostics}}},
                {"glslang_valid",
                 r.glslang_valid ? nlohmann::json(*r.glslang_valid) : nlohmann::json(nullptr)},
                {"views", view_results},
                {"frame_passes", r.passes},
                {"frame_draw_calls", r.draw_calls},
                {"samples_ms", r.samples_ms},
                {"statistics", StatisticsJson(r.statistics)},
                {"cpu_samples_ms", r.cpu_samples_ms},
                {"cpu_statistics", StatisticsJson(r.cpu_statistics)},
                {"plan_ms_median", r.plan_ms_median},
                {"pass_ms", r.pass_ms},
                {"instrumented_frame_ms", r.instrumented_frame_ms},
                {"gl_error", r.gl_error},
                {"ok", r.Ok()},
        };
        configurations.push_back(std::move(entry));
    }
    json["configurations"] = std::move(configurations);
    json["timing"] = {{"clock", FrameClockName(results.clock.clock)},
                      {"clock_reason", results.clock.reason},
                      {"resolution_points", o.rule.resolution_points},
                      {"min_pairs", o.rule.min_pairs},
                      {"max_pairs", o.rule.max_pairs},
                      {"batch_pairs", o.rule.batch_pairs},
                      {"confidence", base::kConfidenceLevel},
                      {"estimator",
                       "Hodges-Lehmann median of Walsh averages of per-pair log "
                       "ratios; Wilcoxon signed-rank interval"}};
    nlohmann::json comparisons = nlohmann::json::array();
    for (const ComparisonResult& c : results.comparisons) {
        const base::PairedEstimate& e = c.timing.estimate;
        auto number = [](double v) {
            return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
        };
        const bool indices_ok = c.comparison.baseline < results.configurations.size() &&
                                c.comparison.candidate < results.configurations.size();
        comparisons.push_back({
                {"label", c.comparison.label},
                {"baseline",
                 indices_ok ? results.configurations[c.comparison.baseline].configuration.id
                            : std::string()},
                {"candidate",
                 indices_ok ? results.configurations[c.comparison.candidate].configuration.id
                            : std::string()},
                {"error", c.error},
                {"pairs", e.pairs},
                {"decision", base::StopDecisionName(c.timing.decision)},
                {"ratio", number(e.ratio)},
                {"ratio_low", number(e.ratio_low)},
                {"ratio_high", number(e.ratio_high)},
                {"change_percent", number(e.change_percent)},
                {"change_low", number(e.change_low)},
                {"change_high", number(e.change_high)},
                {"baseline_ms", c.timing.samples.baseline_ms},
                {"candidate_ms", c.timing.samples.candidate_ms},
                {"baseline_wall_ms", c.timing.samples.baseline_wall_ms},
                {"candidate_wall_ms", c.timing.samples.candidate_wall_ms},
        });
    }
    json["comparisons"] = std::move(comparisons);
    nlohmann::json disagreements = nlohmann::json::array();
    for (const VerdictDisagreement& d : results.disagreements) {
        disagreements.push_back({{"variant", d.variant},
                                 {"glslang_valid", d.glslang_valid},
                                 {"mesa_valid", d.mesa_valid}});
    }
    json["disagreements"] = std::move(disagreements);
    nlohmann::json diagnostics = nlohmann::json::array();
    for (const Diagnostic& d : results.diagnostics) {
        diagnostics.push_back(DiagnosticJson(d));
    }
    json["diagnostics"] = std::move(diagnostics);
    json["ok"] = results.AllOk();
    return json;
}

}  // namespace tidepool::runner
