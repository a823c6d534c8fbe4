// Writing outputs so that a reader never sees half a file: temp file in the same folder, then
// rename over the destination.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace tidepool {

/// Writes `content` to `path` atomically, creating parent folders; returns "" on success or a
/// message naming the file and the system error.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace tidepool
