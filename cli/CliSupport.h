// Small pieces every `tidepool` command shares: printing diagnostics, reading the host, sizes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Results.h"

namespace CLI {
class App;
}

namespace tidepool::cli {

/// The exit code of a failed publication: kExitUsage when the folder is someone else's (choose
/// another), kExitEnvironment when the file system failed (disk full, permissions).
int PublishExitCode(const base::PublishError& error);

/// Begins publishing the output folder `target` for `writer` ("tidepool expand"); on failure
/// prints why and sets `*exit_code` (PublishExitCode) and returns null.
std::unique_ptr<base::FolderPublisher> BeginPublishing(const std::filesystem::path& target,
                                                       const std::string& writer, int* exit_code);

/// Writes `text` to `folder`/`file_name` atomically, refusing (exit kExitUsage, message printed
/// naming the file as not a tidepool `what`, nothing changed) to overwrite a file there whose
/// "schema" is not `schema`, unless the folder carries tidepool's marker. Returns kExitOk, or
/// kExitEnvironment (message printed) when the write fails. With `check_only`, writes nothing.
int WriteOwnJsonInto(const std::filesystem::path& folder, const std::string& file_name,
                     const std::string& schema, const std::string& what, const std::string& text,
                     bool check_only = false);

/// Writes the manifest `text` to `folder`/manifest.json atomically, refusing (exit kExitUsage,
/// message printed, nothing changed) to overwrite a manifest.json that is not tidepool's (its
/// "schema" is not kManifestSchema) unless the folder carries tidepool's marker. Returns kExitOk,
/// or kExitEnvironment (message printed) when the write fails. With `check_only`, writes nothing.
int WriteManifestInto(const std::filesystem::path& folder, const std::string& text,
                      bool check_only = false);

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

/// Parses a whole number in [min, max] for option `flag`, refusing signs, fractions, exponents
/// and values that overflow; on failure prints "error: FLAG must be a whole number from MIN to
/// MAX[ HINT], not 'TEXT'" and returns false.
bool ParseCountOption(std::string_view flag, const std::string& text, std::uint64_t min,
                      std::uint64_t max, std::string_view hint, std::uint64_t* value);

/// How many valid variants a command may expand, and how many pruned combinations it lists.
struct MatrixLimits {
    std::optional<std::string> max_variants;  // --max-variants as typed; none: the file's
    bool allow_large_matrix = false;  // --allow-large-matrix: limits above kVariantCeiling
    std::uint64_t pruned_limit = 0;   // pruned combinations to list (expand --pruned)
};

/// Adds --max-variants and --allow-large-matrix to `command`, writing into `limits`.
void AddMatrixLimitOptions(CLI::App* command, MatrixLimits* limits);

/// Loads `config_path` and expands it (to at most --max-variants valid variants, or the file's
/// own max_variants), printing every diagnostic; fails through exit_code kExitUsage (and no
/// config) when --max-variants is out of range, the file does not load or the expansion has
/// errors.
LoadedMatrix LoadAndExpand(const std::string& config_path, const MatrixLimits& limits = {});

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

/// The timing flags `render`, `bench` and `run` share (the one timing engine's settings).
struct TimingFlags {
    double resolution = 1.5;  // half-width of a comparison's 95% interval, percent points
    int min_pairs = 20;
    int max_pairs = 400;
    int coarse_frames = 3;
    int warmup = 2;
    int workers = 0;  // rendering threads; 0: one per core
    int threads = 0;  // LP_NUM_THREADS: 0 renders on each worker's own thread
};

/// Adds --resolution, --min-pairs, --max-pairs, --coarse-frames, --warmup, --workers and
/// --threads to `command`, writing into `flags`.
void AddTimingFlags(CLI::App* command, TimingFlags* flags);

/// Prints why `flags` cannot be used, naming the option and its range, and returns false.
bool CheckTimingFlags(const TimingFlags& flags);

/// Sets LP_NUM_THREADS from `flags` (llvmpipe reads it when the first context is created) and
/// fills the timing part of `run`: rule, frames, workers and a factory for the workers'
/// contexts on `backend`. Comparisons are every pair of ComparedPresetPairs() whose two presets
/// are both among `run->configurations`.
void ApplyTimingFlags(const TimingFlags& flags, runner::BackendKind backend,
                      runner::RunOptions* run);

/// "42s" or "3m05s". Never fails.
std::string FormatDuration(double seconds);

/// A render progress callback printing to stderr: on a terminal one line rewritten in place
/// (FinishProgress ends it), in a log a plain line on every stage change and at most every 10
/// seconds. Never fails.
runner::ProgressCallback MakeProgressPrinter();

/// Ends the line a terminal progress printer left open. Never fails.
void FinishProgress();

/// What the run records about the machine and build for `command`, reading `config_path`'s
/// folder for the git revision.
runner::HostInfo DescribeHost(const std::string& command, const std::string& config_path);

}  // namespace tidepool::cli
