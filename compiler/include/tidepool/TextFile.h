// Reading an input file the user named, refusing what is not a regular file before opening it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace tidepool {

/// A whole file read as bytes, or why it could not be.
struct TextFileRead {
    bool ok = false;
    std::string text;
    std::string error;  // e.g. "is a folder, not a file"; empty when ok
};

/// Reads a regular file. A missing path, a folder, a FIFO, a socket or a device is refused with a
/// message saying which, without blocking: a FIFO with no writer would block an open() forever.
/// So is a file of more than `max_bytes` (0: no bound), unread.
TextFileRead ReadTextFile(const std::filesystem::path& path, std::uint64_t max_bytes = 0);

/// The largest shader file read: 4 MiB, hundreds of times a large real shader. Checking one costs
/// about 70 bytes of memory per byte in the process that reads it before glslang's token limit
/// can refuse it (a 50 MB file took 3.35 GB).
inline constexpr std::uint64_t kMaxShaderFileBytes = std::uint64_t{4} << 20;

/// Drops a UTF-8 byte-order mark from the start of `text`, where an editor may have written it
/// unseen; it sits on line 1 before any newline, so line numbers stay right.
void DropByteOrderMark(std::string* text);

/// ReadTextFile for a shader, at most kMaxShaderFileBytes: a UTF-8 byte-order mark at the start is
/// dropped, as GL drivers and glslangValidator accept it; it sits on line 1 before any newline,
/// so line numbers stay right.
TextFileRead ReadShaderFile(const std::filesystem::path& path);

}  // namespace tidepool
