#include "tidepool/stagefiles/StabilityFile.h"

#include "FieldReader.h"

namespace tidepool::stagefiles {

// The readers, one per type; FieldReader::Value finds them by ADL.
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                StabilityCase* out) {
    r.Field(o, path, "name", &out->name);
    r.Field(o, path, "description", &out->description);
    r.Field(o, path, "kind", &out->kind);
    r.Field(o, path, "variants_checked", &out->variants_checked);
    r.Field(o, path, "nan_count", &out->nan_count);
    r.Field(o, path, "inf_count", &out->inf_count);
    r.Field(o, path, "max_error", &out->max_error);
    r.Field(o, path, "bound", &out->bound);
    r.Field(o, path, "passed", &out->passed);
    r.Field(o, path, "fix", &out->fix);
    r.Field(o, path, "note", &out->note);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PrecisionEntry* out) {
    r.Field(o, path, "expression", &out->expression);
    r.Field(o, path, "max_abs_error_float", &out->max_abs_error_float);
    r.Field(o, path, "max_abs_error_fp16", &out->max_abs_error_fp16);
    r.Field(o, path, "max_rel_error_fp16", &out->max_rel_error_fp16);
    r.Field(o, path, "bound_fp16", &out->bound_fp16);
    r.Field(o, path, "non_finite_fp16", &out->non_finite_fp16);
    r.Field(o, path, "loses_precision", &out->loses_precision);
    r.Field(o, path, "note", &out->note);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path, GuardEntry* out) {
    r.Field(o, path, "guard", &out->guard);
    r.Field(o, path, "max_channel_diff_normal_views", &out->max_channel_diff_normal_views);
    r.Field(o, path, "tolerance", &out->tolerance);
    r.Field(o, path, "passed", &out->passed);
}

void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                StabilityFile* out) {
    r.Field(o, path, "environment", &out->environment);
    r.Field(o, path, "cases", &out->cases);
    r.Field(o, path, "precision", &out->precision);
    r.Field(o, path, "guards", &out->guards);
}

nlohmann::json ToJson(const StabilityFile& file) {
    nlohmann::json json;
    json["schema"] = kStabilitySchemaName;
    json[kVersionKey] = kStabilityVersion;
    nlohmann::json environment = nlohmann::json::object();
    for (const auto& [key, value] : file.environment) {
        environment[key] = value;
    }
    json["environment"] = environment;
    nlohmann::json cases = nlohmann::json::array();
    for (const StabilityCase& c : file.cases) {
        cases.push_back({{"name", c.name},
                         {"description", c.description},
                         {"kind", c.kind},
                         {"variants_checked", c.variants_checked},
                         {"nan_count", c.nan_count},
                         {"inf_count", c.inf_count},
                         {"max_error", c.max_error},
                         {"bound", c.bound},
                         {"passed", c.passed},
                         {"fix", c.fix},
                         {"note", c.note}});
    }
    json["cases"] = cases;
    nlohmann::json precision = nlohmann::json::array();
    for (const PrecisionEntry& p : file.precision) {
        precision.push_back({{"expression", p.expression},
                             {"max_abs_error_float", p.max_abs_error_float},
                             {"max_abs_error_fp16", p.max_abs_error_fp16},
                             {"max_rel_error_fp16", p.max_rel_error_fp16},
                             {"bound_fp16", p.bound_fp16},
                             {"non_finite_fp16", p.non_finite_fp16},
                             {"loses_precision", p.loses_precision},
                             {"note", p.note}});
    }
    json["precision"] = precision;
    nlohmann::json guards = nlohmann::json::array();
    for (const GuardEntry& g : file.guards) {
        guards.push_back({{"guard", g.guard},
                          {"max_channel_diff_normal_views", g.max_channel_diff_normal_views},
                          {"tolerance", g.tolerance},
                          {"passed", g.passed}});
    }
    json["guards"] = guards;
    return json;
}

std::string StabilityFileText(const StabilityFile& file) {
    return JsonText(ToJson(file), 2) + "\n";
}

ReadResult<StabilityFile> StabilityFileFromJson(const nlohmann::json& document,
                                                const std::string& file_name) {
    return ReadStageDocument<StabilityFile>(document, file_name, kStabilitySchemaName,
                                            kStabilityVersion);
}

ReadResult<StabilityFile> ReadStabilityFile(const std::filesystem::path& path) {
    return ReadStageFile<StabilityFile>(path, kStabilitySchemaName, kStabilityVersion);
}

}  // namespace tidepool::stagefiles
