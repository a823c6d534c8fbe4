// tidepool: expand, validate, render and report GLSL ES water shader variants.
#include <cstdio>

#include "Commands.h"
#include "PlanCommands.h"
#include "StabilityCommands.h"

int main(int argc, char** argv) {
    CLI::App app{"tidepool: shader-variant compiler and validation toolchain for GLSL ES water "
                 "effects"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "tidepool 0.1.0");
    int exit_code = tidepool::cli::kExitOk;
    tidepool::cli::RegisterCompilerCommands(app, exit_code);
    tidepool::cli::RegisterRunnerCommands(app, exit_code);
    tidepool::cli::RegisterReportCommands(app, exit_code);
    tidepool::cli::RegisterStabilityCommands(app, exit_code);
    tidepool::cli::RegisterPlanCommands(app, exit_code);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        // CLI11 returns 0 for --help/--version and its own codes for usage errors; ours is 2.
        return code == 0 ? tidepool::cli::kExitOk : tidepool::cli::kExitUsage;
    }
    return exit_code;
}
