#include "CliSupport.h"

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

LoadedMatrix LoadAndExpand(const std::string& config_path, std::uint64_t max_variants) {
    LoadedMatrix loaded;
    ConfigResult config = LoadVariantConfig(config_path);
    PrintDiagnostics(config.diagnostics);
    if (!config.config) {
        loaded.exit_code = kExitUsage;
        return loaded;
    }
    ExpansionOptions expansion_options;
    expansion_options.max_variants =
            max_variants != 0 ? max_variants : config.config->max_variants;
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
