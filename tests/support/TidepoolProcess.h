// Running the tidepool binary (or any shell command) from a CLI test, as a user would.
#pragma once

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace tidepool::testing {

/// What a command did: its exit code, and its stdout and stderr apart, so a test can tell
/// diagnostics from data.
struct CommandResult {
    int exit_code = -1;
    std::string out;  // stdout alone
    std::string err;  // stderr alone
};

/// Runs a shell command and collects its stdout and its stderr apart. stderr goes through a
/// uniquely named temp file (read back and removed), so concurrent tests never share one and a
/// diagnostic can never be mistaken for JSON on stdout. A command that wants its streams merged
/// (a tool's log, not tidepool's output) says `2>&1` itself.
inline CommandResult RunShell(const std::string& command) {
    CommandResult result;
    std::string err_path =
            (std::filesystem::temp_directory_path() / "tidepool-stderr.XXXXXX").string();
    const int err_fd = ::mkstemp(err_path.data());
    if (err_fd < 0) {
        return result;
    }
    ::close(err_fd);
    FILE* pipe = ::popen(("{ " + command + "\n} 2>'" + err_path + "'").c_str(), "r");
    if (pipe != nullptr) {
        std::array<char, 4096> buffer{};
        std::size_t n = 0;
        while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
            result.out.append(buffer.data(), n);
        }
        const int status = ::pclose(pipe);
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        std::ifstream in(err_path, std::ios::binary);
        std::ostringstream err;
        err << in.rdbuf();
        result.err = err.str();
    }
    std::filesystem::remove(err_path);
    return result;
}

/// The shell command that runs the tidepool binary with `args` in `cwd`, with `environment`
/// (NAME=VALUE words) set for it alone.
inline std::string TidepoolCommand(const std::string& args, const std::filesystem::path& cwd,
                                   const std::string& environment = "") {
    return "cd '" + cwd.string() + "' && " + environment + " '" + std::string(TIDEPOOL_BINARY) +
           "' " + args;
}

/// Runs the tidepool binary with `args` (a shell fragment) in `cwd`, with `environment` set for
/// it alone, stdout and stderr apart.
inline CommandResult RunTidepool(const std::string& args,
                                 const std::filesystem::path& cwd = TIDEPOOL_SOURCE_ROOT,
                                 const std::string& environment = "") {
    return RunShell(TidepoolCommand(args, cwd, environment));
}

}  // namespace tidepool::testing
