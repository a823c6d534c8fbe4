// Each `tidepool` subcommand registers itself on the CLI11 app; its callback runs the library
// calls, prints, and stores the process exit code (see ExitCode).
#pragma once

#include <CLI/CLI.hpp>

namespace tidepool::cli {

/// The process exit codes every command shares (README.md, "Exit codes").
enum ExitCode : int {
    kExitOk = 0,           // everything valid / rendered
    kExitShaderErrors = 1, // at least one shader or variant has errors
    kExitUsage = 2,        // bad command line or configuration
    kExitEnvironment = 3,  // no EGL/OSMesa, no GL context
};

/// `tidepool expand`, `tidepool validate`, `tidepool stats` (the compiler side).
void RegisterCompilerCommands(CLI::App& app, int& exit_code);

/// `tidepool render`, `tidepool bench` (the runner side).
void RegisterRunnerCommands(CLI::App& app, int& exit_code);

/// `tidepool report` (from saved manifest and results) and `tidepool run` (validate, render,
/// report).
void RegisterReportCommands(CLI::App& app, int& exit_code);

}  // namespace tidepool::cli
