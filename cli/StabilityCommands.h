// `tidepool stability`: runs the hard-case catalogue and writes stability.json.
#pragma once

#include <CLI/CLI.hpp>

namespace tidepool::cli {

/// Registers `tidepool stability` on `app`; its callback stores the exit code in `exit_code`
/// (0 every case passed, 1 a case failed, 2 usage, 3 no GL context).
void RegisterStabilityCommands(CLI::App& app, int& exit_code);

}  // namespace tidepool::cli
