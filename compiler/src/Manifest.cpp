#include "tidepool/Manifest.h"

#include <map>

namespace tidepool {

stagefiles::DiagnosticEntry ToEntry(const Diagnostic& d) {
    return {SeverityName(d.severity), d.file, d.line, d.column, d.message, d.variant, {}};
}

nlohmann::json ToJson(const Diagnostic& diagnostic) {
    return stagefiles::ToJson(ToEntry(diagnostic));
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

stagefiles::StageCostEntry ToEntry(const StageCost& c) {
    stagefiles::StageCostEntry entry{c.arithmetic_ops,   c.texture_samples, {},
                                     c.branches,         c.loops,           c.uniforms,
                                     c.varyings,         c.samplers,        c.shortest_path_ops,
                                     c.longest_path_ops, c.TotalOps()};
    entry.builtin_calls.insert(c.builtin_calls.begin(), c.builtin_calls.end());
    return entry;
}

}  // namespace

stagefiles::ManifestFile BuildManifestFile(const VariantConfig& config,
                                           const ExpansionResult& expansion,
                                           const ValidationReport* validation) {
    stagefiles::ManifestFile manifest;
    manifest.config = config.path;
    for (GlslTarget target : config.targets) {
        manifest.targets.emplace_back(TargetName(target));
    }
    for (const ProgramConfig& program : config.programs) {
        manifest.programs.push_back(
                {program.name, program.vertex_path, program.fragment_path, program.AllDefines()});
    }
    for (const Preset& preset : config.presets) {
        manifest.presets.push_back({preset.name,
                                    preset.description,
                                    MakeVariant(preset.program, preset.defines).Id(),
                                    preset.runtime_features,
                                    {preset.passes.reflection_size, preset.passes.refraction_size,
                                     preset.passes.low_res_water, preset.passes.depth_fog,
                                     preset.passes.clip, preset.passes.culling}});
    }

    // Stage programs by (file, hash) so each verdict can carry its stages' static cost.
    std::map<std::string, const StageProgram*> by_hash;
    if (validation != nullptr) {
        for (const StageProgram& program : validation->stage_programs) {
            by_hash[program.file + "|" + program.hash] = &program;
        }
    }

    if (validation == nullptr) {
        for (const Variant& variant : expansion.variants) {
            stagefiles::ManifestVariant& entry = manifest.variants.emplace_back();
            entry.id = variant.Id();
            entry.program = variant.program;
            entry.defines = variant.defines;
        }
    } else {
        for (const VariantVerdict& verdict : validation->verdicts) {
            const ProgramConfig* program = config.FindProgram(verdict.variant.program);
            stagefiles::ManifestVariant entry;
            entry.id = verdict.variant.Id();
            entry.program = verdict.variant.program;
            entry.defines = verdict.variant.defines;
            entry.target = TargetName(verdict.target);
            entry.valid = verdict.valid;
            entry.stages.emplace();
            entry.stages->vertex.hash = verdict.vertex_hash;
            entry.stages->fragment.hash = verdict.fragment_hash;
            entry.diagnostics.emplace();
            for (const Diagnostic& d : verdict.diagnostics) {
                entry.diagnostics->push_back(ToEntry(d));
            }
            entry.steps.emplace();
            entry.failed_steps.emplace();
            for (const auto& [name, step] : verdict.NamedSteps()) {
                (*entry.steps)[name] = StepStatusName(step->status);
                if (step->status == StepStatus::kInvalid) {
                    entry.failed_steps->emplace_back(name);
                }
            }
            if (program != nullptr) {
                for (const auto& [stage, file, hash] :
                     {std::tuple{&entry.stages->vertex, program->vertex_path, verdict.vertex_hash},
                      std::tuple{&entry.stages->fragment, program->fragment_path,
                                 verdict.fragment_hash}}) {
                    stage->file = file;
                    auto it = by_hash.find(std::string(file).append("|").append(hash));
                    if (it != by_hash.end()) {
                        stage->cost = ToEntry(it->second->cost);
                    }
                }
            }
            manifest.variants.push_back(std::move(entry));
        }
    }

    // Counts per rule, not the combinations: their number grows with 2^features, while the
    // rules and their counts say all a reader needs (`expand --pruned` lists combinations).
    manifest.pruned_by_rule.emplace();
    for (const RulePruneCount& p : expansion.pruned_by_rule) {
        manifest.pruned_by_rule->push_back(
                {p.program, p.rule, p.where.file, p.where.line, static_cast<long long>(p.count)});
    }

    stagefiles::ManifestCounts& counts = manifest.counts;
    counts.variants = static_cast<long long>(expansion.variants.size());
    counts.pruned = static_cast<long long>(expansion.pruned_total);
    if (validation != nullptr) {
        manifest.stage_programs.emplace();
        for (const StageProgram& program : validation->stage_programs) {
            manifest.stage_programs->push_back({StageName(program.stage),
                                                TargetName(program.target), program.file,
                                                program.hash, program.defines, program.variants,
                                                program.valid, ToEntry(program.cost)});
        }
        counts.stage_slots = static_cast<long long>(validation->stage_slots);
        counts.stage_programs = static_cast<long long>(validation->stage_programs.size());
        counts.shared_stage_slots = static_cast<long long>(validation->SharedStageSlots());
        counts.links = static_cast<long long>(validation->links);
        counts.invalid = static_cast<long long>(validation->InvalidCount());
    }
    return manifest;
}

nlohmann::json BuildManifest(const VariantConfig& config, const ExpansionResult& expansion,
                             const ValidationReport* validation) {
    return stagefiles::ToJson(BuildManifestFile(config, expansion, validation));
}

}  // namespace tidepool
