// `tidepool expand`, `validate` and `stats`: flags → options → library calls → print → exit code.
#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/SarifLog.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/TextFile.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "BuildOutputs.h"
#include "CliSupport.h"
#include "Commands.h"
#include <fmt/format.h>
#include <unistd.h>

namespace tidepool::cli {
namespace {

struct CompilerOptions {
    std::string config = "variants.yaml";
    bool json = false;
    std::string out;
    MatrixLimits limits;
    bool pruned = false;                // expand: list pruned combinations
    std::string pruned_limit = "1000";  // expand: at most this many
    int jobs = 0;                       // 0: one per core
    std::vector<std::string> files;     // validate: plain shader files
    std::string stage;                  // validate: force the stage of plain files
    std::vector<std::string> defines;
    // For build systems and CI (BuildOutputs.h): one program's slice, a depfile beside --out,
    // validate's driver-ready sources, and validate's report format and file.
    std::string program;
    std::string depfile;
    bool sources = false;
    std::string format = "text";  // text, json (as --json) or sarif
    std::string output_file;      // where json or sarif goes instead of stdout
    CacheFlags cache;             // validate: --cache, --no-cache
    std::string device_limits;    // validate: --limits FILE
    std::string target;           // validate: --target webgl1|webgl2
};

// The device limits --limits names, read into `limits`; false (after printing the file's
// errors) when they cannot be used. No --limits: true, and `limits` stays empty.
bool LoadDeviceLimits(const CompilerOptions& options, std::optional<DeviceLimits>* limits) {
    if (options.device_limits.empty()) {
        return true;
    }
    DeviceLimitsRead read = ReadDeviceLimits(options.device_limits);
    PrintDiagnostics(read.diagnostics);
    if (!read.ok) {
        return false;
    }
    *limits = std::move(read.limits);
    return true;
}

// The target --target names, if any.
std::optional<GlslTarget> TargetOption(const CompilerOptions& options) {
    GlslTarget target = GlslTarget::kEs100;
    if (options.target.empty() || !TargetFromName(options.target, &target)) {
        return std::nullopt;
    }
    return target;
}

// Prints `text` (a JSON or SARIF report) on stdout, or writes it to --output-file atomically.
int EmitReport(const CompilerOptions& options, const std::string& text) {
    if (options.output_file.empty()) {
        std::printf("%s\n", text.c_str());
        return kExitOk;
    }
    if (const std::string error = base::WriteFileAtomically(options.output_file, text + "\n");
        !error.empty()) {
        std::fprintf(stderr, "error: --output-file: %s\n", error.c_str());
        return kExitEnvironment;
    }
    return kExitOk;
}

// With --depfile, the depfile of --out's manifest.json (see WriteDepfile).
int WriteDepfileIfAsked(const CompilerOptions& options, const VariantConfig& config) {
    if (options.depfile.empty()) {
        return kExitOk;
    }
    return WriteDepfile(options.depfile, std::filesystem::path(options.out) / "manifest.json",
                        config);
}

// The report format asked for: --json is --format json.
std::string ReportFormat(const CompilerOptions& options) {
    return options.json ? "json" : options.format;
}

int RunExpand(const CompilerOptions& options) {
    MatrixLimits limits = options.limits;
    if (options.pruned && !ParseCountOption("--pruned-limit", options.pruned_limit, 1,
                                            kVariantCeiling, "", &limits.pruned_limit)) {
        return kExitUsage;
    }
    LoadedMatrix loaded = LoadAndExpand(options.config, limits);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    if (!options.program.empty() && !KeepOnlyProgram(&loaded, options.program)) {
        return kExitUsage;
    }
    const VariantConfig& config = *loaded.config;
    const ExpansionResult& expansion = loaded.expansion;
    const nlohmann::json manifest = BuildManifest(config, expansion, nullptr);
    // Listed combinations go to the printed JSON only: the manifest keeps counts per rule.
    const std::uint64_t unlisted = expansion.pruned_total - expansion.pruned.size();
    if (options.json) {
        nlohmann::json printed = manifest;
        if (options.pruned) {
            nlohmann::json list = nlohmann::json::array();
            for (const PrunedCombination& p : expansion.pruned) {
                list.push_back({{"id", p.combination.Id()},
                                {"program", p.combination.program},
                                {"defines", p.combination.defines},
                                {"rule", p.rule},
                                {"file", p.where.file},
                                {"line", p.where.line}});
            }
            printed["pruned"] = list;
            printed["pruned_unlisted"] = unlisted;
        }
        std::printf("%s\n", JsonText(printed, 2).c_str());
    } else {
        for (const Variant& variant : expansion.variants) {
            std::printf("%s\n", variant.Id().c_str());
        }
        for (const PrunedCombination& p : expansion.pruned) {
            std::printf("pruned %s  (%s, %s:%d)\n", p.combination.Id().c_str(), p.rule.c_str(),
                        p.where.file.c_str(), p.where.line);
        }
        if (options.pruned && unlisted > 0) {
            std::printf("... %llu more pruned combinations not listed (raise --pruned-limit)\n",
                        static_cast<unsigned long long>(unlisted));
        }
        for (const RulePruneCount& rule : expansion.pruned_by_rule) {
            std::printf("%llu pruned by %s: %s  (%s:%d)\n",
                        static_cast<unsigned long long>(rule.count), rule.program.c_str(),
                        rule.rule.c_str(), rule.where.file.c_str(), rule.where.line);
        }
        std::printf("%zu variants, %llu pruned combinations\n", expansion.variants.size(),
                    static_cast<unsigned long long>(expansion.pruned_total));
    }
    if (options.out.empty()) {
        return kExitOk;
    }
    // Every variant's stage sources exactly as a GL driver receives them, plus the manifest.
    int begin_code = kExitOk;
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(options.out, "tidepool expand", &begin_code);
    if (!publisher) {
        return begin_code;
    }
    // Everything goes to a private staging folder, removed by the publisher unless published.
    const std::filesystem::path& staging = publisher->Staging();
    if (const int code = WriteVariantSources(config, expansion.variants, staging);
        code != kExitOk) {
        return code;
    }
    if (std::string error =
                base::WriteFileAtomically(staging / "manifest.json", JsonText(manifest, 2) + "\n");
        !error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitEnvironment;
    }
    if (base::PublishError error = publisher->Publish(); error.Failed()) {
        std::fprintf(stderr, "error: %s\n", error.message.c_str());
        return PublishExitCode(error);
    }
    if (const int code = WriteDepfileIfAsked(options, config); code != kExitOk) {
        return code;
    }
    if (!options.json) {
        std::printf("wrote %s/<target>/<program>/<variant>.vert|.frag and %s/manifest.json\n",
                    options.out.c_str(), options.out.c_str());
    }
    return kExitOk;
}

int RunValidateFiles(const CompilerOptions& options) {
    std::vector<ShaderFile> files;
    for (const std::string& path : options.files) {
        ShaderFile file{path, Stage::kVertex};
        if (options.stage == "vert" || options.stage == "vertex") {
            file.stage = Stage::kVertex;
        } else if (options.stage == "frag" || options.stage == "fragment") {
            file.stage = Stage::kFragment;
        } else if (!StageFromExtension(path, &file.stage)) {
            std::fprintf(stderr,
                         "%s: error: cannot tell the stage from the extension; use .vert/.vsh, "
                         ".frag/.fsh or --stage vert|frag\n",
                         path.c_str());
            return kExitUsage;
        }
        if (const TextFileRead read = ReadShaderFile(path); !read.ok) {
            std::fprintf(stderr, "%s: error: cannot read the shader file: %s\n", path.c_str(),
                         read.error.c_str());
            return kExitUsage;
        }
        files.push_back(file);
    }
    std::optional<DeviceLimits> limits;
    if (!LoadDeviceLimits(options, &limits)) {
        return kExitUsage;
    }
    ShaderFileOptions file_options;
    file_options.target = TargetOption(options);
    file_options.limits = limits ? &*limits : nullptr;
    const std::unique_ptr<base::ContentCache> cache = OpenCache(options.cache);
    file_options.cache = cache.get();
    const ValidationReport report = ValidateShaderFiles(files, options.defines, file_options);
    WarnAboutCache(cache.get());
    const std::string format = ReportFormat(options);
    int errors = 0;
    nlohmann::json json = nlohmann::json::array();
    for (const VariantVerdict& verdict : report.verdicts) {
        PrintDiagnostics(verdict.diagnostics);
        errors += verdict.valid ? 0 : 1;
        nlohmann::json diagnostics = nlohmann::json::array();
        for (const Diagnostic& d : verdict.diagnostics) {
            diagnostics.push_back(ToJson(d));
        }
        nlohmann::json entry = {{"files", verdict.variant.program},
                                {"valid", verdict.valid},
                                {"diagnostics", diagnostics}};
        entry.update(StepsJson(verdict));
        json.push_back(std::move(entry));
    }
    if (format == "sarif") {
        if (const int code =
                    EmitReport(options, JsonText(BuildSarifLog(report, "", TIDEPOOL_VERSION), 2));
            code != kExitOk) {
            return code;
        }
    } else if (format == "json") {
        if (const int code = EmitReport(options, JsonText(json, 2)); code != kExitOk) {
            return code;
        }
    } else {
        std::printf("%zu file(s): %s\n", files.size(), errors == 0 ? "valid" : "INVALID");
    }
    return errors == 0 ? kExitOk : kExitShaderErrors;
}

// Records in each variant entry of `manifest` where WriteVariantSources put its stages:
// "sources": {"vertex": PATH, "fragment": PATH}, relative to the manifest's folder.
void AddSourcePaths(const std::vector<Variant>& variants, nlohmann::json* manifest) {
    std::map<std::string, const Variant*> by_id;
    for (const Variant& variant : variants) {
        by_id[variant.Id()] = &variant;
    }
    for (nlohmann::json& entry : (*manifest)["variants"]) {
        const Variant& variant = *by_id.at(entry["id"].get<std::string>());
        GlslTarget target = GlslTarget::kEs100;
        TargetFromName(entry["target"].get<std::string>(), &target);
        entry["sources"] = {
                {"vertex", VariantSourcePath(target, variant, Stage::kVertex).generic_string()},
                {"fragment",
                 VariantSourcePath(target, variant, Stage::kFragment).generic_string()}};
    }
}

// Adds the flags validate has for build systems and CI; the rest of validate's flags stay where
// they are registered.
void AddValidateOutputFlags(CLI::App* validate, CompilerOptions& options, CLI::Option* out) {
    validate->add_option("--format", options.format,
                         "report on stdout as text, json (as --json) or sarif (SARIF 2.1.0, for "
                         "code scanning)")
            ->check(CLI::IsMember({"text", "json", "sarif"}))
            ->excludes(validate->get_option("--json"));
    validate->add_option("--output-file", options.output_file,
                         "write the json or sarif report to this file (atomically), not stdout");
    validate->add_option("--program", options.program,
                         "validate only this program of the configuration");
    validate->add_flag("--sources", options.sources,
                       "with --out, also write each variant's driver-ready sources (rewritten "
                       "only when changed) and name them in the manifest")
            ->needs(out);
    validate->add_option("--depfile", options.depfile,
                         "with --out, write a Make/Ninja depfile naming the configuration and "
                         "every shader read")
            ->needs(out);
}

int RunValidate(const CompilerOptions& options) {
    if (!options.output_file.empty() && ReportFormat(options) == "text") {
        std::fprintf(stderr,
                     "error: --output-file takes the json or sarif report; add --format "
                     "json or --format sarif\n");
        return kExitUsage;
    }
    if (!CheckDefineOptions(options.defines)) {
        return kExitUsage;
    }
    if (!options.files.empty()) {
        return RunValidateFiles(options);
    }
    if (!options.defines.empty()) {
        std::fprintf(stderr,
                     "error: -D applies to the shader FILEs given, and none was given; "
                     "the variants of a configuration get their defines from it\n");
        return kExitUsage;
    }
    LoadedMatrix loaded = LoadAndExpand(options.config, options.limits);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    if (!options.program.empty() && !KeepOnlyProgram(&loaded, options.program)) {
        return kExitUsage;
    }
    std::optional<DeviceLimits> device_limits;
    if (!LoadDeviceLimits(options, &device_limits)) {
        return kExitUsage;
    }
    if (const std::optional<GlslTarget> target = TargetOption(options)) {
        loaded.config->targets = {*target};  // instead of the file's `targets`
    }
    const VariantConfig& config = *loaded.config;
    // Refused before the validation's work, not after it.
    if (!options.out.empty()) {
        if (const int code = WriteManifestInto(options.out, "", true); code != 0) {
            return code;
        }
    }
    ValidationOptions validation_options;
    validation_options.jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
    validation_options.targets = config.targets;
    validation_options.limits = device_limits ? &*device_limits : nullptr;
    const std::unique_ptr<base::ContentCache> cache = OpenCache(options.cache);
    validation_options.cache = cache.get();
    const ValidationReport report =
            ValidateVariants(config, loaded.expansion.variants, validation_options);
    WarnAboutCache(cache.get());
    PrintDiagnostics(report.diagnostics);
    for (const VariantVerdict& verdict : report.verdicts) {
        PrintDiagnostics(verdict.diagnostics);
    }
    // Built only when printed or written: it costs as much as a validation the cache answers.
    nlohmann::json manifest = ReportFormat(options) == "json" || !options.out.empty()
                                      ? BuildManifest(config, loaded.expansion, &report)
                                      : nlohmann::json();
    if (!options.out.empty()) {
        if (options.sources) {
            if (const int code =
                        WriteVariantSources(config, loaded.expansion.variants, options.out);
                code != kExitOk) {
                return code;
            }
            AddSourcePaths(loaded.expansion.variants, &manifest);
        }
        if (const int code = WriteManifestInto(options.out, JsonText(manifest, 2) + "\n");
            code != 0) {
            return code;
        }
        if (const int code = WriteDepfileIfAsked(options, config); code != kExitOk) {
            return code;
        }
    }
    const int invalid = report.InvalidCount();
    const std::string format = ReportFormat(options);
    if (format == "sarif") {
        if (const int code = EmitReport(
                    options, JsonText(BuildSarifLog(report, config.base_dir, TIDEPOOL_VERSION), 2));
            code != kExitOk) {
            return code;
        }
    } else if (format == "json") {
        if (const int code = EmitReport(options, JsonText(manifest, 2)); code != kExitOk) {
            return code;
        }
    } else {
        std::printf(
                "%zu variants (%llu pruned combinations) x %zu target(s): %d stage slots -> "
                "%zu distinct stage programs (%d shared), %d links; %s\n",
                loaded.expansion.variants.size(),
                static_cast<unsigned long long>(loaded.expansion.pruned_total),
                config.targets.size(), report.stage_slots, report.stage_programs.size(),
                report.SharedStageSlots(), report.links,
                invalid == 0 ? "all valid" : fmt::format("{} INVALID", invalid).c_str());
    }
    return invalid == 0 && !HasErrors(report.diagnostics) ? kExitOk : kExitShaderErrors;
}

int RunStats(const CompilerOptions& options) {
    LoadedMatrix loaded = LoadAndExpand(options.config, options.limits);
    if (!loaded.config) {
        return loaded.exit_code;
    }
    const VariantConfig& config = *loaded.config;
    ValidationOptions validation_options;
    validation_options.jobs = options.jobs > 0 ? options.jobs : DefaultJobs();
    validation_options.targets = {GlslTarget::kEs100};
    const ValidationReport report =
            ValidateVariants(config, loaded.expansion.variants, validation_options);
    std::map<std::string, const StageProgram*> programs;
    for (const StageProgram& program : report.stage_programs) {
        programs[program.file + "|" + program.hash] = &program;
    }
    nlohmann::json json = nlohmann::json::array();
    if (!options.json) {
        std::printf("%-62s %6s %6s %5s %4s %4s %5s %9s\n", "variant", "vs.ops", "fs.ops", "tex",
                    "pow", "norm", "brnch", "fs.paths");
    }
    int invalid = 0;
    for (const VariantVerdict& verdict : report.verdicts) {
        const ProgramConfig* program = config.FindProgram(verdict.variant.program);
        const StageProgram* vs = programs[program->vertex_path + "|" + verdict.vertex_hash];
        const StageProgram* fs = programs[program->fragment_path + "|" + verdict.fragment_hash];
        if (!verdict.valid || vs == nullptr || fs == nullptr) {
            PrintDiagnostics(verdict.diagnostics);
            ++invalid;
            continue;
        }
        auto builtin = [](const StageCost& cost, const char* name) {
            auto it = cost.builtin_calls.find(name);
            return it == cost.builtin_calls.end() ? 0 : it->second;
        };
        const StageCost& v = vs->cost;
        const StageCost& f = fs->cost;
        json.push_back(
                {{"id", verdict.variant.Id()}, {"vertex", ToJson(v)}, {"fragment", ToJson(f)}});
        if (!options.json) {
            std::printf("%-62s %6d %6d %5d %4d %4d %5d %4d-%-4d\n", verdict.variant.Id().c_str(),
                        v.TotalOps(), f.TotalOps(), v.texture_samples + f.texture_samples,
                        builtin(v, "pow") + builtin(f, "pow"),
                        builtin(v, "normalize") + builtin(f, "normalize"), v.branches + f.branches,
                        f.shortest_path_ops, f.longest_path_ops);
        }
    }
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    }
    return invalid == 0 ? kExitOk : kExitShaderErrors;
}

void AddCommonFlags(CLI::App* command, CompilerOptions& options) {
    command->add_option("--config", options.config, "variant matrix file")->capture_default_str();
    command->add_flag("--json", options.json, "print JSON instead of text");
    AddMatrixLimitOptions(command, &options.limits);
}

}  // namespace

void RegisterCompilerCommands(CLI::App& app, int& exit_code) {
    // The options live as long as the app: CLI11 writes into them during parse.
    static CompilerOptions expand_options;
    static CompilerOptions validate_options;
    static CompilerOptions stats_options;

    CLI::App* expand = app.add_subcommand(
            "expand",
            "List every variant and how many combinations each rule pruned (with "
            "--pruned, the combinations too); with --out, write each variant's "
            "driver-ready sources");
    AddCommonFlags(expand, expand_options);
    CLI::Option* pruned =
            expand->add_flag("--pruned", expand_options.pruned,
                             "also list pruned combinations, each with the first rule it breaks");
    expand->add_option(
                  "--pruned-limit", expand_options.pruned_limit,
                  fmt::format("list at most this many pruned combinations, 1..{}", kVariantCeiling))
            ->capture_default_str()
            ->needs(pruned);
    CLI::Option* expand_out =
            expand->add_option("--out", expand_options.out,
                               "folder for <target>/<program>/<variant>.vert|.frag and "
                               "manifest.json")
                    ->transform(NormaliseOutPath);
    expand->add_option("--program", expand_options.program,
                       "expand only this program of the configuration");
    expand->add_option("--depfile", expand_options.depfile,
                       "with --out, write a Make/Ninja depfile naming the configuration and "
                       "every shader read")
            ->needs(expand_out);
    expand->callback([&exit_code] { exit_code = RunExpand(expand_options); });

    CLI::App* validate = app.add_subcommand(
            "validate",
            "Validate every variant with glslang (stages and linked programs), or "
            "the shader FILEs given");
    AddCommonFlags(validate, validate_options);
    validate->add_option("files", validate_options.files,
                         "plain shader files (.vert/.vsh, .frag/.fsh); a vertex and a fragment "
                         "file given together are linked");
    validate->add_option("--stage", validate_options.stage, "stage of plain files: vert or frag")
            ->check(CLI::IsMember({"vert", "frag", "vertex", "fragment"}));
    // One value per -D, so `-D NAME FILE` leaves FILE to the file list.
    validate->add_option("-D,--define", validate_options.defines,
                         "define for plain files: NAME or NAME=VALUE")
            ->allow_extra_args(false);
    validate->add_option("-j,--jobs", validate_options.jobs, "worker threads (default: cores)");
    AddValidateOutputFlags(validate, validate_options,
                           validate->add_option("--out", validate_options.out,
                                                "folder to write manifest.json into")
                                   ->transform(NormaliseOutPath));
    AddCacheFlags(validate, &validate_options.cache);
    validate->add_option("--limits", validate_options.device_limits,
                         "check against a device's resource limits: a file of 'Name value' "
                         "lines, glslang's -c names (README: validator)");
    validate->add_option("--target", validate_options.target,
                         "add the WebGL rules: webgl1 (GLSL ES 1.00) or webgl2 (GLSL ES 3.00); "
                         "with a configuration, instead of its targets")
            ->check(CLI::IsMember({"webgl1", "webgl2"}));
    validate->callback([&exit_code] { exit_code = RunValidate(validate_options); });

    CLI::App* stats = app.add_subcommand(
            "stats",
            "Static cost of every variant from glslang's tree: ops, texture samples, "
            "pow/normalize calls, branches, shortest and longest fragment path");
    AddCommonFlags(stats, stats_options);
    stats->add_option("-j,--jobs", stats_options.jobs, "worker threads (default: cores)");
    stats->callback([&exit_code] { exit_code = RunStats(stats_options); });
}

}  // namespace tidepool::cli
