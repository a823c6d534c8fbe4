#include "tidepool/stagefiles/ManifestFile.h"

#include "FieldReader.h"
#include <fmt/format.h>

namespace tidepool::stagefiles {
namespace {

// Declared before ListJson, whose ToJson calls must see them.
nlohmann::json ToJson(const ManifestProgram& p);
nlohmann::json ToJson(const ManifestPreset& p);
nlohmann::json ToJson(const ManifestVariant& v);
nlohmann::json ToJson(const ManifestPrunedRule& p);
nlohmann::json ToJson(const ManifestPrunedCombination& p);
nlohmann::json ToJson(const ManifestStageProgram& p);

template <typename T>
nlohmann::json ListJson(const std::vector<T>& items) {
    nlohmann::json list = nlohmann::json::array();
    for (const T& item : items) {
        list.push_back(ToJson(item));
    }
    return list;
}

nlohmann::json ToJson(const ManifestProgram& p) {
    return {{"name", p.name},
            {"vertex", p.vertex},
            {"fragment", p.fragment},
            {"defines", p.defines}};
}

nlohmann::json ToJson(const ManifestPreset& p) {
    return {{"name", p.name},
            {"description", p.description},
            {"variant", p.variant},
            {"runtime_features", p.runtime_features},
            {"passes", ToJson(p.passes)}};
}

nlohmann::json ToJson(const ManifestStage& s) {
    nlohmann::json stage = {{"hash", s.hash}};
    if (s.file) {
        stage["file"] = *s.file;
    }
    if (s.cost) {
        stage["cost"] = ToJson(*s.cost);
    }
    return stage;
}

nlohmann::json ToJson(const ManifestVariant& v) {
    nlohmann::json entry = {{"id", v.id}, {"program", v.program}, {"defines", v.defines}};
    if (v.target) {
        entry["target"] = *v.target;
    }
    if (v.valid) {
        entry["valid"] = *v.valid;
    }
    if (v.stages) {
        entry["stages"] = {{"vertex", ToJson(v.stages->vertex)},
                           {"fragment", ToJson(v.stages->fragment)}};
    }
    if (v.diagnostics) {
        entry["diagnostics"] = ListJson(*v.diagnostics);
    }
    if (v.steps) {
        entry["steps"] = *v.steps;
    }
    if (v.failed_steps) {
        entry["failed_steps"] = *v.failed_steps;
    }
    if (v.sources) {
        entry["sources"] = {{"vertex", v.sources->vertex}, {"fragment", v.sources->fragment}};
    }
    return entry;
}

nlohmann::json ToJson(const ManifestPrunedRule& p) {
    return {{"program", p.program},
            {"rule", p.rule},
            {"file", p.file},
            {"line", p.line},
            {"count", p.count}};
}

nlohmann::json ToJson(const ManifestPrunedCombination& p) {
    return {{"id", p.id},
            {"program", p.program},
            {"rule", p.rule},
            {"file", p.file},
            {"line", p.line}};
}

nlohmann::json ToJson(const ManifestStageProgram& p) {
    return {{"stage", p.stage}, {"target", p.target},    {"file", p.file},
            {"hash", p.hash},   {"defines", p.defines},  {"variants", p.variants},
            {"valid", p.valid}, {"cost", ToJson(p.cost)}};
}

}  // namespace

nlohmann::json ToJson(const DiagnosticEntry& d) {
    nlohmann::json json = {{"severity", d.severity}, {"file", d.file},
                           {"line", d.line},         {"column", d.column},
                           {"message", d.message},   {"variant", d.variant}};
    if (d.text) {
        json["text"] = *d.text;
    }
    return json;
}

nlohmann::json ToJson(const PassOptionsEntry& p) {
    nlohmann::json json = {{"reflection_size", p.reflection_size},
                           {"low_res_water", p.low_res_water},
                           {"depth_fog", p.depth_fog},
                           {"clip", p.clip},
                           {"culling", p.culling}};
    if (p.refraction_size) {
        json["refraction_size"] = *p.refraction_size;
    }
    return json;
}

nlohmann::json ToJson(const StageCostEntry& c) {
    return {{"arithmetic_ops", c.arithmetic_ops},
            {"texture_samples", c.texture_samples},
            {"builtin_calls", c.builtin_calls},
            {"branches", c.branches},
            {"loops", c.loops},
            {"uniforms", c.uniforms},
            {"varyings", c.varyings},
            {"samplers", c.samplers},
            {"shortest_path_ops", c.shortest_path_ops},
            {"longest_path_ops", c.longest_path_ops},
            {"total_ops", c.total_ops}};
}

nlohmann::json ToJson(const ManifestCounts& c) {
    nlohmann::json counts = {{"variants", c.variants}, {"pruned", c.pruned}};
    for (const auto& [key, value] :
         {std::pair{"stage_slots", &c.stage_slots}, std::pair{"stage_programs", &c.stage_programs},
          std::pair{"shared_stage_slots", &c.shared_stage_slots}, std::pair{"links", &c.links},
          std::pair{"invalid", &c.invalid}}) {
        if (*value) {
            counts[key] = **value;
        }
    }
    return counts;
}

nlohmann::json ToJson(const ManifestFile& file) {
    nlohmann::json manifest;
    manifest["schema"] = kManifestSchemaName;
    manifest[kVersionKey] = kManifestVersion;
    manifest["config"] = file.config;
    manifest["targets"] = file.targets;
    manifest["programs"] = ListJson(file.programs);
    manifest["presets"] = ListJson(file.presets);
    manifest["variants"] = ListJson(file.variants);
    if (file.pruned_by_rule) {
        manifest["pruned_by_rule"] = ListJson(*file.pruned_by_rule);
    }
    if (!file.pruned.empty()) {
        manifest["pruned"] = ListJson(file.pruned);
    }
    if (file.stage_programs) {
        manifest["stage_programs"] = ListJson(*file.stage_programs);
    }
    manifest["counts"] = ToJson(file.counts);
    return manifest;
}

// The readers, one per type; FieldReader::Value finds them by ADL.
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                DiagnosticEntry* out) {
    r.Field(o, path, "severity", &out->severity);
    r.Field(o, path, "file", &out->file);
    r.Field(o, path, "line", &out->line);
    r.Field(o, path, "column", &out->column);
    r.Field(o, path, "message", &out->message);
    r.Field(o, path, "variant", &out->variant);
    r.Field(o, path, "text", &out->text);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PassOptionsEntry* out) {
    r.Field(o, path, "reflection_size", &out->reflection_size);
    r.Field(o, path, "refraction_size", &out->refraction_size);
    r.Field(o, path, "low_res_water", &out->low_res_water);
    r.Field(o, path, "depth_fog", &out->depth_fog);
    r.Field(o, path, "clip", &out->clip);
    r.Field(o, path, "culling", &out->culling);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                StageCostEntry* out) {
    r.Field(o, path, "arithmetic_ops", &out->arithmetic_ops);
    r.Field(o, path, "texture_samples", &out->texture_samples);
    r.Field(o, path, "builtin_calls", &out->builtin_calls);
    r.Field(o, path, "branches", &out->branches);
    r.Field(o, path, "loops", &out->loops);
    r.Field(o, path, "uniforms", &out->uniforms);
    r.Field(o, path, "varyings", &out->varyings);
    r.Field(o, path, "samplers", &out->samplers);
    r.Field(o, path, "shortest_path_ops", &out->shortest_path_ops);
    r.Field(o, path, "longest_path_ops", &out->longest_path_ops);
    r.Field(o, path, "total_ops", &out->total_ops);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestProgram* out) {
    r.Field(o, path, "name", &out->name);
    r.Field(o, path, "vertex", &out->vertex);
    r.Field(o, path, "fragment", &out->fragment);
    r.Field(o, path, "defines", &out->defines);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestPreset* out) {
    r.Field(o, path, "name", &out->name);
    r.Field(o, path, "description", &out->description);
    r.Field(o, path, "variant", &out->variant);
    r.Field(o, path, "runtime_features", &out->runtime_features);
    r.Field(o, path, "passes", &out->passes);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestStage* out) {
    r.Field(o, path, "hash", &out->hash);
    r.Field(o, path, "file", &out->file);
    r.Field(o, path, "cost", &out->cost);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestStages* out) {
    r.Field(o, path, "vertex", &out->vertex);
    r.Field(o, path, "fragment", &out->fragment);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestSources* out) {
    r.Field(o, path, "vertex", &out->vertex);
    r.Field(o, path, "fragment", &out->fragment);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestVariant* out) {
    r.Field(o, path, "id", &out->id);
    r.Field(o, path, "program", &out->program);
    // The report keys everything on these two: present but empty is as bad as absent.
    for (const auto& [key, value] :
         {std::pair{"id", &out->id}, std::pair{"program", &out->program}}) {
        if (r.Ok() && value->empty()) {
            r.Fail(ReadFailure::kMissingField,
                   fmt::format("'{}' is not a non-empty string", FieldReader::Join(path, key)));
        }
    }
    r.Field(o, path, "defines", &out->defines);
    r.Field(o, path, "target", &out->target);
    r.Field(o, path, "valid", &out->valid);
    r.Field(o, path, "stages", &out->stages);
    r.Field(o, path, "diagnostics", &out->diagnostics);
    r.Field(o, path, "steps", &out->steps);
    r.Field(o, path, "failed_steps", &out->failed_steps);
    r.Field(o, path, "sources", &out->sources);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestPrunedRule* out) {
    r.Field(o, path, "program", &out->program);
    r.Field(o, path, "rule", &out->rule);
    r.Field(o, path, "file", &out->file);
    r.Field(o, path, "line", &out->line);
    r.Field(o, path, "count", &out->count);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestPrunedCombination* out) {
    r.Field(o, path, "id", &out->id);
    r.Field(o, path, "program", &out->program);
    r.Field(o, path, "rule", &out->rule);
    r.Field(o, path, "file", &out->file);
    r.Field(o, path, "line", &out->line);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestStageProgram* out) {
    r.Field(o, path, "stage", &out->stage);
    r.Field(o, path, "target", &out->target);
    r.Field(o, path, "file", &out->file);
    r.Field(o, path, "hash", &out->hash);
    r.Field(o, path, "defines", &out->defines);
    r.Field(o, path, "variants", &out->variants);
    r.Field(o, path, "valid", &out->valid);
    r.Field(o, path, "cost", &out->cost);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestCounts* out) {
    r.Field(o, path, "variants", &out->variants);
    r.Field(o, path, "pruned", &out->pruned);
    r.Field(o, path, "stage_slots", &out->stage_slots);
    r.Field(o, path, "stage_programs", &out->stage_programs);
    r.Field(o, path, "shared_stage_slots", &out->shared_stage_slots);
    r.Field(o, path, "links", &out->links);
    r.Field(o, path, "invalid", &out->invalid);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                ManifestFile* out) {
    r.Field(o, path, "config", &out->config);
    r.Field(o, path, "targets", &out->targets);
    r.Field(o, path, "programs", &out->programs);
    r.Field(o, path, "presets", &out->presets);
    r.Required(o, path, "variants", &out->variants);
    r.Field(o, path, "pruned_by_rule", &out->pruned_by_rule);
    r.Field(o, path, "pruned", &out->pruned);
    r.Field(o, path, "stage_programs", &out->stage_programs);
    r.Required(o, path, "counts", &out->counts);
}

ReadResult<ManifestFile> ManifestFileFromJson(const nlohmann::json& document,
                                              const std::string& file_name) {
    return ReadStageDocument<ManifestFile>(document, file_name, kManifestSchemaName,
                                           kManifestVersion);
}

ReadResult<ManifestFile> ReadManifestFile(const std::filesystem::path& path) {
    return ReadStageFile<ManifestFile>(path, kManifestSchemaName, kManifestVersion);
}

std::string ManifestFileText(const ManifestFile& file) {
    return JsonText(ToJson(file), 2) + "\n";
}

}  // namespace tidepool::stagefiles
