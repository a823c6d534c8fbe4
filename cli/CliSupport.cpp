#include "CliSupport.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <thread>
#include <utility>

#include "Commands.h"
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace tidepool::cli {

int PublishExitCode(const base::PublishError& error) {
    return error.failure == base::PublishFailure::kRefused ? kExitUsage : kExitEnvironment;
}

std::unique_ptr<base::FolderPublisher> BeginPublishing(const std::filesystem::path& target,
                                                       const std::string& writer, int* exit_code) {
    base::PublishError begin;
    std::unique_ptr<base::FolderPublisher> publisher =
            base::FolderPublisher::Begin(target, writer, &begin);
    if (!publisher) {
        std::fprintf(stderr, "error: %s\n", begin.message.c_str());
        *exit_code = PublishExitCode(begin);
    }
    return publisher;
}

int WriteOwnJsonInto(const std::filesystem::path& folder, const std::string& file_name,
                     const std::string& schema, const std::string& what, const std::string& text,
                     bool check_only) {
    const std::filesystem::path path = folder / file_name;
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !base::IsTidepoolOutput(folder)) {
        // A file named manifest.json is common (web apps, packages); the schema key inside it
        // is what says it is ours.
        std::ifstream in(path, std::ios::binary);
        const nlohmann::json existing = nlohmann::json::parse(in, nullptr, false);
        const bool ours =
                existing.is_object() && existing.contains("schema") && existing["schema"] == schema;
        if (!ours) {
            std::fprintf(stderr,
                         "error: %s: exists and is not a tidepool %s (no \"schema\": "
                         "\"%s\"); nothing was changed. Choose another --out folder, or "
                         "move the file yourself.\n",
                         path.c_str(), what.c_str(), schema.c_str());
            return kExitUsage;
        }
    }
    if (check_only) {
        return kExitOk;
    }
    if (std::string error = base::WriteFileAtomically(path, text); !error.empty()) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return kExitEnvironment;
    }
    return kExitOk;
}

int WriteManifestInto(const std::filesystem::path& folder, const std::string& text,
                      bool check_only) {
    return WriteOwnJsonInto(folder, "manifest.json", kManifestSchema, "manifest", text, check_only);
}

int ParseAndRun(CLI::App& app, int argc, char** argv, const int& exit_code) {
    app.require_subcommand(1);
    app.set_version_flag("--version", kVersionText);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        // CLI11 returns 0 for --help/--version and its own codes for usage errors; ours is 2.
        return code == 0 ? kExitOk : kExitUsage;
    }
    return exit_code;
}

void PrintDiagnostics(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics) {
        std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
    }
}

std::string CpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) {
                return line.substr(line.find_first_not_of(' ', colon + 1));
            }
        }
    }
    return "unknown";
}

std::string GitRevision(const std::filesystem::path& folder) {
    const std::string command =
            fmt::format("git -C '{}' rev-parse HEAD 2>/dev/null", folder.string());
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return "unknown";
    }
    char buffer[128] = {0};
    std::string revision;
    if (std::fgets(buffer, sizeof buffer, pipe) != nullptr) {
        revision = buffer;
    }
    pclose(pipe);
    while (!revision.empty() && (revision.back() == '\n' || revision.back() == '\r')) {
        revision.pop_back();
    }
    return revision.empty() ? "unknown" : revision;
}

bool ParseSize(const std::string& text, int min_side, int* width, int* height, int max_side) {
    const auto x = text.find('x');
    if (x == std::string::npos) {
        return false;
    }
    try {
        std::size_t used = 0;
        *width = std::stoi(text.substr(0, x), &used);
        if (used != x) {
            return false;
        }
        *height = std::stoi(text.substr(x + 1), &used);
        if (used != text.size() - x - 1) {
            return false;
        }
    } catch (const std::exception&) {
        return false;
    }
    return *width >= min_side && *height >= min_side && *width <= max_side && *height <= max_side;
}

bool ParseSizeOption(std::string_view flag, const std::string& text, int min_side, int* width,
                     int* height, int max_side) {
    if (ParseSize(text, min_side, width, height, max_side)) {
        return true;
    }
    std::fprintf(stderr, "error: %.*s must be WxH with %d..%d each, not '%s'\n",
                 static_cast<int>(flag.size()), flag.data(), min_side, max_side, text.c_str());
    return false;
}

bool ParseCountOption(std::string_view flag, const std::string& text, std::uint64_t min,
                      std::uint64_t max, std::string_view hint, std::uint64_t* value) {
    // Digits only: CLI11 and strtoull would wrap "-1" into 2^64-1 and accept "1e3" as 1.
    std::uint64_t parsed = 0;
    const char* end = text.data() + text.size();
    const bool digits = !text.empty() && std::all_of(text.begin(), text.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    if (digits && std::from_chars(text.data(), end, parsed).ec == std::errc() && parsed >= min &&
        parsed <= max) {
        *value = parsed;
        return true;
    }
    std::fprintf(stderr, "error: %.*s must be a whole number from %llu to %llu%s%.*s, not '%s'\n",
                 static_cast<int>(flag.size()), flag.data(), static_cast<unsigned long long>(min),
                 static_cast<unsigned long long>(max), hint.empty() ? "" : " ",
                 static_cast<int>(hint.size()), hint.data(), text.c_str());
    return false;
}

void AddMatrixLimitOptions(CLI::App* command, MatrixLimits* limits) {
    // A callback, not a bound string, so that `--max-variants=` (empty) is refused, not taken
    // for "not given".
    command->add_option_function<std::string>(
            "--max-variants", [limits](const std::string& text) { limits->max_variants = text; },
            fmt::format("refuse matrices with more valid variants than this, 1..{} "
                        "(default: the file's max_variants, else 4096)",
                        kVariantCeiling));
    command->add_flag("--allow-large-matrix", limits->allow_large_matrix,
                      fmt::format("allow a limit above {} valid variants (up to {})",
                                  kVariantCeiling, kLargeVariantCeiling));
}

LoadedMatrix LoadAndExpand(const std::string& config_path, const MatrixLimits& limits) {
    LoadedMatrix loaded;
    ExpansionOptions expansion_options;
    expansion_options.allow_large_matrix = limits.allow_large_matrix;
    expansion_options.pruned_limit = limits.pruned_limit;
    if (limits.max_variants) {
        const std::uint64_t ceiling =
                limits.allow_large_matrix ? kLargeVariantCeiling : kVariantCeiling;
        const std::string hint =
                limits.allow_large_matrix
                        ? std::string()
                        : fmt::format("(up to {} with --allow-large-matrix)", kLargeVariantCeiling);
        if (!ParseCountOption("--max-variants", *limits.max_variants, 1, ceiling, hint,
                              &expansion_options.max_variants)) {
            loaded.exit_code = kExitUsage;
            return loaded;
        }
        expansion_options.limit_origin = "--max-variants";
    }
    ConfigResult config = LoadVariantConfig(config_path);
    PrintDiagnostics(config.diagnostics);
    if (!config.config) {
        loaded.exit_code = kExitUsage;
        return loaded;
    }
    if (!limits.max_variants) {
        expansion_options.max_variants = config.config->max_variants;
        if (!config.config->max_variants_where.file.empty()) {
            expansion_options.limit_origin = "max_variants";
            expansion_options.limit_where = config.config->max_variants_where;
        }
    }
    loaded.expansion = ExpandVariants(*config.config, expansion_options);
    PrintDiagnostics(loaded.expansion.diagnostics);
    if (HasErrors(loaded.expansion.diagnostics)) {
        loaded.exit_code = kExitUsage;
        return loaded;
    }
    loaded.config = std::move(config.config);
    return loaded;
}

std::string NormaliseOutPath(std::string path) {
    if (path.empty()) {
        return path;
    }
    std::filesystem::path normal = std::filesystem::path(path).lexically_normal();
    if (!normal.has_filename() && normal.has_relative_path()) {
        normal = normal.parent_path();  // "DIR/" → "DIR"; "/" stays the root
    }
    return normal.string();
}

bool CheckDefineOptions(const std::vector<std::string>& defines) {
    for (const std::string& define : defines) {
        const std::size_t equals = define.find('=');
        const std::string name = define.substr(0, equals);
        if (!IsValidDefineName(name)) {
            std::fprintf(stderr,
                         "error: -D '%s': '%s' is not a valid define name: use letters, digits "
                         "and _, start with a letter, no 'GL_' prefix and no '__'\n",
                         define.c_str(), name.c_str());
            return false;
        }
        if (equals != std::string::npos &&
            define.find_first_of("\r\n", equals) != std::string::npos) {
            std::fprintf(stderr,
                         "error: -D '%s': the value must be a single line (a newline would add "
                         "preprocessor lines)\n",
                         name.c_str());
            return false;
        }
    }
    return true;
}

void AddCacheFlags(CLI::App* command, CacheFlags* flags) {
    CLI::Option* folder = command->add_option(
            "--cache", flags->folder,
            "folder of the validation cache (default: $XDG_CACHE_HOME/tidepool, else "
            "~/.cache/tidepool; at most 64 MiB, least recently used entries evicted)");
    command->add_flag("--no-cache", flags->off, "neither read nor write the validation cache")
            ->excludes(folder);
}

std::unique_ptr<base::ContentCache> OpenCache(const CacheFlags& flags) {
    if (flags.off) {
        return nullptr;
    }
    if (!flags.folder.empty()) {
        return std::make_unique<base::ContentCache>(flags.folder);
    }
    // The XDG base directory rules: a relative $XDG_CACHE_HOME is invalid and ignored.
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg != nullptr && xdg[0] == '/') {
        return std::make_unique<base::ContentCache>(std::filesystem::path(xdg) / "tidepool");
    }
    const char* home = std::getenv("HOME");
    if (home != nullptr && home[0] == '/') {
        return std::make_unique<base::ContentCache>(std::filesystem::path(home) / ".cache" /
                                                    "tidepool");
    }
    return nullptr;
}

void WarnAboutCache(const base::ContentCache* cache) {
    if (cache == nullptr) {
        return;
    }
    const base::ContentCacheStats stats = cache->Stats();
    if (!stats.error.empty()) {
        std::fprintf(stderr,
                     "warning: validation cache %s: %s (results were not kept; use "
                     "--cache DIR or --no-cache)\n",
                     cache->Folder().c_str(), stats.error.c_str());
    }
}

int DefaultJobs() {
    const unsigned cores = std::thread::hardware_concurrency();
    return cores == 0 ? 1 : static_cast<int>(cores);
}

}  // namespace tidepool::cli
