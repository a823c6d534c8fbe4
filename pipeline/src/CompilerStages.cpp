#include "tidepool/pipeline/CompilerStages.h"

#include "tidepool/Manifest.h"
#include "tidepool/TextFile.h"
#include "tidepool/pipeline/BuildOutputs.h"
#include "tidepool/pipeline/Host.h"
#include "tidepool/pipeline/OutputFiles.h"

#include <map>
#include <memory>
#include <utility>

namespace tidepool::pipeline {
namespace {

// The device limits `path` names, read into `limits`, their diagnostics into `outcome`; false
// (kUsage) when they cannot be used. No path: true, and `limits` stays empty.
bool LoadDeviceLimits(const std::string& path, std::optional<DeviceLimits>* limits,
                      Outcome* outcome) {
    if (path.empty()) {
        return true;
    }
    DeviceLimitsRead read = ReadDeviceLimits(path);
    outcome->Add(read.diagnostics);
    if (!read.ok) {
        outcome->status = Status::kUsage;
        return false;
    }
    *limits = std::move(read.limits);
    return true;
}

// Loads and expands `config`, narrowed to `program` when one is named; `files_read`, when given,
// receives the files the loader read or checked (FilesRead before the narrowing).
LoadedMatrix LoadProgram(const std::string& config, const MatrixLimits& limits,
                         const std::string& program,
                         std::vector<std::filesystem::path>* files_read = nullptr) {
    LoadedMatrix loaded = LoadMatrix(config, limits);
    if (loaded.config && files_read != nullptr) {
        *files_read = FilesRead(*loaded.config);
    }
    if (loaded.config && !program.empty()) {
        KeepOnlyProgram(&loaded, program);
    }
    return loaded;
}

// `diagnostics` about a configuration's shaders, each file named as the file system finds it from
// the working directory (a program names its shaders relative to the configuration's folder),
// so that a terminal, an IDE or a build log opens it. The manifest and SARIF keep their own.
std::vector<Diagnostic> SeenFromHere(const VariantConfig& config,
                                     std::vector<Diagnostic> diagnostics) {
    for (Diagnostic& d : diagnostics) {
        if (!d.file.empty()) {
            d.file = config.Resolve(d.file).lexically_normal().string();
        }
    }
    return diagnostics;
}

// Appends the cache's warning, if any, to `outcome`.
void WarnAboutCache(const base::ContentCache* cache, Outcome* outcome) {
    if (const std::optional<Diagnostic> warning = CacheWarning(cache)) {
        outcome->diagnostics.push_back(*warning);
    }
}

}  // namespace

ExpandResult Expand(const ExpandOptions& options) {
    ExpandResult result;
    result.matrix = LoadProgram(options.config, options.limits, options.program);
    if (!result.matrix.config) {
        return result;
    }
    const VariantConfig& config = *result.matrix.config;
    const ExpansionResult& expansion = result.matrix.expansion;
    result.manifest = BuildManifest(config, expansion, nullptr);
    if (options.out.empty()) {
        return result;
    }
    Outcome& outcome = result.matrix.outcome;
    const std::filesystem::path manifest_path =
            std::filesystem::path(options.out) / "manifest.json";
    const std::vector<std::filesystem::path> files_read = FilesRead(config);
    // The manifest is planned with the depfile, so that a depfile on the manifest or on the
    // --out folder is refused before any work, as validate refuses it (it replaced the manifest
    // it had just written and exited 0).
    std::vector<PlannedOutput> outputs{{"--out", manifest_path}};
    if (!options.depfile.empty()) {
        outputs.push_back({"--depfile", options.depfile});
    }
    if (!CheckPlannedOutputs(outputs, files_read, &outcome) ||
        (!options.depfile.empty() && !CheckDepfileNames(manifest_path, files_read, &outcome)) ||
        !CheckVariantFileNames(config, expansion.variants, &outcome)) {
        return result;
    }
    // Everything goes to a private staging folder, removed by the publisher unless published.
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(options.out, "tidepool expand", &outcome);
    if (!publisher ||
        !WriteVariantSources(config, expansion.variants, publisher->Staging(), &outcome) ||
        !WriteFile(publisher->Staging() / "manifest.json", JsonText(result.manifest, 2) + "\n",
                   &outcome) ||
        !Publish(*publisher, &outcome)) {
        return result;
    }
    if (!options.depfile.empty()) {
        WriteDepfile(options.depfile, manifest_path, files_read, &outcome);
    }
    return result;
}

ValidateResult ValidateMatrix(const ValidateOptions& options) {
    ValidateResult result;
    // A cache that holds nothing (or none) answers nothing, so glslang will run: its tables for
    // GLSL ES 1.00, which every configuration targets, are built while the configuration loads.
    const std::unique_ptr<base::ContentCache> cache = OpenValidationCache(options.cache);
    std::optional<GlslangWarmUp> warm_up;
    if (cache == nullptr || cache->Empty()) {
        warm_up.emplace(std::vector<GlslTarget>{GlslTarget::kEs100});
    }
    result.matrix =
            LoadProgram(options.config, options.limits, options.program, &result.files_read);
    Outcome& outcome = result.matrix.outcome;
    std::optional<DeviceLimits> device_limits;
    if (!result.matrix.config ||
        !LoadDeviceLimits(options.device_limits, &device_limits, &outcome)) {
        return result;
    }
    if (!options.device_limits.empty()) {
        result.files_read.push_back(std::filesystem::absolute(options.device_limits));
    }
    if (options.target) {
        result.matrix.config->targets = {*options.target};  // instead of the file's `targets`
    }
    const VariantConfig& config = *result.matrix.config;
    const std::vector<Variant>& variants = result.matrix.expansion.variants;
    // Refused before the validation's work, not after it.
    const std::filesystem::path manifest_path =
            std::filesystem::path(options.out) / "manifest.json";
    std::vector<PlannedOutput> outputs;
    if (!options.out.empty()) {
        outputs.push_back({"--out", manifest_path});
        if (!options.depfile.empty()) {
            outputs.push_back({"--depfile", options.depfile});
        }
    }
    if (!options.report_file.empty()) {
        outputs.push_back({"--output-file", options.report_file});
    }
    // The depfile names what the narrowed configuration reads (another program's shaders do
    // not change this one's outputs) and the --limits file.
    std::vector<std::filesystem::path> dependencies = FilesRead(config);
    if (!options.device_limits.empty()) {
        dependencies.push_back(result.files_read.back());
    }
    if (!CheckPlannedOutputs(outputs, result.files_read, &outcome) ||
        (!options.out.empty() && !options.depfile.empty() &&
         !CheckDepfileNames(manifest_path, dependencies, &outcome)) ||
        (!options.out.empty() && options.sources &&
         !CheckVariantFileNames(config, variants, &outcome))) {
        return result;
    }
    if (!options.out.empty()) {
        if (Outcome check = WriteManifest(options.out, "", true); check.Stopped()) {
            outcome.Add(check.diagnostics);
            outcome.status = check.status;
            return result;
        }
    }
    ValidationOptions validation_options;
    validation_options.jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
    validation_options.targets = config.targets;
    validation_options.limits = device_limits ? &*device_limits : nullptr;
    validation_options.cache = cache.get();
    validation_options.warm_up = warm_up ? &*warm_up : nullptr;
    // The costs appear only in the manifest.
    validation_options.static_costs = options.manifest_wanted || !options.out.empty();
    result.report = ValidateVariants(config, variants, validation_options);
    WarnAboutCache(cache.get(), &outcome);
    outcome.Add(SeenFromHere(config, result.report.diagnostics));
    for (const VariantVerdict& verdict : result.report.verdicts) {
        outcome.Add(SeenFromHere(config, verdict.diagnostics));
    }
    // Built only when printed or written: it costs as much as a validation the cache answers.
    if (options.manifest_wanted || !options.out.empty()) {
        stagefiles::ManifestFile manifest =
                BuildManifestFile(config, result.matrix.expansion, &result.report);
        if (!options.out.empty() && options.sources) {
            if (!WriteVariantSources(config, variants, options.out, &outcome)) {
                return result;
            }
            AddSourcePaths(variants, &manifest);
        }
        result.manifest = stagefiles::ToJson(manifest);
    }
    if (!options.out.empty()) {
        result.manifest_text = JsonText(result.manifest, 2) + "\n";
        if (Outcome write = WriteManifest(options.out, *result.manifest_text); write.Stopped()) {
            outcome.Add(write.diagnostics);
            outcome.status = write.status;
            return result;
        }
        if (!options.depfile.empty() && !WriteDepfile(options.depfile, manifest_path, dependencies,
                                                      &outcome, &result.depfile_text.emplace())) {
            return result;
        }
    }
    const bool valid = result.report.InvalidCount() == 0 && !HasErrors(result.report.diagnostics);
    outcome.status = valid ? Status::kOk : Status::kInvalid;
    // Not with --sources: a record holds the manifest and the depfile, not the variants' sources.
    result.repeatable = !options.sources && !result.report.internal_errors &&
                        (cache == nullptr || cache->Stats().error.empty());
    return result;
}

ValidateFilesResult ValidateFiles(const ValidateFilesOptions& options) {
    ValidateFilesResult result;
    Outcome& outcome = result.outcome;
    std::vector<ShaderFile> files;
    for (const std::string& path : options.files) {
        ShaderFile file{path, Stage::kVertex};
        if (options.stage == "vert" || options.stage == "vertex") {
            file.stage = Stage::kVertex;
        } else if (options.stage == "frag" || options.stage == "fragment") {
            file.stage = Stage::kFragment;
        } else if (!StageFromExtension(path, &file.stage)) {
            outcome.diagnostics.push_back(
                    MakeError(path, 0, 0,
                              "cannot tell the stage from the extension; use .vert/.vsh, "
                              ".frag/.fsh or --stage vert|frag"));
            outcome.status = Status::kUsage;
            return result;
        }
        if (const TextFileRead read = ReadShaderFile(path); !read.ok) {
            outcome.diagnostics.push_back(
                    MakeError(path, 0, 0, "cannot read the shader file: " + read.error));
            outcome.status = Status::kUsage;
            return result;
        }
        files.push_back(file);
    }
    std::optional<DeviceLimits> limits;
    if (!LoadDeviceLimits(options.device_limits, &limits, &outcome)) {
        return result;
    }
    if (!options.report_file.empty()) {
        std::vector<std::filesystem::path> inputs(options.files.begin(), options.files.end());
        if (!options.device_limits.empty()) {
            inputs.emplace_back(options.device_limits);
        }
        if (!CheckPlannedOutputs({{"--output-file", options.report_file}}, inputs, &outcome)) {
            return result;
        }
    }
    ShaderFileOptions file_options;
    file_options.target = options.target;
    file_options.limits = limits ? &*limits : nullptr;
    const std::unique_ptr<base::ContentCache> cache = OpenValidationCache(options.cache);
    file_options.cache = cache.get();
    result.report = ValidateShaderFiles(files, options.defines, file_options);
    WarnAboutCache(cache.get(), &outcome);
    for (const VariantVerdict& verdict : result.report.verdicts) {
        outcome.Add(verdict.diagnostics);
    }
    outcome.status = result.report.InvalidCount() == 0 ? Status::kOk : Status::kInvalid;
    return result;
}

StatsResult MeasureStaticCosts(const StatsOptions& options) {
    StatsResult result;
    result.matrix = LoadMatrix(options.config, options.limits);
    if (!result.matrix.config) {
        return result;
    }
    const VariantConfig& config = *result.matrix.config;
    ValidationOptions validation_options;
    validation_options.jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
    validation_options.targets = {GlslTarget::kEs100};
    const ValidationReport report =
            ValidateVariants(config, result.matrix.expansion.variants, validation_options);
    std::map<std::string, const StageProgram*> programs;
    for (const StageProgram& program : report.stage_programs) {
        programs[program.file + "|" + program.hash] = &program;
    }
    Outcome& outcome = result.matrix.outcome;
    for (const VariantVerdict& verdict : report.verdicts) {
        const ProgramConfig* program = config.FindProgram(verdict.variant.program);
        const StageProgram* vs = programs[program->vertex_path + "|" + verdict.vertex_hash];
        const StageProgram* fs = programs[program->fragment_path + "|" + verdict.fragment_hash];
        if (!verdict.valid || vs == nullptr || fs == nullptr) {
            outcome.Add(SeenFromHere(config, verdict.diagnostics));
            outcome.status = Status::kInvalid;
            continue;
        }
        result.costs.push_back({verdict.variant.Id(), vs->cost, fs->cost});
    }
    return result;
}

}  // namespace tidepool::pipeline
