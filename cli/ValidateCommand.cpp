// `tidepool validate`: flags → pipeline::ValidateMatrix or pipeline::ValidateFiles → diagnostics
// and a summary, JSON or SARIF → exit code.
#include "tidepool/pipeline/CompilerStages.h"

#include <cstdio>
#include <memory>

#include "CliSupport.h"
#include "Commands.h"
#include "ValidateOutput.h"

namespace tidepool::cli {
namespace {

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
    GlslTarget target = GlslTarget::kEs100;
    if (!options.target.empty() && TargetFromName(options.target, &target)) {
        options.matrix.target = options.files.target = target;
    }
    options.files.device_limits = options.matrix.device_limits;
    options.files.cache = options.matrix.cache;
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
    const pipeline::ValidateResult result = pipeline::ValidateMatrix(options.matrix);
    const int code = PrintOutcome(result.matrix.outcome);
    return result.matrix.outcome.Stopped() ? code : ReportMatrix(options, result);
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
    validate->add_option("-j,--jobs", matrix.jobs, "worker threads (default: cores)");
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
                         "add the WebGL rules: webgl1 (GLSL ES 1.00) or webgl2 (GLSL ES 3.00); "
                         "with a configuration, instead of its targets")
            ->check(CLI::IsMember({"webgl1", "webgl2"}));
    validate->callback([options, &exit_code] { exit_code = RunValidate(*options); });
}

}  // namespace tidepool::cli
