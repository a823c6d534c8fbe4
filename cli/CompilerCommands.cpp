// `tidepool expand`, `validate` and `stats`: flags → options → library calls → print → exit code.
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "CliSupport.h"
#include "Commands.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/TextFile.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

namespace tidepool::cli {
namespace {

struct CompilerOptions {
    std::string config = "variants.yaml";
    bool json = false;
    std::string out;
    MatrixLimits limits;
    bool pruned = false;                       // expand: list pruned combinations
    std::string pruned_limit = "1000";         // expand: at most this many
    int jobs = 0;                    // 0: one per core
    std::vector<std::string> files;  // validate: plain shader files
    std::string stage;               // validate: force the stage of plain files
    std::vector<std::string> defines;
    CacheFlags cache;                // validate: --cache, --no-cache
};

// The configuration and its expansion, or the exit code that explains why there is none.

std::string SafeFileName(const std::string& id) {
    std::string name;
    for (char c : id) {
        name += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '.';
    }
    return name;
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
    base::PublishError begin;
    const std::unique_ptr<base::FolderPublisher> publisher =
            base::FolderPublisher::Begin(options.out, "tidepool expand", &begin);
    if (!publisher) {
        std::fprintf(stderr, "error: %s\n", begin.message.c_str());
        return PublishExitCode(begin);
    }
    // Everything goes to a private staging folder, removed by the publisher unless published.
    const std::filesystem::path& staging = publisher->Staging();
    std::map<std::string, std::string> sources;  // path → text, read once
    for (GlslTarget target : config.targets) {
        for (const Variant& variant : loaded.expansion.variants) {
            const ProgramConfig* program = config.FindProgram(variant.program);
            for (Stage stage : {Stage::kVertex, Stage::kFragment}) {
                const std::string& path =
                        stage == Stage::kVertex ? program->vertex_path : program->fragment_path;
                if (sources.count(path) == 0) {
                    TextFileRead read = ReadShaderFile(config.Resolve(path));
                    if (!read.ok) {
                        std::fprintf(stderr, "%s: error: cannot read shader file: %s\n",
                                     path.c_str(), read.error.c_str());
                        return kExitUsage;
                    }
                    sources[path] = std::move(read.text);
                }
                const std::filesystem::path file =
                        staging / TargetName(target) / variant.program /
                        fmt::format("{}.{}", SafeFileName(variant.Id()),
                                    stage == Stage::kVertex ? "vert" : "frag");
                const std::string error = base::WriteFileAtomically(
                        file, AssembleDriverSource(sources[path], variant.defines, stage, target));
                if (!error.empty()) {
                    std::fprintf(stderr, "error: %s\n", error.c_str());
                    return kExitEnvironment;
                }
            }
        }
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
    const ValidationReport report = ValidateShaderFiles(files, options.defines);
    int errors = 0;
    nlohmann::json json = nlohmann::json::array();
    for (const VariantVerdict& verdict : report.verdicts) {
        PrintDiagnostics(verdict.diagnostics);
        errors += verdict.valid ? 0 : 1;
        nlohmann::json diagnostics = nlohmann::json::array();
        for (const Diagnostic& d : verdict.diagnostics) {
            diagnostics.push_back(ToJson(d));
        }
        json.push_back({{"files", verdict.variant.program},
                        {"valid", verdict.valid},
                        {"diagnostics", diagnostics}});
    }
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    } else {
        std::printf("%zu file(s): %s\n", files.size(), errors == 0 ? "valid" : "INVALID");
    }
    return errors == 0 ? kExitOk : kExitShaderErrors;
}

int RunValidate(const CompilerOptions& options) {
    if (!CheckDefineOptions(options.defines)) {
        return kExitUsage;
    }
    if (!options.files.empty()) {
        return RunValidateFiles(options);
    }
    if (!options.defines.empty()) {
        std::fprintf(stderr, "error: -D applies to the shader FILEs given, and none was given; "
                             "the variants of a configuration get their defines from it\n");
        return kExitUsage;
    }
    LoadedMatrix loaded = LoadAndExpand(options.config, options.limits);
    if (!loaded.config) {
        return loaded.exit_code;
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
    const nlohmann::json manifest = options.json || !options.out.empty()
                                            ? BuildManifest(config, loaded.expansion, &report)
                                            : nlohmann::json();
    if (!options.out.empty()) {
        if (const int code = WriteManifestInto(options.out, JsonText(manifest, 2) + "\n"); code != 0) {
            return code;
        }
    }
    const int invalid = report.InvalidCount();
    if (options.json) {
        std::printf("%s\n", JsonText(manifest, 2).c_str());
    } else {
        std::printf("%zu variants (%llu pruned combinations) x %zu target(s): %d stage slots -> "
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
        std::printf("%-62s %6s %6s %5s %4s %4s %5s %9s\n", "variant", "vs.ops", "fs.ops",
                    "tex", "pow", "norm", "brnch", "fs.paths");
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
        json.push_back({{"id", verdict.variant.Id()},
                        {"vertex", ToJson(v)},
                        {"fragment", ToJson(f)}});
        if (!options.json) {
            std::printf("%-62s %6d %6d %5d %4d %4d %5d %4d-%-4d\n", verdict.variant.Id().c_str(),
                        v.TotalOps(), f.TotalOps(), v.texture_samples + f.texture_samples,
                        builtin(v, "pow") + builtin(f, "pow"),
                        builtin(v, "normalize") + builtin(f, "normalize"),
                        v.branches + f.branches, f.shortest_path_ops, f.longest_path_ops);
        }
    }
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    }
    return invalid == 0 ? kExitOk : kExitShaderErrors;
}

void AddCommonFlags(CLI::App* command, CompilerOptions& options) {
    command->add_option("--config", options.config, "variant matrix file")
            ->capture_default_str();
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
            "expand", "List every variant and how many combinations each rule pruned (with "
                      "--pruned, the combinations too); with --out, write each variant's "
                      "driver-ready sources");
    AddCommonFlags(expand, expand_options);
    CLI::Option* pruned = expand->add_flag(
            "--pruned", expand_options.pruned,
            "also list pruned combinations, each with the first rule it breaks");
    expand->add_option("--pruned-limit", expand_options.pruned_limit,
                       fmt::format("list at most this many pruned combinations, 1..{}",
                                   kVariantCeiling))
            ->capture_default_str()
            ->needs(pruned);
    expand->add_option("--out", expand_options.out,
                       "folder for <target>/<program>/<variant>.vert|.frag and manifest.json")
            ->transform(NormaliseOutPath);
    expand->callback([&exit_code] { exit_code = RunExpand(expand_options); });

    CLI::App* validate = app.add_subcommand(
            "validate", "Validate every variant with glslang (stages and linked programs), or "
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
    validate->add_option("--out", validate_options.out, "folder to write manifest.json into")
            ->transform(NormaliseOutPath);
    AddCacheFlags(validate, &validate_options.cache);
    validate->callback([&exit_code] { exit_code = RunValidate(validate_options); });

    CLI::App* stats = app.add_subcommand(
            "stats", "Static cost of every variant from glslang's tree: ops, texture samples, "
                     "pow/normalize calls, branches, shortest and longest fragment path");
    AddCommonFlags(stats, stats_options);
    stats->add_option("-j,--jobs", stats_options.jobs, "worker threads (default: cores)");
    stats->callback([&exit_code] { exit_code = RunStats(stats_options); });
}

}  // namespace tidepool::cli
