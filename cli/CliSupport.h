// Small pieces every `tidepool` command shares: printing diagnostics, reading the host, sizes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tidepool/Diagnostic.h"
#include "tidepool/runner/FourierReflection.h"

namespace CLI {
class App;
}

namespace tidepool::cli {

/// Prints each diagnostic in GCC form on stderr, one per line.
void PrintDiagnostics(const std::vector<Diagnostic>& diagnostics);

/// The CPU's model name from /proc/cpuinfo, or "unknown".
std::string CpuModel();

/// `git rev-parse HEAD` in `folder`, or "unknown" outside a repository or without git.
std::string GitRevision(const std::filesystem::path& folder);

/// Parses "WxH"; false unless both sides are whole numbers in [min_side, 8192] (8192: the
/// largest render target the renderer allocates).
bool ParseSize(const std::string& text, int min_side, int* width, int* height);

/// Adds --fourier-coefficients and --fourier-directions (REFLECTION_FOURIER) to `command`,
/// writing into `settings`.
void AddFourierOptions(CLI::App* command, runner::FourierSettings* settings);

/// Prints why `settings` cannot be used, naming the options, and returns false; true when they
/// can.
bool CheckFourierOptions(const runner::FourierSettings& settings);

}  // namespace tidepool::cli
