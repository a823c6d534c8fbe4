// Small pieces every `tidepool` command shares: printing diagnostics, reading the host, sizes.
// Nothing here needs GL: the GL commands' own pieces are in GlCliSupport.h.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ContentCache.h"
#include "tidepool/base/FolderPublisher.h"

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

/// Parses `argv` into `app` (whose command callbacks store `exit_code`) and returns the process
/// exit code: 0 for --help/--version, kExitUsage for a usage error (CLI11's message printed),
/// else what the command stored.
int ParseAndRun(CLI::App& app, int argc, char** argv, const int& exit_code);

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
    bool allow_large_matrix = false;          // --allow-large-matrix: limits above kVariantCeiling
    std::uint64_t pruned_limit = 0;           // pruned combinations to list (expand --pruned)
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

/// --cache DIR and --no-cache as a command received them.
struct CacheFlags {
    std::string folder;  // --cache; "" for the default folder
    bool off = false;    // --no-cache
};

/// Adds --cache DIR and --no-cache (mutually exclusive) to `command`, writing into `flags`.
void AddCacheFlags(CLI::App* command, CacheFlags* flags);

/// The validation cache the flags ask for: --cache DIR, else $XDG_CACHE_HOME/tidepool (when
/// absolute), else $HOME/.cache/tidepool; none with --no-cache or when no folder can be named.
std::unique_ptr<base::ContentCache> OpenCache(const CacheFlags& flags);

/// Prints "warning: validation cache DIR: ..." on stderr when the cache could not be written or
/// trimmed (validation itself is unaffected).
void WarnAboutCache(const base::ContentCache* cache);

/// Validation jobs when the user gives none: one per core (1 when unknown).
int DefaultJobs();

}  // namespace tidepool::cli
