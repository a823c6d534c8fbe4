// `tidepool plan`: scene descriptions → the cheapest water configuration that meets each
// scene's quality target, chosen by rendering and measuring.
#pragma once

#include <CLI/CLI.hpp>

namespace tidepool::cli {

/// Registers `tidepool plan` (--scene NAME or --all); stores the exit code in `exit_code`.
void RegisterPlanCommands(CLI::App& app, int& exit_code);

}  // namespace tidepool::cli
