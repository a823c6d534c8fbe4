// The render run: compile, images, warm-up, interleaved timing rounds, results.json.
#include "tidepool/runner/Results.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <system_error>

#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/ImageIo.h"

namespace tidepool::runner {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time of this whole process: llvmpipe rasterises on worker threads of this process, so the
// sum over threads is the work a frame costs, whatever else the machine is running.
double ProcessCpuSeconds() {
    timespec now{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

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
    return {{"severity", SeverityName(d.severity)}, {"file", d.file},
            {"line", d.line},                       {"column", d.column},
            {"message", d.message},                 {"variant", d.variant},
            {"text", FormatDiagnostic(d)}};
}

nlohmann::json StatisticsJson(const SampleStatistics& s) {
    return {{"count", s.count},     {"min_ms", s.min},         {"max_ms", s.max},
            {"mean_ms", s.mean},    {"median_ms", s.median},   {"q1_ms", s.q1},
            {"q3_ms", s.q3},        {"iqr_ms", s.iqr},         {"ci_low_ms", s.ci_low},
            {"ci_high_ms", s.ci_high}, {"ci_coverage", s.ci_coverage},
            {"ci_method", "order statistics of the median, binomial(n, 0.5) coverage"}};
}

}  // namespace

bool RunResults::AllOk() const {
    return std::all_of(configurations.begin(), configurations.end(),
                       [](const ConfigurationResult& c) { return c.Ok(); });
}

RunResults RunRender(GlContext& context, const VariantConfig& config, const RunOptions& options,
                     const ProgressCallback& progress) {
    RunResults results;
    results.gl = context.Environment();
    results.host = options.host;
    results.options = options;
    results.started_utc = UtcNow();
    const Clock::time_point start = Clock::now();

    std::string error;
    std::unique_ptr<WaterRenderer> renderer =
        WaterRenderer::Create(context, config, options.settings, &error);
    if (!renderer) {
        results.diagnostics.push_back(MakeError("", 0, 0, "cannot set up the renderer: " + error));
        return results;
    }
    const CameraView* timing_view = nullptr;
    for (const CameraView& view : options.views) {
        if (options.timing_view.empty() || view.name == options.timing_view) {
            timing_view = &view;
            break;
        }
    }

    const long count = static_cast<long>(options.configurations.size());
    const long per_config = static_cast<long>(options.views.size()) + options.warmup_frames +
                            static_cast<long>(options.rounds) *
                                    std::max(options.frames_per_round,
                                             options.preset_frames_per_round) +
                            1;
    RunProgress state;
    state.total = count * per_config;
    auto step = [&](const char* stage, const std::string& id, long amount) {
        state.stage = stage;
        state.configuration = id;
        state.done += amount;
        state.elapsed_seconds = Seconds(Clock::now() - start);
        state.eta_seconds = state.done > 0 ? state.elapsed_seconds /
                                                 static_cast<double>(state.done) *
                                                 static_cast<double>(state.total - state.done)
                                           : 0.0;
        if (progress) {
            progress(state);
        }
    };

    // Driver compile and link of every configuration.
    for (const RenderConfiguration& configuration : options.configurations) {
        ConfigurationResult result;
        result.configuration = configuration;
        result.verdict = renderer->Prepare(configuration);
        for (const Diagnostic& d : result.verdict.diagnostics) {
            results.diagnostics.push_back(d);
        }
        results.configurations.push_back(std::move(result));
        step("compile", configuration.id, 1);
    }

    // glslang's verdict on the same variants, to list where the two compilers disagree.
    if (options.compare_with_glslang) {
        std::vector<Variant> variants;
        std::set<std::string> seen;
        for (const ConfigurationResult& r : results.configurations) {
            if (seen.insert(r.configuration.variant.Id()).second) {
                variants.push_back(r.configuration.variant);
            }
        }
        const ValidationReport report = ValidateVariants(config, variants, ValidationOptions{});
        std::map<std::string, bool> glslang;
        for (const VariantVerdict& v : report.verdicts) {
            glslang[v.variant.Id()] = v.valid;
        }
        std::set<std::string> listed;
        for (ConfigurationResult& r : results.configurations) {
            const std::string id = r.configuration.variant.Id();
            auto found = glslang.find(id);
            if (found == glslang.end()) {
                continue;
            }
            r.glslang_valid = found->second;
            // Only the variant's own program counts: a helper program's failure is not its fault.
            const bool mesa_valid = r.verdict.linked;
            if (found->second != mesa_valid && listed.insert(id).second) {
                results.disagreements.push_back(VerdictDisagreement{id, found->second, mesa_valid});
            }
        }
    }

    // One image per configuration per view.
    for (ConfigurationResult& r : results.configurations) {
        for (const CameraView& view : options.views) {
            if (!r.verdict.valid) {
                step("images", r.configuration.id, 1);
                continue;
            }
            ViewResult view_result;
            view_result.view = view.name;
            view_result.frame = renderer->RenderFrame(r.configuration, view);
            renderer->Finish();
            if (!view_result.frame.gl_error.empty() && r.gl_error.empty()) {
                r.gl_error = fmt::format("{} (view {})", view_result.frame.gl_error, view.name);
            }
            if (options.write_images) {
                const std::string name = fmt::format(
                    "images/{}-{}.png", SanitiseFileName(r.configuration.id), view.name);
                const std::string write_error =
                    WritePng(options.out_dir / name, renderer->ReadImage());
                if (write_error.empty()) {
                    view_result.image_path = name;
                } else {
                    results.diagnostics.push_back(MakeError("", 0, 0, write_error));
                }
            }
            if (&view == timing_view) {
                r.passes = view_result.frame.passes;
                r.draw_calls = view_result.frame.draw_calls;
            }
            r.views.push_back(std::move(view_result));
            step("images", r.configuration.id, 1);
        }
    }

    // Timing at one view: warm-up, then rounds that each render every configuration.
    std::vector<std::size_t> timed;
    for (std::size_t i = 0; i < results.configurations.size(); ++i) {
        if (results.configurations[i].verdict.valid && timing_view != nullptr) {
            timed.push_back(i);
        }
    }
    std::vector<std::vector<double>> plan_ms(results.configurations.size());
    for (std::size_t i : timed) {
        ConfigurationResult& r = results.configurations[i];
        for (int f = 0; f < options.warmup_frames; ++f) {
            const FrameReport frame = renderer->RenderFrame(r.configuration, *timing_view);
            renderer->Finish();
            if (!frame.gl_error.empty() && r.gl_error.empty()) {
                r.gl_error = frame.gl_error;
            }
            step("warmup", r.configuration.id, 1);
        }
        r.samples_ms.assign(static_cast<std::size_t>(std::max(options.rounds, 0)), {});
        r.cpu_samples_ms.assign(r.samples_ms.size(), {});
    }
    // With preset frames set, the configurations a preset asked for form a group of their own,
    // timed first in every round: the whitepaper verdicts compare them in pairs, and within
    // their group a pair's samples lie a few seconds apart instead of a whole matrix round
    // (minutes, with every variant in it), so drift on a shared machine mostly cancels in the
    // per-round ratio. Without preset frames every configuration is one group.
    const bool preset_group = options.preset_frames_per_round > 0;
    std::vector<std::vector<std::size_t>> groups(2);
    for (std::size_t i : timed) {
        const bool preset = preset_group && !results.configurations[i].configuration.presets.empty();
        groups[preset ? 0 : 1].push_back(i);
    }
    for (int round = 0; round < options.rounds; ++round) {
        for (std::size_t g = 0; g < groups.size(); ++g) {
            const std::vector<std::size_t>& group = groups[g];
            const int frames = g == 0 ? options.preset_frames_per_round : options.frames_per_round;
            for (std::size_t k = 0; k < group.size(); ++k) {
                // Rotate the order each round so no configuration always follows the same one.
                const std::size_t i = group[(k + static_cast<std::size_t>(round)) % group.size()];
                ConfigurationResult& r = results.configurations[i];
                for (int f = 0; f < frames; ++f) {
                    const double cpu_start = ProcessCpuSeconds();
                    const Clock::time_point frame_start = Clock::now();
                    const FrameReport frame = renderer->RenderFrame(r.configuration, *timing_view);
                    renderer->Finish();
                    const double ms = Seconds(Clock::now() - frame_start) * 1000.0;
                    const double cpu_ms = (ProcessCpuSeconds() - cpu_start) * 1000.0;
                    r.samples_ms[static_cast<std::size_t>(round)].push_back(ms);
                    r.cpu_samples_ms[static_cast<std::size_t>(round)].push_back(cpu_ms);
                    plan_ms[i].push_back(frame.plan_seconds * 1000.0);
                    if (!frame.gl_error.empty() && r.gl_error.empty()) {
                        r.gl_error = frame.gl_error;
                    }
                    step("timing", r.configuration.id, 1);
                }
            }
        }
    }
    for (std::size_t i : timed) {
        ConfigurationResult& r = results.configurations[i];
        std::vector<double> all;
        for (const std::vector<double>& round : r.samples_ms) {
            all.insert(all.end(), round.begin(), round.end());
        }
        r.statistics = ComputeSampleStatistics(all);
        std::vector<double> all_cpu;
        for (const std::vector<double>& round : r.cpu_samples_ms) {
            all_cpu.insert(all_cpu.end(), round.begin(), round.end());
        }
        r.cpu_statistics = ComputeSampleStatistics(all_cpu);
        r.plan_ms_median = ComputeSampleStatistics(plan_ms[i]).median;
    }
    for (const ConfigurationResult& r : results.configurations) {
        if (!r.gl_error.empty()) {
            results.diagnostics.push_back(Diagnostic{
                Severity::kError, "", 0, 0, "GL error while rendering: " + r.gl_error,
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
    json["schema_version"] = kResultsSchemaVersion;
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
        {"timing_view", o.timing_view.empty() && !o.views.empty() ? o.views.front().name
                                                                   : o.timing_view},
        {"warmup_frames", o.warmup_frames},
        {"rounds", o.rounds},
        {"frames_per_round", o.frames_per_round},
        {"preset_frames_per_round",
         o.preset_frames_per_round > 0 ? o.preset_frames_per_round : o.frames_per_round},
        {"timing_method", "steady_clock (samples_ms) and CLOCK_PROCESS_CPUTIME_ID "
                          "(cpu_samples_ms) around submission + glFinish, per frame; rounds "
                          "interleave configurations, order rotated each round; with "
                          "preset_frames_per_round the preset configurations are timed as a "
                          "group of their own at the start of each round"},
        {"animation_time_s", s.animation_time},
        {"clip_plane_offset", s.clip_plane_offset},
        {"wave_distortion", s.wave_distortion},
        {"bump_scale", {{s.bump_scale0.x, s.bump_scale0.y}, {s.bump_scale1.x, s.bump_scale1.y}}},
        {"bump_velocity",
         {{s.bump_velocity0.x, s.bump_velocity0.y}, {s.bump_velocity1.x, s.bump_velocity1.y}}},
        {"fog_colour", {s.fog_colour.r, s.fog_colour.g, s.fog_colour.b}},
        {"rcp_max_fog_distance", s.rcp_max_fog_distance},
        {"underwater_colour",
         {s.underwater_colour.r, s.underwater_colour.g, s.underwater_colour.b}},
        {"rcp_max_fog_depth", s.rcp_max_fog_depth},
        {"water_colour", {s.water_colour.r, s.water_colour.g, s.water_colour.b, s.water_colour.a}},
        {"low_res_water_size", s.low_res_water_size},
        {"sky_size", s.sky_size},
        {"normal_map_size", s.normal_map_size},
        {"normalisation_cube_size", s.normalisation_cube_size},
        {"max_water_depth", s.max_water_depth},
        {"extinction",
         {{"extinction", {s.extinction.extinction.r, s.extinction.extinction.g,
                          s.extinction.extinction.b}},
          {"visibility", s.extinction.visibility},
          {"surface_colour", {s.extinction.surface_colour.r, s.extinction.surface_colour.g,
                              s.extinction.surface_colour.b}},
          {"depth_colour", {s.extinction.depth_colour.r, s.extinction.depth_colour.g,
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
            view_results.push_back({{"view", v.view},
                                    {"image", v.image_path},
                                    {"passes", v.frame.passes},
                                    {"pass_names", v.frame.pass_names},
                                    {"draw_calls", v.frame.draw_calls},
                                    {"oblique_fallback", v.frame.oblique_fallback},
                                    {"gl_error", v.frame.gl_error}});
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
             {{"reflection_size", c.passes.reflection_size},
              {"low_res_water", c.passes.low_res_water},
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
            {"glslang_valid", r.glslang_valid ? nlohmann::json(*r.glslang_valid)
                                              : nlohmann::json(nullptr)},
            {"views", view_results},
            {"frame_passes", r.passes},
            {"frame_draw_calls", r.draw_calls},
            {"samples_ms", r.samples_ms},
            {"statistics", StatisticsJson(r.statistics)},
            {"cpu_samples_ms", r.cpu_samples_ms},
            {"cpu_statistics", StatisticsJson(r.cpu_statistics)},
            {"plan_ms_median", r.plan_ms_median},
            {"gl_error", r.gl_error},
            {"ok", r.Ok()},
        };
        configurations.push_back(std::move(entry));
    }
    json["configurations"] = std::move(configurations);
    nlohmann::json disagreements = nlohmann::json::array();
    for (const VerdictDisagreement& d : results.disagreements) {
        disagreements.push_back(
            {{"variant", d.variant}, {"glslang_valid", d.glslang_valid}, {"mesa_valid", d.mesa_valid}});
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

std::string WriteJsonAtomically(const std::filesystem::path& path, const nlohmann::json& json) {
    std::error_code error;
    if (path.has_parent_path()) {
        std::filesystem::create_directories(path.parent_path(), error);
        if (error) {
            return "cannot create " + path.parent_path().string() + ": " + error.message();
        }
    }
    std::filesystem::path temporary = path;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << JsonText(json, 2) << '\n';
        out.flush();
        if (!out) {
            return "cannot write " + temporary.string();
        }
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        return "cannot rename " + temporary.string() + " to " + path.string() + ": " +
               error.message();
    }
    return "";
}

}  // namespace tidepool::runner
