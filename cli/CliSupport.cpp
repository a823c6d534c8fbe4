#include "CliSupport.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "Commands.h"

namespace tidepool::cli {

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

bool ParseBackendOption(const std::string& text, runner::BackendKind* backend) {
    if (runner::ParseBackendKind(text, backend)) {
        return true;
    }
    std::fprintf(stderr, "error: --backend must be auto, egl or osmesa, not '%s'\n",
                 text.c_str());
    return false;
}

bool ParseCountOption(std::string_view flag, const std::string& text, std::uint64_t min,
                      std::uint64_t max, std::string_view hint, std::uint64_t* value) {
    // Digits only: CLI11 and strtoull would wrap "-1" into 2^64-1 and accept "1e3" as 1.
    std::uint64_t parsed = 0;
    const char* end = text.data() + text.size();
    const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return c >= '0' && c <= '9';
    });
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

int DefaultJobs() {
    const unsigned cores = std::thread::hardware_concurrency();
    return cores == 0 ? 1 : static_cast<int>(cores);
}

void AddFourierOptions(CLI::App* command, runner::FourierSettings* settings) {
    command
        ->add_option("--fourier-coefficients", settings->coefficients,
                     "REFLECTION_FOURIER: Fourier terms kept per water vertex, 1..8 "
                     "(a0, a1, b1, a2, b2, a3, b3, a4)")
        ->capture_default_str();
    command
        ->add_option("--fourier-directions", settings->directions,
                     "REFLECTION_FOURIER: directions the terrain is marched in per vertex (>= 3)")
        ->capture_default_str();
}

bool CheckFourierOptions(const runner::FourierSettings& settings) {
    const std::string error = runner::CheckFourierSettings(settings);
    if (!error.empty()) {
        std::fprintf(stderr,
                     "error: %s (set --fourier-coefficients 1..8 and --fourier-directions >= 3)\n",
                     error.c_str());
        return false;
    }
    return true;
}

}  // namespace tidepool::cli
