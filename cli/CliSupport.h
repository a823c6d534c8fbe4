// Small pieces every `tidepool` command shares: printing diagnostics, reading the host, sizes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"

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

/// The largest render target side the commands accept.
inline constexpr int kMaxRenderSide = 8192;

/// Parses "WxH"; false unless both sides are whole numbers in [min_side, max_side].
bool ParseSize(const std::string& text, int min_side, int* width, int* height,
               int max_side = kMaxRenderSide);

/// ParseSize for the value of option `flag` (e.g. "--plan-size"); on failure prints
/// "error: FLAG must be WxH with MIN..MAX each, not 'TEXT'" and returns false.
bool ParseSizeOption(std::string_view flag, const std::string& text, int min_side, int* width,
                     int* height, int max_side = kMaxRenderSide);

/// Parses --backend; on failure prints "error: --backend must be auto, egl or osmesa, not
/// 'TEXT'" and returns false.
bool ParseBackendOption(const std::string& text, runner::BackendKind* backend);

/// A configuration file loaded and expanded, or the exit code of why not.
struct LoadedMatrix {
    std::optional<VariantConfig> config;
    ExpansionResult expansion;
    int exit_code = 0;  // kExitOk, or kExitUsage when config is missing
};

/// Loads `config_path` and expands it (to at most `max_variants` combinations, or the file's own
/// max_variants when 0), printing every diagnostic; fails through exit_code kExitUsage (and no
/// config) when the file does not load or the expansion has errors.
LoadedMatrix LoadAndExpand(const std::string& config_path, std::uint64_t max_variants = 0);

/// An --out folder as every command uses it: lexically normal and without a trailing slash, so
/// that `--out DIR/` names DIR (and its staging sibling) rather than an empty file name inside it.
/// Registered as a CLI11 transform on every --out option.
std::string NormaliseOutPath(std::string path);

/// Checks the -D values of plain-file validation: each must be NAME or NAME=VALUE, NAME a define
/// name config mode accepts (IsValidDefineName) and VALUE a single line; prints why not and
/// returns false otherwise.
bool CheckDefineOptions(const std::vector<std::string>& defines);

/// Validation jobs when the user gives none: one per core (1 when unknown).
int DefaultJobs();

/// Adds --fourier-coefficients and --fourier-directions (REFLECTION_FOURIER) to `command`,
/// writing into `settings`.
void AddFourierOptions(CLI::App* command, runner::FourierSettings* settings);

/// Prints why `settings` cannot be used, naming the options, and returns false; true when they
/// can.
bool CheckFourierOptions(const runner::FourierSettings& settings);

}  // namespace tidepool::cli
