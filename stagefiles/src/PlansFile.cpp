#include "tidepool/stagefiles/PlansFile.h"

#include "tidepool/base/AtomicFile.h"

#include "FieldReader.h"

namespace tidepool::stagefiles {
namespace {

nlohmann::json ToJson(const PlanConfiguration& c) {
    return {{"id", c.id},
            {"variant", c.variant},
            {"passes", c.passes},
            {"pass_draw_calls", c.pass_draw_calls},
            {"pass_options",
             {{"reflection_size", c.pass_options.reflection_size},
              {"low_res_water", c.pass_options.low_res_water}}},
            {"draw_calls", c.draw_calls},
            {"image", c.image},
            {"pixels_shaded_estimate", c.pixels_shaded_estimate}};
}

nlohmann::json ToJson(const PlanImageError& e) {
    return {{"psnr_db", e.psnr_db}, {"ssim", e.ssim}, {"share_visible", e.share_visible}};
}

nlohmann::json ToJson(const PlanEffect& e) {
    return {{"effect", e.effect},
            {"reason", e.reason},
            {"psnr_change_db", e.psnr_change_db},
            {"time_change_percent", e.time_change_percent}};
}

nlohmann::json ToJson(const std::vector<PlanEffect>& effects) {
    nlohmann::json list = nlohmann::json::array();
    for (const PlanEffect& e : effects) {
        list.push_back(ToJson(e));
    }
    return list;
}

// A candidate is one flat object: its configuration's fields beside what was measured.
nlohmann::json ToJson(const PlanCandidate& c) {
    nlohmann::json j = ToJson(c.configuration);
    j["proposed_because"] = c.proposed_because;
    if (c.water_colour_alpha) {
        j["water_colour_alpha"] = *c.water_colour_alpha;
    }
    j["valid"] = c.valid;
    if (c.valid) {
        j.update(ToJson(c.measurement.error));
        j["time_ms"] = c.measurement.time_ms;
        j["time_change_percent"] = c.measurement.time_change_percent;
        j["time_change_interval"] = c.measurement.time_change_interval;
        j["pairs"] = c.measurement.pairs;
        j["meets_quality"] = c.measurement.meets_quality;
    } else {
        j["diagnostics"] = c.diagnostics;
    }
    return j;
}

nlohmann::json ToJson(const PlanTarget& t) {
    nlohmann::json target = nlohmann::json::object();
    for (const auto& [key, bound] : {std::pair{"min_psnr_db", &t.min_psnr_db},
                                     std::pair{"max_share_visible", &t.max_share_visible},
                                     std::pair{"frame_budget_ms", &t.frame_budget_ms}}) {
        if (*bound) {
            target[key] = **bound;
        }
    }
    return target;
}

}  // namespace

// The readers, one per type; FieldReader::Value finds them by ADL.
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlanPassOptions* out) {
    r.Field(o, path, "reflection_size", &out->reflection_size);
    r.Field(o, path, "low_res_water", &out->low_res_water);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlanConfiguration* out) {
    r.Field(o, path, "id", &out->id);
    r.Field(o, path, "variant", &out->variant);
    r.Field(o, path, "passes", &out->passes);
    r.Field(o, path, "pass_draw_calls", &out->pass_draw_calls);
    r.Field(o, path, "pass_options", &out->pass_options);
    r.Field(o, path, "draw_calls", &out->draw_calls);
    r.Field(o, path, "image", &out->image);
    r.Field(o, path, "pixels_shaded_estimate", &out->pixels_shaded_estimate);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlanImageError* out) {
    r.Field(o, path, "psnr_db", &out->psnr_db);
    r.Field(o, path, "ssim", &out->ssim);
    r.Field(o, path, "share_visible", &out->share_visible);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlanCandidate* out) {
    ReadFields(r, o, path, &out->configuration);
    r.Field(o, path, "proposed_because", &out->proposed_because);
    r.Field(o, path, "water_colour_alpha", &out->water_colour_alpha);
    r.Field(o, path, "valid", &out->valid);
    PlanMeasurement& m = out->measurement;
    ReadFields(r, o, path, &m.error);
    r.Field(o, path, "time_ms", &m.time_ms);
    r.Field(o, path, "time_change_percent", &m.time_change_percent);
    r.Field(o, path, "time_change_interval", &m.time_change_interval);
    r.Field(o, path, "pairs", &m.pairs);
    r.Field(o, path, "meets_quality", &m.meets_quality);
    r.Field(o, path, "diagnostics", &out->diagnostics);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path, PlanEffect* out) {
    r.Field(o, path, "effect", &out->effect);
    r.Field(o, path, "reason", &out->reason);
    r.Field(o, path, "psnr_change_db", &out->psnr_change_db);
    r.Field(o, path, "time_change_percent", &out->time_change_percent);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path, PlanTarget* out) {
    r.Field(o, path, "frame_budget_ms", &out->frame_budget_ms);
    r.Field(o, path, "max_share_visible", &out->max_share_visible);
    r.Field(o, path, "min_psnr_db", &out->min_psnr_db);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path, PlanChoice* out) {
    r.Field(o, path, "chosen", &out->chosen);
    r.Field(o, path, "full", &out->full);
    r.Field(o, path, "time_ms_chosen", &out->time_ms_chosen);
    r.Field(o, path, "time_ms_full", &out->time_ms_full);
    r.Field(o, path, "time_change_percent", &out->time_change_percent);
    r.Field(o, path, "time_change_interval", &out->time_change_interval);
    r.Field(o, path, "choice_reason", &out->choice_reason);
    r.Field(o, path, "error", &out->error);
    r.Field(o, path, "dropped", &out->dropped);
    r.Field(o, path, "kept", &out->kept);
    r.Field(o, path, "passes_saved", &out->passes_saved);
    r.Field(o, path, "draws_saved", &out->draws_saved);
    r.Field(o, path, "pixels_saved", &out->pixels_saved);
    r.Field(o, path, "candidates", &out->candidates);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlannedScene* out) {
    r.Required(o, path, "scene", &out->scene);
    r.Field(o, path, "description", &out->description);
    r.Field(o, path, "target", &out->target);
    r.Field(o, path, "needed", &out->needed);
    r.Field(o, path, "errors", &out->errors);
    r.Field(o, path, "met", &out->met);
    // A plan that failed was written without a choice: its fields are all absent together.
    if (o.contains("chosen")) {
        out->choice.emplace();
        ReadFields(r, o, path, &*out->choice);
    }
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PlansTiming* out) {
    r.Field(o, path, "resolution_points", &out->resolution_points);
    r.Field(o, path, "min_pairs", &out->min_pairs);
    r.Field(o, path, "max_pairs", &out->max_pairs);
    r.Field(o, path, "missed_target_pairs", &out->missed_target_pairs);
    r.Field(o, path, "contended_share", &out->contended_share);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path, PlansFile* out) {
    r.Field(o, path, "size", &out->size);
    r.Field(o, path, "timing", &out->timing);
    r.Required(o, path, "plans", &out->plans);
}

nlohmann::json ToJson(const PlannedScene& plan) {
    nlohmann::json p;
    p["scene"] = plan.scene;
    p["description"] = plan.description;
    p["target"] = ToJson(plan.target);
    p["needed"] = plan.needed;
    p["errors"] = plan.errors;
    p["met"] = plan.met;
    if (!plan.choice) {
        return p;
    }
    const PlanChoice& c = *plan.choice;
    p["chosen"] = ToJson(c.chosen);
    p["full"] = ToJson(c.full);
    p["time_ms_chosen"] = c.time_ms_chosen;
    p["time_ms_full"] = c.time_ms_full;
    p["time_change_percent"] = c.time_change_percent;
    p["time_change_interval"] = c.time_change_interval;
    p["choice_reason"] = c.choice_reason;
    p["error"] = ToJson(c.error);
    p["dropped"] = ToJson(c.dropped);
    p["kept"] = ToJson(c.kept);
    p["passes_saved"] = c.passes_saved;
    p["draws_saved"] = c.draws_saved;
    p["pixels_saved"] = c.pixels_saved;
    nlohmann::json candidates = nlohmann::json::array();
    for (const PlanCandidate& candidate : c.candidates) {
        candidates.push_back(ToJson(candidate));
    }
    p["candidates"] = candidates;
    return p;
}

nlohmann::json ToJson(const PlansFile& file) {
    nlohmann::json out;
    out["schema"] = kPlansSchemaName;
    out[kVersionKey] = kPlansVersion;
    out["size"] = file.size;
    out["timing"] = {{"resolution_points", file.timing.resolution_points},
                     {"min_pairs", file.timing.min_pairs},
                     {"max_pairs", file.timing.max_pairs},
                     {"missed_target_pairs", file.timing.missed_target_pairs},
                     {"contended_share", file.timing.contended_share}};
    out["plans"] = nlohmann::json::array();
    for (const PlannedScene& plan : file.plans) {
        out["plans"].push_back(ToJson(plan));
    }
    return out;
}

ReadResult<PlansFile> PlansFileFromJson(const nlohmann::json& document,
                                        const std::string& file_name) {
    return ReadStageDocument<PlansFile>(document, file_name, kPlansSchemaName, kPlansVersion);
}

ReadResult<PlansFile> ReadPlansFile(const std::filesystem::path& path) {
    return ReadStageFile<PlansFile>(path, kPlansSchemaName, kPlansVersion);
}

std::string WritePlansFile(const PlansFile& file, const std::filesystem::path& path) {
    return base::WriteFileAtomically(path, JsonText(ToJson(file), 2) + "\n");
}

}  // namespace tidepool::stagefiles
