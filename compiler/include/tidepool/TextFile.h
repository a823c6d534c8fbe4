// Reading an input file the user named, refusing what is not a regular file before opening it.
#pragma once

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
TextFileRead ReadTextFile(const std::filesystem::path& path);

/// ReadTextFile for a shader: a UTF-8 byte-order mark at the start is dropped, as GL drivers and
/// glslangValidator accept it; it sits on line 1 before any newline, so line numbers stay right.
TextFileRead ReadShaderFile(const std::filesystem::path& path);

}  // namespace tidepool
