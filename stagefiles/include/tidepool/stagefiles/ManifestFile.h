// manifest.json (schema "tidepool.manifest", version 1, README.md "The manifest"): every variant
// of the matrix with its defines and, after a validation, its verdict, stage hashes, diagnostics
// and static cost. Written by `tidepool expand` and `tidepool validate` (compiler/Manifest.h
// builds it), read by the report.
#pragma once

#include "tidepool/stagefiles/StageFile.h"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::stagefiles {

class FieldReader;

inline constexpr std::string_view kManifestSchemaName = "tidepool.manifest";
inline constexpr int kManifestVersion = 1;

/// A diagnostic as a stage file holds it (tidepool/Diagnostic.h's fields); results.json adds
/// its GCC-form `text`.
struct DiagnosticEntry {
    std::string severity;
    std::string file;
    int line = 0;
    int column = 0;
    std::string message;
    std::string variant;
    std::optional<std::string> text;  // results.json only

    bool operator==(const DiagnosticEntry&) const = default;
};

/// A configuration's pass options (manifest presets, results configurations). The defaults are
/// what a file written before a field existed meant.
struct PassOptionsEntry {
    int reflection_size = 256;
    std::optional<int> refraction_size;  // absent: the reflection's size (older files)
    bool low_res_water = false;
    bool depth_fog = true;
    std::string clip = "oblique";
    bool culling = true;

    bool operator==(const PassOptionsEntry&) const = default;
};

/// A stage's static cost (compiler/StaticCost.h), with its total.
struct StageCostEntry {
    int arithmetic_ops = 0;
    int texture_samples = 0;
    std::map<std::string, int, std::less<>> builtin_calls;
    int branches = 0;
    int loops = 0;
    int uniforms = 0;
    int varyings = 0;
    int samplers = 0;
    int shortest_path_ops = 0;
    int longest_path_ops = 0;
    int total_ops = 0;

    bool operator==(const StageCostEntry&) const = default;
};

/// A program of the matrix.
struct ManifestProgram {
    std::string name;
    std::string vertex;
    std::string fragment;
    std::vector<std::string> defines;

    bool operator==(const ManifestProgram&) const = default;
};

/// A preset of the matrix.
struct ManifestPreset {
    std::string name;
    std::string description;
    std::string variant;
    std::vector<std::string> runtime_features;
    PassOptionsEntry passes;

    bool operator==(const ManifestPreset&) const = default;
};

/// One stage of a validated variant.
struct ManifestStage {
    std::string hash;
    std::optional<std::string> file;     // absent when the program is not in the config
    std::optional<StageCostEntry> cost;  // absent when no stage program matched

    bool operator==(const ManifestStage&) const = default;
};

/// Both stages of a validated variant.
struct ManifestStages {
    ManifestStage vertex;
    ManifestStage fragment;

    bool operator==(const ManifestStages&) const = default;
};

/// The driver-ready sources `validate --sources` wrote for a variant.
struct ManifestSources {
    std::string vertex;
    std::string fragment;

    bool operator==(const ManifestSources&) const = default;
};

/// One variant; the verdict fields are absent when nothing was validated (`tidepool expand`).
struct ManifestVariant {
    std::string id;       // required, non-empty
    std::string program;  // required, non-empty
    std::vector<std::string> defines;
    std::optional<std::string> target;
    std::optional<bool> valid;
    std::optional<ManifestStages> stages;
    std::optional<std::vector<DiagnosticEntry>> diagnostics;
    std::optional<std::map<std::string, std::string, std::less<>>> steps;  // "valid", ...
    std::optional<std::vector<std::string>> failed_steps;
    std::optional<ManifestSources> sources;

    bool operator==(const ManifestVariant&) const = default;
};

/// How many combinations one rule pruned.
struct ManifestPrunedRule {
    std::string program;
    std::string rule;
    std::string file;
    int line = 0;
    long long count = 0;

    bool operator==(const ManifestPrunedRule&) const = default;
};

/// One pruned combination, as manifests listed them before `pruned_by_rule` (read only).
struct ManifestPrunedCombination {
    std::string id;
    std::string program;
    std::string rule;
    std::string file;
    int line = 0;

    bool operator==(const ManifestPrunedCombination&) const = default;
};

/// A distinct stage program and the variants that share it.
struct ManifestStageProgram {
    std::string stage;
    std::string target;
    std::string file;
    std::string hash;
    std::vector<std::string> defines;
    std::vector<std::string> variants;
    bool valid = false;
    StageCostEntry cost;

    bool operator==(const ManifestStageProgram&) const = default;
};

/// The matrix's counts; the validation's are absent after `tidepool expand`.
struct ManifestCounts {
    long long variants = 0;
    long long pruned = 0;
    std::optional<long long> stage_slots;
    std::optional<long long> stage_programs;
    std::optional<long long> shared_stage_slots;
    std::optional<long long> links;
    std::optional<long long> invalid;

    bool operator==(const ManifestCounts&) const = default;
};

/// Everything manifest.json holds.
struct ManifestFile {
    std::string config;
    std::vector<std::string> targets;
    std::vector<ManifestProgram> programs;
    std::vector<ManifestPreset> presets;
    std::vector<ManifestVariant> variants;  // required
    std::optional<std::vector<ManifestPrunedRule>> pruned_by_rule;
    std::vector<ManifestPrunedCombination> pruned;  // older manifests only; never written
    std::optional<std::vector<ManifestStageProgram>> stage_programs;  // after a validation
    ManifestCounts counts;                                            // required

    bool operator==(const ManifestFile&) const = default;
};

/// The JSON of each part, as the manifest (and results.json, for the shared ones) holds it.
/// Never fail.
nlohmann::json ToJson(const DiagnosticEntry& diagnostic);
nlohmann::json ToJson(const PassOptionsEntry& passes);
nlohmann::json ToJson(const StageCostEntry& cost);
nlohmann::json ToJson(const ManifestCounts& counts);
nlohmann::json ToJson(const ManifestFile& file);

/// The readers of the parts results.json shares (FieldReader::Value finds them by ADL).
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                DiagnosticEntry* out);
void ReadFields(FieldReader& r, const nlohmann::json& o, const std::string& path,
                PassOptionsEntry* out);

/// Reads `document` as manifest.json, naming `file_name` in the error. Fails as
/// ReadManifestFile.
ReadResult<ManifestFile> ManifestFileFromJson(const nlohmann::json& document,
                                              const std::string& file_name);
/// Reads manifest.json at `path`: kUnreadable, kForeign (another schema or version),
/// kMissingField ('variants', 'counts', or a variant's 'id' or 'program' absent or empty) or
/// kWrongType, with an error naming the file and the field.
ReadResult<ManifestFile> ReadManifestFile(const std::filesystem::path& path);
/// `file` as the text of manifest.json: two-space indented with a final newline. Never fails.
std::string ManifestFileText(const ManifestFile& file);

}  // namespace tidepool::stagefiles
