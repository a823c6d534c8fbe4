// What stands at a path, for the error when a regular file was wanted there.
#pragma once

#include <filesystem>
#include <string>

namespace tidepool::base {

/// "" when `path` names a regular file (through links); otherwise why it is none, as an error
/// reads after the path: "no such file", "is a folder, not a file", "is a device, a named pipe or
/// a socket, not a regular file", or the system's words (a loop of symbolic links: "Too many
/// levels of symbolic links"). Never blocks: nothing is opened.
std::string WhyNotARegularFile(const std::filesystem::path& path);

}  // namespace tidepool::base
