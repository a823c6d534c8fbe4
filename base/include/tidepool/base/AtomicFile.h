// Writing a file so that a reader, or the next run after a crash, never sees half of it.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace tidepool::base {

/// Writes `content` to `path` atomically and durably, creating parent folders: a uniquely named
/// temp file in the same folder (mkstemp), fsync, rename over `path`, fsync of the folder. Returns
/// "" on success, otherwise a message naming the path and the system error; on failure no temp
/// file is left and an earlier `path` is untouched.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace tidepool::base
