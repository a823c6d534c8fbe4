// Writing a file so that a reader, or the next run after a crash, never sees half of it.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace tidepool::base {

/// Whether a write must survive a power cut (kSynced: fsync of the file and its folder) or only a
/// process crash (kUnsynced: for caches, whose entries carry their own checksum and cost only a
/// recomputation when lost; fsync costs milliseconds per file).
enum class Durability { kSynced, kUnsynced };

/// Writes `content` to `path` atomically and (kSynced) durably, creating parent folders: a
/// uniquely named temp file in the same folder (mkstemp), fsync, rename over `path`, fsync of
/// the folder. Returns "" on success, otherwise a message naming the path and the system error;
/// on failure no temp file is left and an earlier `path` is untouched. A file replaced keeps its
/// permissions (a new one gets 0644). Where `path` is a symbolic link, the file it names is
/// replaced, never the link. Where it is a device, a named pipe or a socket (`/dev/stdout`, a
/// shell's process substitution), `content` is written to it as to a stream, with no rename
/// (which would put a file in the node's place); a named pipe that no process reads is an
/// error, not a wait.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view content,
                                Durability durability = Durability::kSynced);

}  // namespace tidepool::base
