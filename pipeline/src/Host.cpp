#include "tidepool/pipeline/Host.h"

#include <cstdio>
#include <fstream>
#include <thread>

#include <fmt/format.h>

namespace tidepool::pipeline {

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
    // The folder goes to the shell in single quotes; a quote inside it is closed, escaped and
    // reopened ('\''), so no folder name can end the argument and run a command of its own.
    std::string quoted;
    for (const char c : folder.string()) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    const std::string command = fmt::format("git -C '{}' rev-parse HEAD 2>/dev/null", quoted);
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

int DefaultJobs() {
    const unsigned cores = std::thread::hardware_concurrency();
    return cores == 0 ? 1 : static_cast<int>(cores);
}

}  // namespace tidepool::pipeline
