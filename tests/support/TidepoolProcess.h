// Running the tidepool binary (or any shell command) from a CLI test, as a user would.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace tidepool::testing {

/// What a command did: its exit code and output.
struct CommandResult {
    int exit_code = -1;
    std::string out;  // stdout (and stderr, where the command sends it there)
};

/// Runs a shell command and collects its stdout.
inline CommandResult RunShell(const std::string& command) {
    CommandResult result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
        result.out.append(buffer.data(), n);
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

/// The shell command that runs the tidepool binary with `args` in `cwd`, with `environment`
/// (NAME=VALUE words) set for it alone.
inline std::string TidepoolCommand(const std::string& args, const std::filesystem::path& cwd,
                                   const std::string& environment = "") {
    return "cd '" + cwd.string() + "' && " + environment + " '" + std::string(TIDEPOOL_BINARY) +
           "' " + args;
}

/// Runs the tidepool binary with `args` (a shell fragment) in `cwd`.
inline CommandResult RunTidepool(const std::string& args,
                                 const std::filesystem::path& cwd = TIDEPOOL_SOURCE_ROOT) {
    return RunShell(TidepoolCommand(args, cwd) + " 2>&1");
}

/// What a command did, stdout and stderr apart.
struct SplitResult {
    int exit_code = -1;
    std::string out;  // stdout alone
    std::string err;  // stderr alone
};

/// Runs the tidepool binary with `args` in `cwd`, keeping stdout and stderr apart (stderr goes
/// through a file, so a diagnostic can never be mistaken for JSON on stdout).
inline SplitResult RunTidepoolSplit(const std::string& args, const std::filesystem::path& cwd,
                                    const std::string& environment = "") {
    const std::filesystem::path err_file = cwd / ".tidepool-stderr";
    const CommandResult r =
            RunShell(TidepoolCommand(args, cwd, environment) + " 2>'" + err_file.string() + "'");
    SplitResult split{r.exit_code, r.out, {}};
    std::ifstream in(err_file, std::ios::binary);
    std::ostringstream err;
    err << in.rdbuf();
    split.err = err.str();
    std::filesystem::remove(err_file);
    return split;
}

}  // namespace tidepool::testing
