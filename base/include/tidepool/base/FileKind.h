// What stands at a path, for the error when a regular file was wanted there.
#pragma once

#include <filesystem>
#include <string>

#include <sys/types.h>

namespace tidepool::base {

/// "" for a regular file's mode (st_mode); otherwise what the node is, as an error reads after
/// the path: "is a folder, not a file", "is a FIFO (named pipe), not a regular file", "is a
/// socket, not a regular file", "is a device, not a regular file".
std::string KindProblem(mode_t mode);

/// "" when `path` names a regular file (through links); otherwise why it is none: "no such
/// file", KindProblem's words, or the system's (a loop of symbolic links: "Too many levels of
/// symbolic links"). Never blocks: nothing is opened.
std::string WhyNotARegularFile(const std::filesystem::path& path);

}  // namespace tidepool::base
