// Running a command line through the shell, as a user would, for the CLI tests.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace tidepool::testing {

/// A finished command: its exit code (-1 when it did not exit normally) and its stdout.
struct ShellResult {
    int exit_code = -1;
    std::string out;
};

/// Runs `command` with /bin/sh and collects its stdout (redirect stderr in `command` to keep it).
inline ShellResult RunShellCommand(const std::string& command) {
    ShellResult result;
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

}  // namespace tidepool::testing
