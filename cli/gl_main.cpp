// tidepool-gl: every tidepool command, the ones that render included. The `tidepool` front end
// (main.cpp) runs it, with the same arguments, for the commands that need GL, so that the
// front end itself never loads Mesa, LLVM or their dependencies.
#include "CliSupport.h"
#include "Commands.h"
#include "PlanCommands.h"
#include "StabilityCommands.h"

int main(int argc, char** argv) {
    CLI::App app{tidepool::cli::kAppDescription};
    int exit_code = tidepool::cli::kExitOk;
    tidepool::cli::RegisterExpandCommand(app, exit_code);
    tidepool::cli::RegisterValidateCommand(app, exit_code);
    tidepool::cli::RegisterStatsCommand(app, exit_code);
    tidepool::cli::RegisterRunnerCommands(app, exit_code);
    tidepool::cli::RegisterReportCommand(app, exit_code);
    tidepool::cli::RegisterRunCommand(app, exit_code);
    tidepool::cli::RegisterStabilityCommands(app, exit_code);
    tidepool::cli::RegisterPlanCommands(app, exit_code);
    return tidepool::cli::ParseAndRun(app, argc, argv, exit_code);
}
