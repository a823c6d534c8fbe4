#include "tidepool/Manifest.h"

#include <map>

namespace tidepool {

nlohmann::json ToJson(const Diagnostic& diagnostic) {
    return {{"severity", SeverityName(diagnostic.severity)},
            {"file", diagnostic.file},
            {"line", diagnostic.line},
            {"column", diagnostic.column},
            {"message", diagnostic.message},
            {"variant", diagnostic.variant}};
}

nlohmann::json StepsJson(const VariantVerdict& verdict) {
    nlohmann::json steps = nlohmann::json::object();
    nlohmann::json failed = nlohmann::json::array();
    for (const auto& [name, step] : verdict.NamedSteps()) {
        steps[name] = StepStatusName(step->status);
        if (step->status == StepStatus::kInvalid) {
            failed.push_back(name);
        }
    }
    return {{"steps", steps}, {"failed_steps", failed}};
}

namespace {

nlohmann::json DiagnosticsJson(const std::vector<Diagnostic>& diagnostics) {
    nlohmann::json list = nlohmann::json::array();
    for (const Diagnostic& d : diagnostics) {
        list.push_back(ToJson(d));
    }
    return list;
}

}  // namespace

nlohmann::json BuildManifest(const VariantConfig& config, const ExpansionResult& expansion,
                             const ValidationReport* validation) {
    nlohmann::json manifest;
    manifest["schema"] = kManifestSchema;
    manifest["version"] = kManifestVersion;
    manifest["config"] = config.path;
    nlohmann::json targets = nlohmann::json::array();
    for (GlslTarget target : config.targets) {
        targets.push_back(TargetName(target));
    }
    manifest["targets"] = targets;

    nlohmann::json programs = nlohmann::json::array();
    for (const ProgramConfig& program : config.programs) {
        programs.push_back({{"name", program.name},
                            {"vertex", program.vertex_path},
                            {"fragment", program.fragment_path},
                            {"defines", program.AllDefines()}});
    }
    manifest["programs"] = programs;

    nlohmann::json presets = nlohmann::json::array();
    for (const Preset& preset : config.presets) {
        presets.push_back({{"name", preset.name},
                           {"description", preset.description},
                           {"variant", MakeVariant(preset.program, preset.defines).Id()},
                           {"runtime_features", preset.runtime_features},
                           {"passes",
                            {{"reflection_size", preset.passes.reflection_size},
                             {"refraction_size", preset.passes.refraction_size},
                             {"low_res_water", preset.passes.low_res_water},
                             {"depth_fog", preset.passes.depth_fog},
                             {"clip", preset.passes.clip},
                             {"culling", preset.passes.culling}}}});
    }
    manifest["presets"] = presets;

    // Stage programs by (file, hash) so each verdict can carry its stages' static cost.
    std::map<std::string, const StageProgram*> by_hash;
    if (validation != nullptr) {
        for (const StageProgram& program : validation->stage_programs) {
            by_hash[program.file + "|" + program.hash] = &program;
        }
    }

    nlohmann::json variants = nlohmann::json::array();
    if (validation == nullptr) {
        for (const Variant& variant : expansion.variants) {
            variants.push_back({{"id", variant.Id()},
                                {"program", variant.program},
                                {"defines", variant.defines}});
        }
    } else {
        for (const VariantVerdict& verdict : validation->verdicts) {
            const ProgramConfig* program = config.FindProgram(verdict.variant.program);
            nlohmann::json entry = {{"id", verdict.variant.Id()},
                                    {"program", verdict.variant.program},
                                    {"defines", verdict.variant.defines},
                                    {"target", TargetName(verdict.target)},
                                    {"valid", verdict.valid},
                                    {"stages",
                                     {{"vertex", {{"hash", verdict.vertex_hash}}},
                                      {"fragment", {{"hash", verdict.fragment_hash}}}}},
                                    {"diagnostics", DiagnosticsJson(verdict.diagnostics)}};
            entry.update(StepsJson(verdict));
            if (program != nullptr) {
                for (const auto& [stage, file, hash] :
                     {std::tuple{"vertex", program->vertex_path, verdict.vertex_hash},
                      std::tuple{"fragment", program->fragment_path, verdict.fragment_hash}}) {
                    entry["stages"][stage]["file"] = file;
                    auto it = by_hash.find(std::string(file).append("|").append(hash));
                    if (it != by_hash.end()) {
                        entry["stages"][stage]["cost"] = ToJson(it->second->cost);
                    }
                }
            }
            variants.push_back(std::move(entry));
        }
    }
    manifest["variants"] = variants;

    // Counts per rule, not the combinations: their number grows with 2^features, while the
    // rules and their counts say all a reader needs (`expand --pruned` lists combinations).
    nlohmann::json pruned_by_rule = nlohmann::json::array();
    for (const RulePruneCount& p : expansion.pruned_by_rule) {
        pruned_by_rule.push_back({{"program", p.program},
                                  {"rule", p.rule},
                                  {"file", p.where.file},
                                  {"line", p.where.line},
                                  {"count", p.count}});
    }
    manifest["pruned_by_rule"] = pruned_by_rule;

    nlohmann::json counts = {{"variants", expansion.variants.size()},
                             {"pruned", expansion.pruned_total}};
    if (validation != nullptr) {
        nlohmann::json stage_programs = nlohmann::json::array();
        for (const StageProgram& program : validation->stage_programs) {
            stage_programs.push_back({{"stage", StageName(program.stage)},
                                      {"target", TargetName(program.target)},
                                      {"file", program.file},
                                      {"hash", program.hash},
                                      {"defines", program.defines},
                                      {"variants", program.variants},
                                      {"valid", program.valid},
                                      {"cost", ToJson(program.cost)}});
        }
        manifest["stage_programs"] = stage_programs;
        counts["stage_slots"] = validation->stage_slots;
        counts["stage_programs"] = validation->stage_programs.size();
        counts["shared_stage_slots"] = validation->SharedStageSlots();
        counts["links"] = validation->links;
        counts["invalid"] = validation->InvalidCount();
    }
    manifest["counts"] = counts;
    return manifest;
}

}  // namespace tidepool
