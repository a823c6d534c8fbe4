// Small pieces every `tidepool` command shares: printing diagnostics, reading the host, sizes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tidepool/Diagnostic.h"

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

}  // namespace tidepool::cli
