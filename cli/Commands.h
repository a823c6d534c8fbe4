// Each `tidepool` subcommand registers itself on the CLI11 app; its callback runs the library
// calls, prints, and stores the process exit code (see ExitCode).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace tidepool::cli {

/// The process exit codes every command shares (README.md, "Exit codes").
enum ExitCode : int {
    kExitOk = 0,            // everything valid / rendered
    kExitShaderErrors = 1,  // at least one shader or variant has errors
    kExitUsage = 2,         // bad command line or configuration
    kExitEnvironment = 3,   // no EGL/OSMesa, no GL context
};

/// `tidepool expand` (ExpandCommand.cpp).
void RegisterExpandCommand(CLI::App& app, int& exit_code);

/// `tidepool validate` (ValidateCommand.cpp).
void RegisterValidateCommand(CLI::App& app, int& exit_code);

/// `tidepool stats` (StatsCommand.cpp).
void RegisterStatsCommand(CLI::App& app, int& exit_code);

/// `tidepool render`, `tidepool bench` (RenderCommands.cpp; `tidepool-gl` only).
void RegisterRunnerCommands(CLI::App& app, int& exit_code);

/// `tidepool report` (from saved manifest and results; needs no GL).
void RegisterReportCommand(CLI::App& app, int& exit_code);

/// `tidepool run` (validate, render, stability, plans, report; `tidepool-gl` only).
void RegisterRunCommand(CLI::App& app, int& exit_code);

/// Loads a manifest and results, writes the report into `out`/`name` and prints the
/// whitepaper table; returns kExitOk, kExitShaderErrors when a configuration failed, kExitUsage
/// for unusable inputs, kExitEnvironment when writing failed (message printed).
int BuildAndWriteReport(const std::filesystem::path& manifest, const std::filesystem::path& results,
                        const std::string& name, const std::filesystem::path& out);

/// A command that renders, and so lives in `tidepool-gl`: its name and its one-line help, which
/// the `tidepool` front end lists in its own --help.
struct GlCommand {
    const char* name;
    const char* summary;
};

/// Every GL command, in the order --help lists them.
inline constexpr GlCommand kGlCommands[] = {
        {"render",
         "render every configuration headless through Mesa: images at every view, the "
         "driver's verdict and a short timing"},
        {"bench",
         "time configurations through Mesa: each configuration's median on the run's "
         "clock, and every compared pair of presets timed pair by pair to a stated "
         "resolution"},
        {"run",
         "validate, render, run the stability catalogue and the scene plans, and report "
         "in one go: <out>/manifest/, <out>/render/ (results.json, stability.json, "
         "plans.json) and the report in <out>/<name>/"},
        {"stability",
         "Run the numerical hard cases (CPU sweeps, every water variant rendered "
         "into a float target), the mediump precision study and the shader-guard "
         "comparison; write DIR/stability.json"},
        {"plan",
         "pick the cheapest water configuration that meets a scene's quality target, by "
         "rendering and timing a short candidate list (scenes/NAME.yaml)"},
};

/// The one-line help of GL command `name` (one of kGlCommands).
inline const char* GlCommandSummary(std::string_view name) {
    for (const GlCommand& command : kGlCommands) {
        if (name == command.name) {
            return command.summary;
        }
    }
    return "";
}

}  // namespace tidepool::cli
