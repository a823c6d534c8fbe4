// What every benchmark needs and none of the libraries should offer: a wall clock, the smallest
// of repeated runs and a description of the machine and build, so that every printed figure can
// be read next to the conditions it was measured under. (The median is base::Median, the
// parallel loop base::ParallelFor.)
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern "C" char** environ;

namespace tidepool::bench {

/// Seconds since an arbitrary fixed point, from a monotonic clock (never jumps with NTP).
inline double NowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
}

/// CPU seconds this process has used so far, all threads together (user + system), so that a
/// figure can be checked against wall time when other work shares the machine.
inline double ProcessCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

/// The 1-, 5- and 15-minute load averages as /proc/loadavg states them ("unknown" elsewhere):
/// wall-clock figures taken on a loaded machine are slower than the code is.
inline std::string LoadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string one;
    std::string five;
    std::string fifteen;
    if (!(in >> one >> five >> fifteen)) {
        return "unknown";
    }
    return one + " " + five + " " + fifteen;
}

/// The hardware threads the OS reports; 1 when it cannot tell, so callers never start 0 workers.
inline int HardwareThreads() {
    const unsigned threads = std::thread::hardware_concurrency();
    return threads == 0 ? 1 : static_cast<int>(threads);
}

/// The smallest of `samples`; 0 when empty.
inline double Min(const std::vector<double>& samples) {
    return samples.empty() ? 0.0 : *std::min_element(samples.begin(), samples.end());
}

/// One line naming the machine and how this binary was built. The build type is inferred from
/// the compiler's own macros because CMake does not pass CMAKE_BUILD_TYPE into the code:
/// __OPTIMIZE__ means -O1 or higher, NDEBUG means asserts are off (Release, RelWithDebInfo).
inline std::string DescribeEnvironment() {
#if defined(__OPTIMIZE__)
    constexpr const char* optimised = "optimised";
#else
    constexpr const char* optimised = "NOT optimised (-O0: figures are not representative)";
#endif
#if defined(NDEBUG)
    constexpr const char* asserts = "asserts off";
#else
    constexpr const char* asserts = "asserts on";
#endif
#if defined(__clang__)
    const std::string compiler = fmt::format("clang {}", __clang_version__);
#elif defined(__GNUC__)
    const std::string compiler = fmt::format("gcc {}", __VERSION__);
#else
    const std::string compiler = "unknown compiler";
#endif
    return fmt::format("{} hardware threads, load average {}; build: {}, {}, {}", HardwareThreads(),
                       LoadAverage(), optimised, asserts, compiler);
}

/// One whole process as a user runs it: wall time from spawn to reap, its own peak resident set,
/// whether it exited 0, and its output.
struct ProcessRun {
    bool ok = false;  // exited with code 0
    int exit_code = -1;
    double wall_ms = 0;
    double rss_mb = 0;
    std::string output;     // stdout and stderr together
    std::string last_line;  // the output's last non-empty line
};

/// Runs `binary args...` (posix_spawn, no shell; found through PATH when `binary` has no
/// slash), reading its stdout and stderr to the end; wait4's rusage gives that child's peak RSS.
inline ProcessRun RunProcess(const std::string& binary, const std::vector<std::string>& args) {
    ProcessRun result;
    int pipe_fds[2];
    if (pipe(pipe_fds) != 0) {
        return result;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
    posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(binary.c_str()));
    for (const std::string& arg : args) {
        argv.push_back(const_cast<char*>(arg.c_str()));
    }
    argv.push_back(nullptr);
    const double start = NowSeconds();
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(pipe_fds[1]);
    if (spawned == 0) {
        char buffer[65536];
        ssize_t n = 0;
        while ((n = read(pipe_fds[0], buffer, sizeof buffer)) > 0) {
            result.output.append(buffer, static_cast<std::size_t>(n));
        }
    }
    close(pipe_fds[0]);
    if (spawned != 0) {
        return result;
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    result.wall_ms = (NowSeconds() - start) * 1000.0;
    result.rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.ok = result.exit_code == 0;
    std::string out = result.output;
    while (!out.empty() && out.back() == '\n') {
        out.pop_back();
    }
    const std::size_t newline = out.find_last_of('\n');
    result.last_line = out.substr(newline == std::string::npos ? 0 : newline + 1);
    return result;
}

/// The ROUNDS argument (argv[1], 1..max), `fallback` when absent; 0 after printing `usage` when
/// it is out of range.
inline int RoundsArgument(int argc, char** argv, int fallback, int max, const char* usage) {
    if (argc <= 1) {
        return fallback;
    }
    const int rounds = std::atoi(argv[1]);
    if (rounds < 1 || rounds > max) {
        std::fprintf(stderr, "usage: %s\n", usage);
        return 0;
    }
    return rounds;
}

/// A new, empty folder /tmp/tidepool-NAME-XXXXXX; an empty path (message printed) when it
/// cannot be made.
inline std::filesystem::path MakeTempFolder(const std::string& name) {
    std::string pattern = "/tmp/tidepool-" + name + "-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) {
        std::fprintf(stderr, "error: cannot create a temporary folder\n");
        return {};
    }
    return pattern;
}

/// "met" when `met`, else "NOT met": how every benchmark states a target.
inline const char* Verdict(bool met) {
    return met ? "met" : "NOT met";
}

}  // namespace tidepool::bench
