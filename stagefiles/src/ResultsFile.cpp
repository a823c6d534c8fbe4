#include "tidepool/stagefiles/ResultsFile.h"

#include "FieldReader.h"

namespace tidepool::stagefiles {
namespace {

nlohmann::json ToJson(const ResultsView& v) {
    return {{"name", v.name},     {"eye", v.eye},
            {"target", v.target}, {"fov_y_radians", v.fov_y_radians},
            {"near", v.near},     {"far", v.far}};
}

nlohmann::json ToJson(const ResultsStatistics& s) {
    return {{"count", s.count},
            {"min_ms", s.min_ms},
            {"max_ms", s.max_ms},
            {"mean_ms", s.mean_ms},
            {"median_ms", s.median_ms},
            {"q1_ms", s.q1_ms},
            {"q3_ms", s.q3_ms},
            {"iqr_ms", s.iqr_ms},
            {"ci_low_ms", s.ci_low_ms},
            {"ci_high_ms", s.ci_high_ms},
            {"ci_coverage", s.ci_coverage},
            {"ci_method", s.ci_method}};
}

nlohmann::json DiagnosticsJson(const std::vector<DiagnosticEntry>& diagnostics) {
    nlohmann::json list = nlohmann::json::array();
    for (const DiagnosticEntry& d : diagnostics) {
        list.push_back(ToJson(d));
    }
    return list;
}

nlohmann::json ToJson(const ResultsViewResult& v) {
    nlohmann::json view = {{"view", v.view},
                           {"image", v.image},
                           {"passes", v.passes},
                           {"pass_names", v.pass_names},
                           {"oblique_fallback", v.oblique_fallback},
                           {"gl_error", v.gl_error}};
    if (v.draw_calls) {
        view["draw_calls"] = *v.draw_calls;
    }
    if (v.accuracy) {
        view["accuracy"] = {{"psnr_db", v.accuracy->psnr_db},
                            {"ssim", v.accuracy->ssim},
                            {"share_visible", v.accuracy->share_visible}};
    }
    return view;
}

nlohmann::json ToJson(const ResultsConfiguration& c) {
    nlohmann::json views = nlohmann::json::array();
    for (const ResultsViewResult& v : c.views) {
        views.push_back(ToJson(v));
    }
    const ResultsDriver& d = c.driver;
    nlohmann::json entry = {
            {"id", c.id},
            {"program", c.program},
            {"defines", c.defines},
            {"effects", c.effects},
            {"uniform_bools", c.uniform_bools},
            {"presets", c.presets},
            {"passes", ToJson(c.passes)},
            {"driver",
             {{"valid", d.valid},
              {"vertex_compiled", d.vertex_compiled},
              {"fragment_compiled", d.fragment_compiled},
              {"linked", d.linked},
              {"vertex_log", d.vertex_log},
              {"fragment_log", d.fragment_log},
              {"link_log", d.link_log},
              {"diagnostics", DiagnosticsJson(d.diagnostics)}}},
            {"glslang_valid",
             c.glslang_valid ? nlohmann::json(*c.glslang_valid) : nlohmann::json()},
            {"views", views},
            {"frame_passes", c.frame_passes},
            {"frame_draw_calls", c.frame_draw_calls},
            {"samples_ms", c.samples_ms},
            {"cpu_samples_ms", c.cpu_samples_ms},
            {"plan_ms_median", c.plan_ms_median},
            {"pass_ms", c.pass_ms},
            {"instrumented_frame_ms", c.instrumented_frame_ms},
            {"gl_error", c.gl_error},
            {"ok", c.ok},
    };
    if (c.variant) {
        entry["variant"] = *c.variant;
    }
    if (c.statistics) {
        entry["statistics"] = ToJson(*c.statistics);
    }
    if (c.cpu_statistics) {
        entry["cpu_statistics"] = ToJson(*c.cpu_statistics);
    }
    return entry;
}

nlohmann::json ToJson(const ResultsTiming& t) {
    nlohmann::json timing = {{"clock", t.clock},
                             {"clock_reason", t.clock_reason},
                             {"min_pairs", t.min_pairs},
                             {"max_pairs", t.max_pairs},
                             {"batch_pairs", t.batch_pairs},
                             {"contended_share", t.contended_share},
                             {"confidence", t.confidence},
                             {"estimator", t.estimator}};
    if (t.resolution_points) {
        timing["resolution_points"] = *t.resolution_points;
    }
    if (t.boundary_pairs) {
        timing["boundary_pairs"] = *t.boundary_pairs;
    }
    if (t.boundary_standard_errors) {
        timing["boundary_standard_errors"] = *t.boundary_standard_errors;
    }
    return timing;
}

nlohmann::json ToJson(const ResultsComparison& c) {
    return {{"label", c.label},
            {"baseline", c.baseline},
            {"candidate", c.candidate},
            {"error", c.error},
            {"pairs", c.pairs},
            {"decision", c.decision},
            {"ratio", c.ratio},
            {"ratio_low", c.ratio_low},
            {"ratio_high", c.ratio_high},
            {"change_percent", c.change_percent},
            {"change_low", c.change_low},
            {"change_high", c.change_high},
            {"baseline_ms", c.baseline_ms},
            {"candidate_ms", c.candidate_ms},
            {"baseline_wall_ms", c.baseline_wall_ms},
            {"candidate_wall_ms", c.candidate_wall_ms},
            {"contended_baseline_ms", c.contended_baseline_ms},
            {"contended_candidate_ms", c.contended_candidate_ms},
            {"stated_change_low", c.stated_change_low},
            {"stated_change_high", c.stated_change_high},
            {"baseline_pass_ms", c.baseline_pass_ms},
            {"candidate_pass_ms", c.candidate_pass_ms},
            {"baseline_instrumented_frame_ms", c.baseline_instrumented_frame_ms},
            {"candidate_instrumented_frame_ms", c.candidate_instrumented_frame_ms},
            {"timed_by", c.timed_by}};
}

}  // namespace

nlohmann::json ToJson(const ResultsEnvironment& e) {
    return {{"backend", e.backend},
            {"context_api", e.context_api},
            {"gl_renderer", e.gl_renderer},
            {"gl_version", e.gl_version},
            {"glsl_version", e.glsl_version},
            {"mesa_version", e.mesa_version},
            {"float_render_target", e.float_render_target},
            {"timer_query", e.timer_query},
            {"cpu_model", e.cpu_model},
            {"lp_num_threads", e.lp_num_threads},
            {"build_type", e.build_type},
            {"git_revision", e.git_revision},
            {"command", e.command}};
}

nlohmann::json ToJson(const ResultsSettings& s) {
    nlohmann::json views = nlohmann::json::array();
    for (const ResultsView& v : s.views) {
        views.push_back(ToJson(v));
    }
    const ResultsExtinction& x = s.extinction;
    const ResultsFourier& f = s.fourier;
    return {{"config", s.config},
            {"width", s.width},
            {"height", s.height},
            {"views", views},
            {"timing_view", s.timing_view},
            {"warmup_frames", s.warmup_frames},
            {"coarse_frames", s.coarse_frames},
            {"pass_frames", s.pass_frames},
            {"workers", s.workers},
            {"timing_method", s.timing_method},
            {"animation_time_s", s.animation_time_s},
            {"clip_plane_offset", s.clip_plane_offset},
            {"wave_distortion", s.wave_distortion},
            {"bump_scale", s.bump_scale},
            {"bump_velocity", s.bump_velocity},
            {"fog_colour", s.fog_colour},
            {"rcp_max_fog_distance", s.rcp_max_fog_distance},
            {"underwater_colour", s.underwater_colour},
            {"rcp_max_fog_depth", s.rcp_max_fog_depth},
            {"water_colour", s.water_colour},
            {"low_res_water_size", s.low_res_water_size},
            {"sky_size", s.sky_size},
            {"normal_map_size", s.normal_map_size},
            {"normalisation_cube_size", s.normalisation_cube_size},
            {"max_water_depth", s.max_water_depth},
            {"extinction",
             {{"extinction", x.extinction},
              {"visibility", x.visibility},
              {"surface_colour", x.surface_colour},
              {"depth_colour", x.depth_colour}}},
            {"foam_depth", s.foam_depth},
            {"shore_hardness", s.shore_hardness},
            {"shininess", s.shininess},
            {"fourier",
             {{"coefficients", f.coefficients},
              {"directions", f.directions},
              {"march_distance", f.march_distance},
              {"integration_samples", f.integration_samples},
              {"grid_spacing", f.grid_spacing},
              {"grid_margin", f.grid_margin}}}};
}

nlohmann::json ToJson(const ResultsFile& file) {
    nlohmann::json json;
    json["schema"] = kResultsSchemaName;
    json[kVersionKey] = kResultsVersion;
    json["started_utc"] = file.started_utc;
    json["wall_seconds"] = file.wall_seconds;
    json["environment"] = ToJson(file.environment);
    json["settings"] = ToJson(file.settings);
    nlohmann::json configurations = nlohmann::json::array();
    for (const ResultsConfiguration& c : file.configurations) {
        configurations.push_back(ToJson(c));
    }
    json["configurations"] = std::move(configurations);
    json["timing"] = ToJson(file.timing);
    nlohmann::json comparisons = nlohmann::json::array();
    for (const ResultsComparison& c : file.comparisons) {
        comparisons.push_back(ToJson(c));
    }
    json["comparisons"] = std::move(comparisons);
    nlohmann::json disagreements = nlohmann::json::array();
    for (const ResultsDisagreement& d : file.disagreements) {
        disagreements.push_back({{"variant", d.variant},
                                 {"glslang_valid", d.glslang_valid},
                                 {"mesa_valid", d.mesa_valid}});
    }
    json["disagreements"] = std::move(disagreements);
    json["diagnostics"] = DiagnosticsJson(file.diagnostics);
    json["ok"] = file.ok;
    return json;
}

// The readers, one per type; FieldReader::Value finds them by ADL.
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsEnvironment* out) {
    r.Field(o, path, "backend", &out->backend);
    r.Field(o, path, "context_api", &out->context_api);
    r.Field(o, path, "gl_renderer", &out->gl_renderer);
    r.Field(o, path, "gl_version", &out->gl_version);
    r.Field(o, path, "glsl_version", &out->glsl_version);
    r.Field(o, path, "mesa_version", &out->mesa_version);
    r.Field(o, path, "float_render_target", &out->float_render_target);
    r.Field(o, path, "timer_query", &out->timer_query);
    r.Field(o, path, "cpu_model", &out->cpu_model);
    r.Field(o, path, "lp_num_threads", &out->lp_num_threads);
    r.Field(o, path, "build_type", &out->build_type);
    r.Field(o, path, "git_revision", &out->git_revision);
    r.Field(o, path, "command", &out->command);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsView* out) {
    r.Field(o, path, "name", &out->name);
    r.Field(o, path, "eye", &out->eye);
    r.Field(o, path, "target", &out->target);
    r.Field(o, path, "fov_y_radians", &out->fov_y_radians);
    r.Field(o, path, "near", &out->near);
    r.Field(o, path, "far", &out->far);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsExtinction* out) {
    r.Field(o, path, "extinction", &out->extinction);
    r.Field(o, path, "visibility", &out->visibility);
    r.Field(o, path, "surface_colour", &out->surface_colour);
    r.Field(o, path, "depth_colour", &out->depth_colour);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsFourier* out) {
    r.Field(o, path, "coefficients", &out->coefficients);
    r.Field(o, path, "directions", &out->directions);
    r.Field(o, path, "march_distance", &out->march_distance);
    r.Field(o, path, "integration_samples", &out->integration_samples);
    r.Field(o, path, "grid_spacing", &out->grid_spacing);
    r.Field(o, path, "grid_margin", &out->grid_margin);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsSettings* out) {
    r.Field(o, path, "config", &out->config);
    r.Field(o, path, "width", &out->width);
    r.Field(o, path, "height", &out->height);
    r.Field(o, path, "views", &out->views);
    r.Field(o, path, "timing_view", &out->timing_view);
    r.Field(o, path, "warmup_frames", &out->warmup_frames);
    r.Field(o, path, "coarse_frames", &out->coarse_frames);
    r.Field(o, path, "pass_frames", &out->pass_frames);
    r.Field(o, path, "workers", &out->workers);
    r.Field(o, path, "timing_method", &out->timing_method);
    r.Field(o, path, "animation_time_s", &out->animation_time_s);
    r.Field(o, path, "clip_plane_offset", &out->clip_plane_offset);
    r.Field(o, path, "wave_distortion", &out->wave_distortion);
    r.Field(o, path, "bump_scale", &out->bump_scale);
    r.Field(o, path, "bump_velocity", &out->bump_velocity);
    r.Field(o, path, "fog_colour", &out->fog_colour);
    r.Field(o, path, "rcp_max_fog_distance", &out->rcp_max_fog_distance);
    r.Field(o, path, "underwater_colour", &out->underwater_colour);
    r.Field(o, path, "rcp_max_fog_depth", &out->rcp_max_fog_depth);
    r.Field(o, path, "water_colour", &out->water_colour);
    r.Field(o, path, "low_res_water_size", &out->low_res_water_size);
    r.Field(o, path, "sky_size", &out->sky_size);
    r.Field(o, path, "normal_map_size", &out->normal_map_size);
    r.Field(o, path, "normalisation_cube_size", &out->normalisation_cube_size);
    r.Field(o, path, "max_water_depth", &out->max_water_depth);
    r.Field(o, path, "extinction", &out->extinction);
    r.Field(o, path, "foam_depth", &out->foam_depth);
    r.Field(o, path, "shore_hardness", &out->shore_hardness);
    r.Field(o, path, "shininess", &out->shininess);
    r.Field(o, path, "fourier", &out->fourier);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsDriver* out) {
    r.Field(o, path, "valid", &out->valid);
    r.Field(o, path, "vertex_compiled", &out->vertex_compiled);
    r.Field(o, path, "fragment_compiled", &out->fragment_compiled);
    r.Field(o, path, "linked", &out->linked);
    r.Field(o, path, "vertex_log", &out->vertex_log);
    r.Field(o, path, "fragment_log", &out->fragment_log);
    r.Field(o, path, "link_log", &out->link_log);
    r.Field(o, path, "diagnostics", &out->diagnostics);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsAccuracy* out) {
    r.Field(o, path, "psnr_db", &out->psnr_db);
    r.Field(o, path, "ssim", &out->ssim);
    r.Field(o, path, "share_visible", &out->share_visible);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsViewResult* out) {
    r.Field(o, path, "view", &out->view);
    r.Field(o, path, "image", &out->image);
    r.Field(o, path, "passes", &out->passes);
    r.Field(o, path, "pass_names", &out->pass_names);
    r.Field(o, path, "draw_calls", &out->draw_calls);
    r.Field(o, path, "oblique_fallback", &out->oblique_fallback);
    r.Field(o, path, "gl_error", &out->gl_error);
    r.Field(o, path, "accuracy", &out->accuracy);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsStatistics* out) {
    r.Field(o, path, "count", &out->count);
    r.Field(o, path, "min_ms", &out->min_ms);
    r.Field(o, path, "max_ms", &out->max_ms);
    r.Field(o, path, "mean_ms", &out->mean_ms);
    r.Field(o, path, "median_ms", &out->median_ms);
    r.Field(o, path, "q1_ms", &out->q1_ms);
    r.Field(o, path, "q3_ms", &out->q3_ms);
    r.Field(o, path, "iqr_ms", &out->iqr_ms);
    r.Field(o, path, "ci_low_ms", &out->ci_low_ms);
    r.Field(o, path, "ci_high_ms", &out->ci_high_ms);
    r.Field(o, path, "ci_coverage", &out->ci_coverage);
    r.Field(o, path, "ci_method", &out->ci_method);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsConfiguration* out) {
    r.Required(o, path, "id", &out->id);
    r.Field(o, path, "variant", &out->variant);
    r.Field(o, path, "program", &out->program);
    r.Field(o, path, "defines", &out->defines);
    r.Field(o, path, "effects", &out->effects);
    r.Field(o, path, "uniform_bools", &out->uniform_bools);
    r.Field(o, path, "presets", &out->presets);
    r.Field(o, path, "passes", &out->passes);
    r.Field(o, path, "driver", &out->driver);
    // Null when the runner did not compare the verdicts.
    if (const auto g = o.find("glslang_valid"); g == o.end() || !g->is_null()) {
        r.Field(o, path, "glslang_valid", &out->glslang_valid);
    }
    r.Field(o, path, "views", &out->views);
    r.Field(o, path, "frame_passes", &out->frame_passes);
    r.Field(o, path, "frame_draw_calls", &out->frame_draw_calls);
    r.Field(o, path, "samples_ms", &out->samples_ms);
    r.Field(o, path, "statistics", &out->statistics);
    r.Field(o, path, "cpu_samples_ms", &out->cpu_samples_ms);
    r.Field(o, path, "cpu_statistics", &out->cpu_statistics);
    r.Field(o, path, "plan_ms_median", &out->plan_ms_median);
    r.Field(o, path, "pass_ms", &out->pass_ms);
    r.Field(o, path, "instrumented_frame_ms", &out->instrumented_frame_ms);
    r.Field(o, path, "gl_error", &out->gl_error);
    r.Required(o, path, "ok", &out->ok);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsTiming* out) {
    r.Field(o, path, "clock", &out->clock);
    r.Field(o, path, "clock_reason", &out->clock_reason);
    r.Field(o, path, "resolution_points", &out->resolution_points);
    r.Field(o, path, "min_pairs", &out->min_pairs);
    r.Field(o, path, "max_pairs", &out->max_pairs);
    r.Field(o, path, "batch_pairs", &out->batch_pairs);
    r.Field(o, path, "contended_share", &out->contended_share);
    r.Field(o, path, "confidence", &out->confidence);
    r.Field(o, path, "estimator", &out->estimator);
    r.Field(o, path, "boundary_pairs", &out->boundary_pairs);
    r.Field(o, path, "boundary_standard_errors", &out->boundary_standard_errors);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsComparison* out) {
    r.Required(o, path, "label", &out->label);
    r.Required(o, path, "baseline", &out->baseline);
    r.Required(o, path, "candidate", &out->candidate);
    r.Field(o, path, "error", &out->error);
    r.Field(o, path, "pairs", &out->pairs);
    r.Field(o, path, "decision", &out->decision);
    r.Field(o, path, "ratio", &out->ratio);
    r.Field(o, path, "ratio_low", &out->ratio_low);
    r.Field(o, path, "ratio_high", &out->ratio_high);
    r.Field(o, path, "change_percent", &out->change_percent);
    r.Field(o, path, "change_low", &out->change_low);
    r.Field(o, path, "change_high", &out->change_high);
    r.Required(o, path, "baseline_ms", &out->baseline_ms);
    r.Required(o, path, "candidate_ms", &out->candidate_ms);
    r.Field(o, path, "baseline_wall_ms", &out->baseline_wall_ms);
    r.Field(o, path, "candidate_wall_ms", &out->candidate_wall_ms);
    r.Field(o, path, "contended_baseline_ms", &out->contended_baseline_ms);
    r.Field(o, path, "contended_candidate_ms", &out->contended_candidate_ms);
    r.Field(o, path, "stated_change_low", &out->stated_change_low);
    r.Field(o, path, "stated_change_high", &out->stated_change_high);
    r.Field(o, path, "baseline_pass_ms", &out->baseline_pass_ms);
    r.Field(o, path, "candidate_pass_ms", &out->candidate_pass_ms);
    r.Field(o, path, "baseline_instrumented_frame_ms", &out->baseline_instrumented_frame_ms);
    r.Field(o, path, "candidate_instrumented_frame_ms", &out->candidate_instrumented_frame_ms);
    r.Field(o, path, "timed_by", &out->timed_by);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsDisagreement* out) {
    r.Field(o, path, "variant", &out->variant);
    r.Field(o, path, "glslang_valid", &out->glslang_valid);
    r.Field(o, path, "mesa_valid", &out->mesa_valid);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ResultsFile* out) {
    r.Field(o, path, "started_utc", &out->started_utc);
    r.Field(o, path, "wall_seconds", &out->wall_seconds);
    r.Field(o, path, "environment", &out->environment);
    r.Field(o, path, "settings", &out->settings);
    r.Required(o, path, "configurations", &out->configurations);
    r.Field(o, path, "timing", &out->timing);
    r.Field(o, path, "comparisons", &out->comparisons);
    r.Field(o, path, "disagreements", &out->disagreements);
    r.Field(o, path, "diagnostics", &out->diagnostics);
    r.Field(o, path, "ok", &out->ok);
}

ReadResult<ResultsFile> ResultsFileFromJson(const nlohmann::json& document,
                                            const std::string& file_name) {
    // Only a file without `version` is read by its old key, so a file with both is judged by
    // the one every stage file now carries.
    const bool old_key = document.is_object() && !document.contains(kVersionKey) &&
                         document.contains(kOldResultsVersionKey);
    return ReadStageDocument<ResultsFile>(document, file_name, kResultsSchemaName, kResultsVersion,
                                          old_key ? kOldResultsVersionKey : kVersionKey);
}

ReadResult<ResultsFile> ReadResultsFile(const std::filesystem::path& path) {
    ReadResult<ResultsFile> result;
    std::optional<nlohmann::json> document = ReadJsonFile(path, &result.error);
    if (!document) {
        result.failure = ReadFailure::kUnreadable;
        return result;
    }
    return ResultsFileFromJson(*document, path.string());
}

std::string ResultsFileText(const ResultsFile& file) {
    return JsonText(ToJson(file), 2) + "\n";
}

}  // namespace tidepool::stagefiles
