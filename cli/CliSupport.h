// Small pieces every `tidepool` command shares: flags, parsing their values, printing a stage's
// outcome. Nothing here needs GL: the GL commands' own pieces are in GlCliSupport.h. What the
// stages do is in the pipeline library (pipeline/); the few declarations below that forward to
// it keep the commands not yet moved there (RunCommand.cpp) unchanged.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ContentCache.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/pipeline/Host.h"
#include "tidepool/pipeline/MatrixLoading.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/pipeline/ValidationCache.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace CLI {
class App;
}

namespace tidepool::cli {

/// What `tidepool --help` and `tidepool --version` say, in both executables.
inline constexpr const char* kAppDescription =
        "tidepool: shader-variant compiler and validation toolchain for GLSL ES water effects";
inline constexpr const char* kVersionText = "tidepool 0.1.0";

/// Prints `outcome`'s diagnostics on stderr and returns its status as the exit code.
int PrintOutcome(const pipeline::Outcome& outcome);

/// Parses `argv` into `app` (whose command callbacks store `exit_code`) and returns the process
/// exit code: 0 for --help/--version, kExitUsage for a usage error (CLI11's message printed),
/// else what the command stored.
int ParseAndRun(CLI::App& app, int argc, char** argv, const int& exit_code);

/// `text` with every control character but newline and tab (a NUL, an escape sequence, a
/// carriage return) written as \xNN, so a name from an input file shows whole and cannot drive
/// the terminal.
std::string ForTerminal(std::string_view text);

/// Prints each diagnostic in GCC form on stderr, one per line, through ForTerminal.
void PrintDiagnostics(const std::vector<Diagnostic>& diagnostics);

/// The largest render target side the commands accept.
inline constexpr int kMaxRenderSide = 8192;

/// Parses "WxH"; false unless both sides are whole numbers in [min_side, max_side].
bool ParseSize(const std::string& text, int min_side, int* width, int* height,
               int max_side = kMaxRenderSide);

/// ParseSize for the value of option `flag` (e.g. "--plan-size"); on failure prints
/// "error: FLAG must be WxH with MIN..MAX each, not 'TEXT'" and returns false.
bool ParseSizeOption(std::string_view flag, const std::string& text, int min_side, int* width,
                     int* height, int max_side = kMaxRenderSide);

/// Parses a whole number in [min, max] for option `flag`, refusing signs, fractions, exponents
/// and values that overflow; on failure prints "error: FLAG must be a whole number from MIN to
/// MAX[ HINT], not 'TEXT'" and returns false.
bool ParseCountOption(std::string_view flag, const std::string& text, std::uint64_t min,
                      std::uint64_t max, std::string_view hint, std::uint64_t* value);

using MatrixLimits = pipeline::MatrixLimits;

/// Adds -j/--jobs (worker processes, a whole number from 1 to 256) to `command`, into `jobs`.
void AddJobsOption(CLI::App* command, int* jobs);

/// Adds --max-variants and --allow-large-matrix to `command`, writing into `limits`.
void AddMatrixLimitOptions(CLI::App* command, MatrixLimits* limits);

/// Adds what expand, validate and stats share: --config, --json and the matrix limits.
void AddMatrixFlags(CLI::App* command, std::string* config, bool* json, MatrixLimits* limits);

/// An --out folder as every command uses it: lexically normal and without a trailing slash, so
/// that `--out DIR/` names DIR (and its staging sibling) rather than an empty file name inside it.
/// Registered as a CLI11 transform on every --out option.
std::string NormaliseOutPath(std::string path);

/// Checks a --name, the report folder made under --out: a plain folder name (no '/', not
/// starting with '.', so never `..`) other than each of `taken`; prints why not and returns false
/// otherwise.
bool CheckReportName(const std::string& name, const std::vector<std::string>& taken = {});

/// Checks the -D values of plain-file validation: each must be NAME or NAME=VALUE, NAME a define
/// name config mode accepts (IsValidDefineName) and VALUE a single line; prints why not and
/// returns false otherwise.
bool CheckDefineOptions(const std::vector<std::string>& defines);

/// --cache DIR and --no-cache as a command received them.
using CacheFlags = pipeline::CacheChoice;

/// Adds --cache DIR and --no-cache (mutually exclusive) to `command`, writing into `flags`.
void AddCacheFlags(CLI::App* command, CacheFlags* flags);

}  // namespace tidepool::cli
