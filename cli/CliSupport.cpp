#include "CliSupport.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "tidepool/Manifest.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/report/ReportModel.h"

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
        const bool ours = existing.is_object() && existing.contains("schema") &&
                          existing["schema"] == schema;
        if (!ours) {
            std::fprintf(stderr, "error: %s: exists and is not a tidepool %s (no \"schema\": "
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

void AddTimingFlags(CLI::App* command, TimingFlags* flags) {
    command->add_option("--resolution", flags->resolution,
                        "stop timing a comparison when its 95% interval is this narrow "
                        "(half-width, percent points of frame rate)")
        ->capture_default_str();
    command->add_option("--min-pairs", flags->min_pairs, "pairs of frames per comparison, at least")
        ->capture_default_str();
    command->add_option("--max-pairs", flags->max_pairs,
                        "pairs of frames per comparison, at most (the resolution reached is "
                        "reported)")
        ->capture_default_str();
    command->add_option("--coarse-frames", flags->coarse_frames,
                        "timed frames of each configuration on its own (the accuracy chart)")
        ->capture_default_str();
    command->add_option("--warmup", flags->warmup,
                        "untimed frames before a compared configuration is timed, per thread")
        ->capture_default_str();
    command->add_option("--workers", flags->workers,
                        "rendering threads, each with its own GL context (0: one per core)")
        ->capture_default_str();
    command->add_option("--threads", flags->threads,
                        "llvmpipe threads (LP_NUM_THREADS; 0 renders on each worker's thread, "
                        "timed on that thread's CPU clock)")
        ->capture_default_str();
}

bool CheckTimingFlags(const TimingFlags& flags) {
    if (!(flags.resolution > 0 && flags.resolution <= 50)) {
        std::fprintf(stderr, "error: --resolution must be above 0 and at most 50 percent points, "
                             "not %g\n",
                     flags.resolution);
        return false;
    }
    if (flags.min_pairs < base::kMinimumPairs || flags.max_pairs < flags.min_pairs ||
        flags.max_pairs > 100000) {
        std::fprintf(stderr, "error: --min-pairs must be at least %d and --max-pairs between "
                             "--min-pairs and 100000, not %d and %d\n",
                     base::kMinimumPairs, flags.min_pairs, flags.max_pairs);
        return false;
    }
    if (flags.coarse_frames < 1 || flags.warmup < 0 || flags.workers < 0 || flags.workers > 64 ||
        flags.threads < 0 || flags.threads > 64) {
        std::fprintf(stderr, "error: --coarse-frames must be at least 1, --warmup at least 0, "
                             "--workers and --threads between 0 and 64\n");
        return false;
    }
    return true;
}

void ApplyTimingFlags(const TimingFlags& flags, runner::BackendKind backend,
                      runner::RunOptions* run) {
    setenv("LP_NUM_THREADS", std::to_string(flags.threads).c_str(), 1);
    run->host.lp_num_threads = std::to_string(flags.threads);
    run->rule.resolution_points = flags.resolution;
    run->rule.min_pairs = flags.min_pairs;
    run->rule.max_pairs = flags.max_pairs;
    run->coarse_frames = flags.coarse_frames;
    run->warmup_frames = flags.warmup;
    run->workers = flags.workers > 0 ? flags.workers : DefaultJobs();
    run->make_context = [backend] { return runner::CreateGlContext(backend).context; };
    run->comparisons.clear();
    auto find = [&](const std::string& preset) -> std::optional<std::size_t> {
        for (std::size_t i = 0; i < run->configurations.size(); ++i) {
            const auto& presets = run->configurations[i].presets;
            if (std::find(presets.begin(), presets.end(), preset) != presets.end()) {
                return i;
            }
        }
        return std::nullopt;
    };
    for (const report::PresetPair& pair : report::ComparedPresetPairs()) {
        const std::optional<std::size_t> a = find(pair.baseline);
        const std::optional<std::size_t> b = find(pair.candidate);
        if (a && b && *a != *b) {
            run->comparisons.push_back({pair.label, *a, *b});
        }
    }
}

runner::HostInfo DescribeHost(const std::string& command, const std::string& config_path) {
    runner::HostInfo host;
    host.cpu_model = CpuModel();
    if (const char* threads = std::getenv("LP_NUM_THREADS"); threads != nullptr) {
        host.lp_num_threads = threads;
    }
#ifdef NDEBUG
    host.build_type = "release (NDEBUG)";
#else
    host.build_type = "debug (assertions on)";
#endif
    host.git_revision = GitRevision(std::filesystem::absolute(config_path).parent_path());
    host.command = command;
    return host;
}

std::string FormatDuration(double seconds) {
    const long total = static_cast<long>(seconds + 0.5);
    return total >= 60 ? fmt::format("{}m{:02}s", total / 60, total % 60)
                       : fmt::format("{}s", total);
}

runner::ProgressCallback MakeProgressPrinter() {
    struct State {
        bool terminal = isatty(fileno(stderr)) != 0;
        std::string last_stage;
        double last_print = -1e9;
    };
    auto state = std::make_shared<State>();
    return [state](const runner::RunProgress& p) {
        if (state->terminal) {
            std::fprintf(stderr, "\r\033[K[%3.0f%%] %-11s %s  ETA %s", p.percent, p.stage.c_str(),
                         p.configuration.c_str(), FormatDuration(p.eta_seconds).c_str());
            std::fflush(stderr);
        } else if (p.stage != state->last_stage || p.elapsed_seconds - state->last_print >= 10.0 ||
                   p.done == p.total) {
            std::fprintf(stderr, "[%3.0f%%] %s %s (elapsed %s, ETA %s)\n", p.percent,
                         p.stage.c_str(), p.configuration.c_str(),
                         FormatDuration(p.elapsed_seconds).c_str(),
                         FormatDuration(p.eta_seconds).c_str());
            state->last_print = p.elapsed_seconds;
        }
        state->last_stage = p.stage;
    };
}

void FinishProgress() {
    if (isatty(fileno(stderr)) != 0) {
        std::fprintf(stderr, "\n");
    }
}

}  // namespace tidepool::cli
