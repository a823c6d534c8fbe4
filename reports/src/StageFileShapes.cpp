#include "tidepool/report/StageFileShapes.h"

#include "tidepool/stagefiles/WrongTypeMessage.h"

#include <map>
#include <string>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

// Each writer's fields and their types. A writer that adds a field need not change its shape
// (unknown fields pass); one that changes a field's type must, or every report of its files
// fails: the CLI tests build reports from files the real writers wrote, so they catch it.
// Shapes used at several places, named there as "$name" (Resolve): a stage's static cost
// (compiler/src/StaticCost.cpp), a diagnostic (Diagnostic.h's fields, `text` in results.json),
// the summary of a configuration's frame times (base/SampleStatistics.h) and a configuration's
// pass options. plans.json and stability.json are checked by their readers (stagefiles/).
constexpr const char* kStatisticsShape = R"json(
{
  "ci_coverage": "number",
  "ci_high_ms": "number",
  "ci_low_ms": "number",
  "ci_method": "string",
  "count": "number",
  "iqr_ms": "number",
  "max_ms": "number",
  "mean_ms": "number",
  "median_ms": "number",
  "min_ms": "number",
  "q1_ms": "number",
  "q3_ms": "number"
}
)json";

constexpr const char* kDiagnosticShape = R"json(
{
  "severity": "string",
  "file": "string",
  "line": "number",
  "column": "number",
  "message": "string",
  "variant": "string",
  "text": "string"
}
)json";

// A configuration's pass options (manifest presets, results configurations).
constexpr const char* kPassOptionsShape = R"json(
{
  "clip": "string",
  "culling": "bool",
  "depth_fog": "bool",
  "low_res_water": "bool",
  "reflection_size": "number",
  "refraction_size": "number"
}
)json";

constexpr const char* kStageCostShape = R"json(
{
  "arithmetic_ops": "number",
  "branches": "number",
  "builtin_calls": {"*": "number"},
  "longest_path_ops": "number",
  "loops": "number",
  "samplers": "number",
  "shortest_path_ops": "number",
  "texture_samples": "number",
  "total_ops": "number",
  "uniforms": "number",
  "varyings": "number"
}
)json";

// Written by compiler/src/Manifest.cpp (`tidepool validate --out`).
constexpr const char* kManifestShape = R"json(
{
  "config": "string",
  "counts": {
    "invalid": "number",
    "links": "number",
    "pruned": "number",
    "shared_stage_slots": "number",
    "stage_programs": "number",
    "stage_slots": "number",
    "variants": "number"
  },
  "presets": [
    {
      "description": "string",
      "name": "string",
      "passes": "$pass_options",
      "runtime_features": ["string"],
      "variant": "string"
    }
  ],
  "programs": [{"defines": ["string"], "fragment": "string", "name": "string", "vertex": "string"}],
  "pruned_by_rule": [
    {
      "count": "number",
      "file": "string",
      "line": "number",
      "program": "string",
      "rule": "string"
    }
  ],
  "schema": "string",
  "stage_programs": [
    {
      "cost": "$cost",
      "defines": ["string"],
      "file": "string",
      "hash": "string",
      "stage": "string",
      "target": "string",
      "valid": "bool",
      "variants": ["string"]
    }
  ],
  "targets": ["string"],
  "variants": [
    {
      "defines": ["string"],
      "diagnostics": ["$diagnostic"],
      "failed_steps": ["string"],
      "id": "string",
      "program": "string",
      "stages": {
        "fragment": {"cost": "$cost", "file": "string", "hash": "string"},
        "vertex": {"cost": "$cost", "file": "string", "hash": "string"}
      },
      "steps": {"*": "string"},
      "target": "string",
      "valid": "bool"
    }
  ],
  "version": "number"
}
)json";

// Written by runner/src/Results.cpp, ResultsToJson.
constexpr const char* kResultsShape = R"json(
{
  "comparisons": [
    {
      "baseline": "string",
      "baseline_ms": ["number"],
      "baseline_wall_ms": ["number"],
      "candidate": "string",
      "candidate_ms": ["number"],
      "candidate_wall_ms": ["number"],
      "change_high": "number",
      "change_low": "number",
      "change_percent": "number",
      "decision": "string",
      "error": "string",
      "label": "string",
      "pairs": "number",
      "ratio": "number",
      "ratio_high": "number",
      "ratio_low": "number"
    }
  ],
  "configurations": [
    {
      "cpu_samples_ms": [["number"]],
      "cpu_statistics": "$statistics",
      "defines": ["string"],
      "driver": {
        "diagnostics": ["$diagnostic"],
        "fragment_compiled": "bool",
        "fragment_log": "string",
        "link_log": "string",
        "linked": "bool",
        "valid": "bool",
        "vertex_compiled": "bool",
        "vertex_log": "string"
      },
      "effects": ["string"],
      "frame_draw_calls": "number",
      "frame_passes": "number",
      "gl_error": "string",
      "glslang_valid": "bool?",
      "id": "string",
      "instrumented_frame_ms": "number",
      "ok": "bool",
      "pass_ms": {"*": "number"},
      "passes": "$pass_options",
      "plan_ms_median": "number",
      "presets": ["string"],
      "program": "string",
      "samples_ms": [["number"]],
      "statistics": "$statistics",
      "uniform_bools": "bool",
      "variant": "string",
      "views": [
        {
          "accuracy": {"psnr_db": "number", "share_visible": "number", "ssim": "number"},
          "draw_calls": "number",
          "gl_error": "string",
          "image": "string",
          "oblique_fallback": "bool",
          "pass_names": ["string"],
          "passes": "number",
          "view": "string"
        }
      ]
    }
  ],
  "diagnostics": ["$diagnostic"],
  "disagreements": [{"variant": "string", "glslang_valid": "bool", "mesa_valid": "bool"}],
  "environment": {
    "backend": "string",
    "build_type": "string",
    "command": "string",
    "context_api": "string",
    "cpu_model": "string",
    "float_render_target": "bool",
    "git_revision": "string",
    "gl_renderer": "string",
    "gl_version": "string",
    "glsl_version": "string",
    "lp_num_threads": "string",
    "mesa_version": "string",
    "timer_query": "bool"
  },
  "ok": "bool",
  "schema": "string",
  "schema_version": "number",
  "version": "number",
  "settings": {
    "animation_time_s": "number",
    "bump_scale": [["number"]],
    "bump_velocity": [["number"]],
    "clip_plane_offset": "number",
    "coarse_frames": "number",
    "config": "string",
    "extinction": {
      "depth_colour": ["number"],
      "extinction": ["number"],
      "surface_colour": ["number"],
      "visibility": "number"
    },
    "foam_depth": ["number"],
    "fog_colour": ["number"],
    "fourier": {
      "coefficients": "number",
      "directions": "number",
      "grid_margin": "number",
      "grid_spacing": "number",
      "integration_samples": "number",
      "march_distance": "number"
    },
    "height": "number",
    "low_res_water_size": "number",
    "max_water_depth": "number",
    "normal_map_size": "number",
    "normalisation_cube_size": "number",
    "pass_frames": "number",
    "rcp_max_fog_depth": "number",
    "rcp_max_fog_distance": "number",
    "shininess": "number",
    "shore_hardness": "number",
    "sky_size": "number",
    "timing_method": "string",
    "timing_view": "string",
    "underwater_colour": ["number"],
    "views": [
      {
        "eye": ["number"],
        "far": "number",
        "fov_y_radians": "number",
        "name": "string",
        "near": "number",
        "target": ["number"]
      }
    ],
    "warmup_frames": "number",
    "water_colour": ["number"],
    "wave_distortion": "number",
    "width": "number",
    "workers": "number"
  },
  "started_utc": "string",
  "timing": {
    "batch_pairs": "number",
    "clock": "string",
    "clock_reason": "string",
    "confidence": "number",
    "estimator": "string",
    "max_pairs": "number",
    "min_pairs": "number",
    "resolution_points": "number"
  },
  "wall_seconds": "number"
}
)json";

// `shape` with every "$name" leaf replaced by the named shape it stands for.
nlohmann::json Resolve(nlohmann::json shape) {
    static const std::map<std::string, nlohmann::json, std::less<>> named = {
            {"$cost", nlohmann::json::parse(kStageCostShape)},
            {"$diagnostic", nlohmann::json::parse(kDiagnosticShape)},
            {"$statistics", nlohmann::json::parse(kStatisticsShape)},
            {"$pass_options", nlohmann::json::parse(kPassOptionsShape)},
    };
    if (shape.is_string()) {
        const auto found = named.find(shape.get_ref<const std::string&>());
        return found != named.end() ? found->second : shape;
    }
    for (nlohmann::json& part : shape) {
        part = Resolve(std::move(part));
    }
    return shape;
}

// Whether `value` is of the type named by `type` (a shape's leaf; a trailing '?' allows null).
bool IsOfType(const nlohmann::json& value, std::string_view type) {
    if (!type.empty() && type.back() == '?') {
        return value.is_null() || IsOfType(value, type.substr(0, type.size() - 1));
    }
    if (type == "any") {
        return true;
    }
    if (type == "number") {
        return value.is_number() || value.is_null();  // NaN is written as null
    }
    if (type == "string") {
        return value.is_string();
    }
    if (type == "bool") {
        return value.is_boolean();
    }
    return false;
}

}  // namespace

std::string CheckJsonShape(const nlohmann::json& document, const nlohmann::json& shape,
                           const std::string& path) {
    if (shape.is_string()) {
        const std::string& type = shape.get_ref<const std::string&>();
        return IsOfType(document, type) ? std::string()
                                        : stagefiles::WrongTypeMessage(path, type, document);
    }
    if (shape.is_array()) {
        if (!document.is_array()) {
            return stagefiles::WrongTypeMessage(path, "array", document);
        }
        if (shape.empty()) {
            return {};
        }
        for (std::size_t i = 0; i < document.size(); ++i) {
            if (std::string problem =
                        CheckJsonShape(document[i], shape.front(), fmt::format("{}[{}]", path, i));
                !problem.empty()) {
                return problem;
            }
        }
        return {};
    }
    if (!document.is_object()) {
        return stagefiles::WrongTypeMessage(path, "object", document);
    }
    const auto every = shape.find("*");
    for (const auto& [key, value] : document.items()) {
        const auto field = every != shape.end() ? every : shape.find(key);
        if (field == shape.end()) {
            continue;  // a field this shape does not know: a newer writer's
        }
        const std::string field_path = path.empty() ? key : fmt::format("{}.{}", path, key);
        if (std::string problem = CheckJsonShape(value, *field, field_path); !problem.empty()) {
            return problem;
        }
    }
    return {};
}

std::string CheckStageFileShape(StageFile file, const nlohmann::json& document) {
    // Parsed once: the shapes are constants of this build.
    static const nlohmann::json manifest = Resolve(nlohmann::json::parse(kManifestShape));
    static const nlohmann::json results = Resolve(nlohmann::json::parse(kResultsShape));
    switch (file) {
        case StageFile::kManifest:
            return CheckJsonShape(document, manifest);
        case StageFile::kResults:
            return CheckJsonShape(document, results);
    }
    return {};
}

}  // namespace tidepool::report
