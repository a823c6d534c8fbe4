// The stages that need only the compiler: expand a matrix (and write its driver-ready sources),
// validate it or plain shader files with glslang (and write the manifest), and measure each
// variant's static cost. No GL.
#pragma once

#include "tidepool/DeviceLimits.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/StaticCost.h"
#include "tidepool/pipeline/MatrixLoading.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/pipeline/ValidationCache.h"

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::pipeline {

/// What `expand` is asked to do.
struct ExpandOptions {
    std::string config = "variants.yaml";
    MatrixLimits limits;
    std::string program;  // only this program of the configuration; "" for all
    std::string out;      // folder for the driver-ready sources and manifest.json; "" for none
    std::string depfile;  // with `out`: a depfile naming every file read; "" for none
};

/// What `expand` found and wrote: the matrix (its outcome also holds any write error) and the
/// manifest without verdicts.
struct ExpandResult {
    LoadedMatrix matrix;
    nlohmann::json manifest;
};

/// Loads and expands the matrix; with `out`, publishes every variant's stage sources as a GL
/// driver receives them (`out`/<target>/<program>/<variant>.vert|.frag) and the manifest,
/// replacing the folder whole. Stops (the matrix kept when it loaded) when loading fails
/// (kUsage), the folder is someone else's (kUsage) or a write fails (kEnvironment).
ExpandResult Expand(const ExpandOptions& options);

/// What `validate` is asked to do with a configuration.
struct ValidateOptions {
    std::string config = "variants.yaml";
    MatrixLimits limits;
    std::string program;               // only this program; "" for all
    std::string device_limits;         // --limits FILE; "" for none
    std::optional<GlslTarget> target;  // instead of the file's targets
    int jobs = 0;                      // 0: one per core
    CacheChoice cache;
    std::string out;               // folder for manifest.json; "" for none
    bool sources = false;          // with `out`: driver-ready sources too
    std::string depfile;           // with `out`: a depfile; "" for none
    bool manifest_wanted = false;  // build the manifest even without `out` (to print it)
    std::string report_file;       // where the caller will write the report; checked only
};

/// What `validate` found: the matrix, glslang's report, and the manifest (built when written or
/// wanted, else null). The outcome is kInvalid when a variant or the validation has errors.
struct ValidateResult {
    LoadedMatrix matrix;
    ValidationReport report;
    nlohmann::json manifest;
    /// Every file whose bytes decided the result: the configuration, the shaders of all its
    /// programs (before --program narrows them: the loader checked each) and the --limits file.
    std::vector<std::filesystem::path> files_read;
    std::optional<std::string> manifest_text;  // manifest.json as written to `out`
    std::optional<std::string> depfile_text;   // the depfile as written
    /// The result and what was written follow from the options and `files_read` alone, and a
    /// RunRecord can hold them: the run ended normally (valid or invalid), glslang gave every
    /// verdict (no internal compiler error, which a timeout under load may cause), the cache
    /// (whose failure adds a warning) worked, and no sources were written.
    bool repeatable = false;
};

/// Loads, expands and validates every variant with glslang (each distinct stage program once,
/// every pair linked); with `out`, writes manifest.json there (refused before any validation when
/// it is not tidepool's). Stops when the matrix does not load, the device limits cannot be read
/// or the program is unknown (kUsage), or a write fails (kEnvironment).
ValidateResult ValidateMatrix(const ValidateOptions& options);

/// What `validate FILE...` is asked to do.
struct ValidateFilesOptions {
    std::vector<std::string> files;
    std::string stage;                 // vert, vertex, frag, fragment; "" from the extension
    std::vector<std::string> defines;  // NAME or NAME=VALUE
    std::string device_limits;         // --limits FILE; "" for none
    std::optional<GlslTarget> target;  // WebGL rules on top of GLSL ES
    CacheChoice cache;
    std::string report_file;  // where the caller will write the report; checked only
};

/// What `validate FILE...` found; the outcome is kInvalid when a file has errors.
struct ValidateFilesResult {
    Outcome outcome;
    ValidationReport report;
};

/// Validates plain shader files with glslang (a vertex and a fragment file given together are
/// linked). Stops with kUsage when a file's stage cannot be told or the file cannot be read, or
/// the device limits cannot be read.
ValidateFilesResult ValidateFiles(const ValidateFilesOptions& options);

/// What `stats` is asked to do.
struct StatsOptions {
    std::string config = "variants.yaml";
    MatrixLimits limits;
    int jobs = 0;  // 0: one per core
};

/// One valid variant's static cost.
struct VariantCost {
    std::string id;
    StageCost vertex;
    StageCost fragment;
};

/// What `stats` found: every valid variant's cost, in the order of the variants; the invalid
/// ones' diagnostics are in the outcome, which is then kInvalid.
struct StatsResult {
    LoadedMatrix matrix;
    std::vector<VariantCost> costs;
};

/// Loads, expands and validates (GLSL ES 1.00) the matrix and reads each variant's static cost
/// from glslang's tree. Stops with kUsage when the matrix does not load.
StatsResult MeasureStaticCosts(const StatsOptions& options);

}  // namespace tidepool::pipeline
