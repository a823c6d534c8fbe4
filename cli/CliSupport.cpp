#include "CliSupport.h"

#include "tidepool/base/EditDistance.h"
#include "tidepool/pipeline/OutputFiles.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "Commands.h"
#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace tidepool::cli {

int PrintOutcome(const pipeline::Outcome& outcome) {
    PrintDiagnostics(outcome.diagnostics);
    return pipeline::ExitCode(outcome.status);
}

namespace {

// The subcommand is the first argument that is not an option (the top level has only flags).
// False, with the error printed, when that argument names no command of `app`: CLI11 would say
// only "A subcommand is required", without the word it did not take.
bool NamesACommand(CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view word = argv[i];
        if (!word.empty() && word[0] == '-') {
            continue;
        }
        std::vector<std::string> names;
        for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
            names.push_back(command->get_name());
        }
        if (std::find(names.begin(), names.end(), word) != names.end()) {
            return true;
        }
        std::string list;
        for (const std::string& name : names) {
            list += (list.empty() ? "" : ", ") + name;
        }
        // A word far longer than any command is no misspelling of one, and is shown cut.
        constexpr std::size_t kLongestShown = 64;
        const std::size_t limit = word.size() / 3 + 1;
        const std::string closest = base::ClosestName(word.substr(0, kLongestShown), names);
        const bool near =
                word.size() <= kLongestShown && base::EditDistance(word, closest) <= limit;
        std::fprintf(stderr,
                     "error: '%.*s%s' is not a tidepool command; %sthe commands are %s "
                     "(tidepool --help says what each does)\n",
                     static_cast<int>(std::min(word.size(), kLongestShown)), word.data(),
                     word.size() > kLongestShown ? "..." : "",
                     near ? fmt::format("did you mean '{}'? ", closest).c_str() : "", list.c_str());
        return false;
    }
    return true;
}

// False, after saying which, when an argument is empty ('' or `--out=`): no option of tidepool
// takes an empty value, and a script's unset variable (`--out "$OUTDIR"`) would otherwise be
// taken as no value at all: `expand --out ''` wrote nothing and exited 0.
bool NoEmptyArgument(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view word = argv[i];
        const bool empty_value = word.rfind("--", 0) == 0 && word.size() > 2 && word.back() == '=';
        if (!word.empty() && !empty_value) {
            continue;
        }
        const std::string what = empty_value ? fmt::format("'{}' gives an empty value", word)
                                 : i > 1 ? fmt::format("an empty argument after '{}'", argv[i - 1])
                                         : std::string("an empty first argument");
        std::fprintf(stderr,
                     "error: %s; no option takes one: give a value, or leave the option out (an "
                     "unset variable in a script?)\n",
                     what.c_str());
        return false;
    }
    return true;
}

}  // namespace

int ParseAndRun(CLI::App& app, int argc, char** argv, const int& exit_code) {
    if (!NoEmptyArgument(argc, argv) || !NamesACommand(app, argc, argv)) {
        return kExitUsage;
    }
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

std::string ForTerminal(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
            out += fmt::format("\\x{:02x}", byte);
        } else {
            out += c;
        }
    }
    return out;
}

void PrintDiagnostics(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& d : diagnostics) {
        const std::string line = ForTerminal(FormatDiagnostic(d)) + "\n";
        std::fwrite(line.data(), 1, line.size(), stderr);
    }
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
    if (pipeline::ParseWholeNumber(text, min, max, value)) {
        return true;
    }
    std::fprintf(stderr, "error: %s\n",
                 pipeline::WholeNumberError(flag, text, min, max, hint).c_str());
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

void AddJobsOption(CLI::App* command, int* jobs) {
    // Read as the other counts are (ParseCountOption's rules): CLI11's own conversion took
    // `0x2` for 2, and said "1e2 not in range 1 to 256".
    constexpr std::uint64_t kMostJobs = 256;
    command->add_option_function<std::string>(
            "-j,--jobs",
            [jobs](const std::string& text) {
                std::uint64_t value = 0;
                if (!pipeline::ParseWholeNumber(text, 1, kMostJobs, &value)) {
                    throw CLI::ValidationError(
                            "error: " +
                            pipeline::WholeNumberError("--jobs", text, 1, kMostJobs, ""));
                }
                *jobs = static_cast<int>(value);
            },
            fmt::format("worker processes, 1..{} (default: cores)", kMostJobs));
}

void AddMatrixFlags(CLI::App* command, std::string* config, bool* json, MatrixLimits* limits) {
    command->add_option("--config", *config, "variant matrix file")->capture_default_str();
    command->add_flag("--json", *json, "print JSON instead of text");
    AddMatrixLimitOptions(command, limits);
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

bool CheckReportName(const std::string& name, const std::vector<std::string>& taken) {
    const bool is_taken = std::find(taken.begin(), taken.end(), name) != taken.end();
    // A name past 255 bytes failed with "File name too long" (exit 3) after the whole report.
    constexpr std::size_t kLongestName = 255;
    if (name.size() > kLongestName) {
        std::fprintf(stderr, "error: --name must be a folder name of at most %zu bytes, not %zu\n",
                     kLongestName, name.size());
        return false;
    }
    if (name.empty() || name.find('/') != std::string::npos || name[0] == '.' || is_taken) {
        std::string others;
        for (const std::string& t : taken) {
            others += (others.empty() ? " other than '" : "' and '") + t;
        }
        std::fprintf(stderr, "error: --name must be a plain folder name%s, not '%s'\n",
                     others.empty() ? "" : (others + "'").c_str(), name.c_str());
        return false;
    }
    return true;
}

bool CheckDefineOptions(const std::vector<std::string>& defines) {
    std::set<std::string> names;
    for (const std::string& define : defines) {
        const std::size_t equals = define.find('=');
        const std::string name = define.substr(0, equals);
        // glslang's own words for these came as a compile error (exit code 1) at line -1.
        constexpr std::size_t kLongestName = 1024;  // glslang's longest token
        if (name.size() > kLongestName) {
            std::fprintf(stderr,
                         "error: -D '%.64s...': the name has %zu characters, more than the %zu "
                         "of glslang's longest token\n",
                         name.c_str(), name.size(), kLongestName);
            return false;
        }
        if (name == "defined") {
            std::fprintf(stderr,
                         "error: -D 'defined': 'defined' is the preprocessor's operator and "
                         "cannot be a macro name (GLSL ES §3.4)\n");
            return false;
        }
        if (!names.insert(name).second) {
            std::fprintf(stderr, "error: -D '%s' is given twice; keep one\n", name.c_str());
            return false;
        }
        if (equals != std::string::npos && define.find("/*", equals) != std::string::npos) {
            std::fprintf(stderr,
                         "error: -D '%s': the value may not hold '/*' (a comment it opens would "
                         "run on past the define)\n",
                         name.c_str());
            return false;
        }
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
        if (equals != std::string::npos && define.find('\\', equals) != std::string::npos) {
            std::fprintf(stderr,
                         "error: -D '%s': the value may not hold '\\', which GLSL ES has only "
                         "to continue a line (§3.1)\n",
                         name.c_str());
            return false;
        }
        const std::string_view value = equals == std::string::npos
                                               ? std::string_view()
                                               : std::string_view(define).substr(equals + 1);
        // glslang's limit holds for identifiers and numbers, the only long tokens GLSL ES has:
        // `1.0+1.0+...` is many short tokens, not one long one.
        std::size_t run = 0;
        for (char c : value) {
            const bool word =
                    std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
            run = word ? run + 1 : 0;
            if (run > kLongestName) {
                std::fprintf(stderr,
                             "error: -D '%s': the value holds a token of more than the %zu "
                             "characters of glslang's longest token\n",
                             name.c_str(), kLongestName);
                return false;
            }
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

}  // namespace tidepool::cli
