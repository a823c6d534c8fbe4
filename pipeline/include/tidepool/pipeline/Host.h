// What the stages ask of the machine they run on: its CPU, its cores, the source revision.
#pragma once

#include <filesystem>
#include <string>

namespace tidepool::pipeline {

/// The CPU's model name from /proc/cpuinfo, or "unknown".
std::string CpuModel();

/// `git rev-parse HEAD` in `folder`, or "unknown" outside a repository or without git.
std::string GitRevision(const std::filesystem::path& folder);

/// Worker threads or processes when the user gives none: one per core (1 when unknown).
int DefaultJobs();

}  // namespace tidepool::pipeline
