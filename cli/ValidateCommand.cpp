// `tidepool validate`: flags → pipeline::ValidateMatrix or pipeline::ValidateFiles → diagnostics
// and a summary, JSON or SARIF → exit code. A configuration's run is first looked up whole in the
// validation cache (RunRecordCache.h) and, when found, repeated instead.
#include "tidepool/base/AtomicFile.h"
#include "tidepool/pipeline/CompilerStages.h"
#include "tidepool/pipeline/OutputFiles.h"
#include "tidepool/pipeline/RunRecordCache.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "CliSupport.h"
#include "Commands.h"
#include "RunSourceDigest.h"
#include "ValidateOutput.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

// The key of a configuration's run record: everything besides the files read that decides what
// the run prints and writes. Not -j (the output does not depend on it) nor the cache folder (the
// record lives there). None when the working directory, against which paths resolve, is gone.
std::optional<std::string> RunKeyText(const ValidateCommandOptions& options) {
    std::error_code ec;
    const std::filesystem::path cwd = std::filesystem::current_path(ec);
    if (ec) {
        return std::nullopt;
    }
    const pipeline::ValidateOptions& matrix = options.matrix;
    std::string text = fmt::format("tidepool validate\n{}\n{}\n{}", kRunSourceDigest,
                                   TIDEPOOL_VERSION, ValidationCacheIdentity());
    // Length-prefixed, so that no value can pass for another's.
    auto add = [&text](std::string_view name, const std::string& value) {
        text += fmt::format("{} {}:{}\n", name, value.size(), value);
    };
    add("cwd", cwd.string());
    add("config", matrix.config);
    add("program", matrix.program);
    add("limits", matrix.device_limits);
    add("target", options.target);
    add("max-variants", matrix.limits.max_variants.value_or("-"));
    add("allow-large-matrix", matrix.limits.allow_large_matrix ? "1" : "0");
    add("pruned", std::to_string(matrix.limits.pruned_limit));
    add("out", matrix.out);
    add("depfile", matrix.depfile);
    add("format", options.Format());
    add("output-file", options.output_file);
    return text;
}

// Writes `text` to `stream` whole.
void Emit(std::FILE* stream, const std::string& text) {
    std::fwrite(text.data(), 1, text.size(), stream);
}

// Repeats `record`: the files first, as the normal path writes them before printing, then the
// output. False, with nothing printed, when a file cannot be written: the normal path then runs
// and reports why as it always does.
bool Replay(const ValidateCommandOptions& options, const pipeline::RunRecord& record) {
    if (record.manifest &&
        pipeline::WriteManifest(options.matrix.out, *record.manifest).Stopped()) {
        return false;
    }
    pipeline::Outcome written;
    if (record.depfile &&
        !pipeline::WriteFile(options.matrix.depfile, *record.depfile, &written, "--depfile: ")) {
        return false;
    }
    if (record.report_file &&
        !base::WriteFileAtomically(options.output_file, *record.report_file).empty()) {
        return false;
    }
    Emit(stderr, record.err);
    Emit(stdout, record.out);
    return true;
}

// Validates a configuration: repeats its run record when the cache holds one for these options
// and files, else runs the pipeline, prints, and keeps the record of this run.
int RunMatrix(const ValidateCommandOptions& options) {
    const timespec started = pipeline::RunRecordCache::StartTime();
    const std::unique_ptr<base::ContentCache> cache =
            options.matrix.sources ? nullptr : pipeline::OpenValidationCache(options.matrix.cache);
    const std::optional<std::string> key = RunKeyText(options);
    std::optional<pipeline::RunRecordCache> records;
    if (cache && key) {
        records.emplace(*cache, *key);
        if (const std::optional<pipeline::RunRecord> record = records->Find();
            record && Replay(options, *record)) {
            return record->exit_code;
        }
    }
    const pipeline::ValidateResult result = pipeline::ValidateMatrix(options.matrix);
    const pipeline::Outcome& outcome = result.matrix.outcome;
    pipeline::RunRecord record;
    for (const Diagnostic& d : outcome.diagnostics) {
        record.err += ForTerminal(FormatDiagnostic(d)) + "\n";
    }
    record.exit_code = pipeline::ExitCode(outcome.status);
    if (!outcome.Stopped()) {
        MatrixReport report = RenderMatrixReport(options, result);
        record.out = std::move(report.out);
        record.report_file = std::move(report.report_file);
    }
    record.manifest = result.manifest_text;
    record.depfile = result.depfile_text;
    Emit(stderr, record.err);
    if (record.report_file) {
        if (const std::string error =
                    base::WriteFileAtomically(options.output_file, *record.report_file);
            !error.empty()) {
            std::fprintf(stderr, "error: --output-file: %s\n", error.c_str());
            return kExitEnvironment;
        }
    }
    Emit(stdout, record.out);
    if (records && result.repeatable && records->Keep(result.files_read, started, record)) {
        cache->Trim();
    }
    return record.exit_code;
}

int RunValidate(ValidateCommandOptions options) {
    if (!options.output_file.empty() && options.Format() == "text") {
        std::fprintf(stderr,
                     "error: --output-file takes the json or sarif report; add --format "
                     "json or --format sarif\n");
        return kExitUsage;
    }
    if (!CheckDefineOptions(options.files.defines)) {
        return kExitUsage;
    }
    // Silently ignored, such a flag would leave the user believing it had been applied.
    if (!options.files.files.empty() && !options.configuration_flags.empty()) {
        const std::string& flag = options.configuration_flags.front();
        if (flag == "--config") {
            std::fprintf(stderr,
                         "error: --config and shader FILEs were both given; validate checks a "
                         "configuration or plain files, not both: drop one\n");
        } else {
            std::fprintf(stderr,
                         "error: %s applies to a configuration, not to the shader FILEs given; "
                         "drop %s, or drop the FILEs to validate the configuration\n",
                         flag.c_str(), flag.c_str());
        }
        return kExitUsage;
    }
    if (options.files.files.empty() && options.stage_given) {
        std::fprintf(stderr,
                     "error: --stage applies to the shader FILEs given, and none was given; "
                     "a configuration's programs name their own vertex and fragment files\n");
        return kExitUsage;
    }
    GlslTarget target = GlslTarget::kEs100;
    if (!options.target.empty() && TargetFromName(options.target, &target)) {
        options.matrix.target = options.files.target = target;
    }
    options.files.device_limits = options.matrix.device_limits;
    options.files.cache = options.matrix.cache;
    options.files.report_file = options.matrix.report_file = options.output_file;
    if (!options.files.files.empty()) {
        const pipeline::ValidateFilesResult result = pipeline::ValidateFiles(options.files);
        const int code = PrintOutcome(result.outcome);
        return result.outcome.Stopped() ? code : ReportFiles(options, result);
    }
    if (!options.files.defines.empty()) {
        std::fprintf(stderr,
                     "error: -D applies to the shader FILEs given, and none was given; "
                     "the variants of a configuration get their defines from it\n");
        return kExitUsage;
    }
    options.matrix.manifest_wanted = options.Format() == "json";
    return RunMatrix(options);
}

}  // namespace

void RegisterValidateCommand(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<ValidateCommandOptions>();
    pipeline::ValidateOptions& matrix = options->matrix;
    CLI::App* validate = app.add_subcommand(
            "validate",
            "Validate every variant with glslang (stages and linked programs), or "
            "the shader FILEs given");
    AddMatrixFlags(validate, &matrix.config, &options->json, &matrix.limits);
    validate->add_option("files", options->files.files,
                         "plain shader files (.vert/.vsh, .frag/.fsh); a vertex and a fragment "
                         "file given together are linked");
    validate->add_option("--stage", options->files.stage, "stage of plain files: vert or frag")
            ->check(CLI::IsMember({"vert", "frag", "vertex", "fragment"}));
    // One value per -D, so `-D NAME FILE` leaves FILE to the file list.
    validate->add_option("-D,--define", options->files.defines,
                         "define for plain files: NAME or NAME=VALUE")
            ->allow_extra_args(false);
    AddJobsOption(validate, &matrix.jobs);
    CLI::Option* out =
            validate->add_option("--out", matrix.out, "folder to write manifest.json into")
                    ->transform(NormaliseOutPath);
    validate->add_option("--format", options->format,
                         "report on stdout as text, json (as --json) or sarif (SARIF 2.1.0, for "
                         "code scanning)")
            ->check(CLI::IsMember({"text", "json", "sarif"}))
            ->excludes(validate->get_option("--json"));
    validate->add_option("--output-file", options->output_file,
                         "write the json or sarif report to this file (atomically), not stdout");
    validate->add_option("--program", matrix.program,
                         "validate only this program of the configuration");
    validate->add_flag("--sources", matrix.sources,
                       "with --out, also write each variant's driver-ready sources (rewritten "
                       "only when changed) and name them in the manifest")
            ->needs(out);
    validate->add_option("--depfile", matrix.depfile,
                         "with --out, write a Make/Ninja depfile naming the configuration and "
                         "every shader read")
            ->needs(out);
    AddCacheFlags(validate, &matrix.cache);
    validate->add_option("--limits", matrix.device_limits,
                         "check against a device's resource limits: a file of 'Name value' "
                         "lines, glslang's -c names (README: validator)");
    validate->add_option("--target", options->target,
                         "add the WebGL rules: webgl1 (GLSL ES 1.00) or webgl2 (GLSL ES 3.00, "
                         "and 1.00 files as they are); with a configuration, instead of its "
                         "targets")
            ->check(CLI::IsMember({"webgl1", "webgl2"}));
    validate->callback([options, validate, &exit_code] {
        for (const char* flag : {"--config", "--program", "--out", "--sources", "--depfile",
                                 "--max-variants", "--allow-large-matrix"}) {
            if (validate->count(flag) > 0) {
                options->configuration_flags.emplace_back(flag);
            }
        }
        options->stage_given = validate->count("--stage") > 0;
        exit_code = RunValidate(*options);
    });
}

}  // namespace tidepool::cli
