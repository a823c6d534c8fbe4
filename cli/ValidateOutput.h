// How `tidepool validate` prints or writes what it found: diagnostics aside, a one-line summary,
// the manifest as JSON, or a SARIF log, on stdout or in --output-file.
#pragma once

#include "tidepool/pipeline/CompilerStages.h"

#include <optional>
#include <string>
#include <vector>

namespace tidepool::cli {

/// `tidepool validate`'s flags, as the pipeline's options and the output's own.
struct ValidateCommandOptions {
    pipeline::ValidateOptions matrix;
    pipeline::ValidateFilesOptions files;  // plain shader files: files, stage, defines
    bool json = false;
    std::string format = "text";  // text, json (as --json) or sarif
    std::string output_file;      // where json or sarif goes instead of stdout
    std::string target;           // --target webgl1|webgl2
    // The flags given that only a configuration takes (--config, --out, ...), and whether
    // --stage, which only plain files take, was given: each is refused with the other mode.
    std::vector<std::string> configuration_flags;
    bool stage_given = false;

    // The report format asked for: --json is --format json.
    std::string Format() const { return json ? "json" : format; }
};

/// Prints the summary, or emits the JSON or SARIF report of plain files; returns the exit code
/// (kExitEnvironment when --output-file cannot be written, else the result's status).
int ReportFiles(const ValidateCommandOptions& options, const pipeline::ValidateFilesResult& result);

/// What `validate` shows for a configuration: the text for stdout (the summary, or the JSON or
/// SARIF report), or the report's text for --output-file (stdout then shows nothing).
struct MatrixReport {
    std::string out;
    std::optional<std::string> report_file;
};

/// The summary, manifest or SARIF report of a configuration that loaded, as MatrixReport says.
MatrixReport RenderMatrixReport(const ValidateCommandOptions& options,
                                const pipeline::ValidateResult& result);

}  // namespace tidepool::cli
