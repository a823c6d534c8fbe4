#include "tidepool/TextFile.h"

#include "tidepool/base/FileKind.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tidepool {

TextFileRead ReadTextFile(const std::filesystem::path& path, std::uint64_t max_bytes) {
    TextFileRead read;
    // O_NONBLOCK: should the path turn into a FIFO between any check and the open, the open
    // still returns at once; fstat on the open descriptor then refuses it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        read.error = errno == ENOENT ? "no such file" : std::strerror(errno);
        return read;
    }
    struct stat info {};
    if (::fstat(fd, &info) != 0) {
        read.error = std::strerror(errno);
    } else {
        read.error = base::KindProblem(info.st_mode);
    }
    auto too_large = [&](std::uint64_t bytes) {
        return fmt::format("is {} bytes, more than the {} tidepool reads of such a file", bytes,
                           max_bytes);
    };
    if (read.error.empty() && max_bytes > 0 &&
        static_cast<std::uint64_t>(info.st_size) > max_bytes) {
        read.error = too_large(static_cast<std::uint64_t>(info.st_size));
    }
    if (read.error.empty()) {
        char buffer[65536];
        for (;;) {
            const ssize_t got = ::read(fd, buffer, sizeof buffer);
            if (got > 0) {
                read.text.append(buffer, static_cast<std::size_t>(got));
                if (max_bytes > 0 && read.text.size() > max_bytes) {  // it grew while read
                    read.error = too_large(read.text.size());
                    break;
                }
            } else if (got == 0) {
                read.ok = true;
                break;
            } else if (errno != EINTR) {
                read.error = std::strerror(errno);
                break;
            }
        }
    }
    ::close(fd);
    if (!read.ok) {
        read.text.clear();
    }
    return read;
}

void DropByteOrderMark(std::string* text) {
    if (text->rfind("\xEF\xBB\xBF", 0) == 0) {
        text->erase(0, 3);
    }
}

TextFileRead ReadShaderFile(const std::filesystem::path& path) {
    TextFileRead read = ReadTextFile(path, kMaxShaderFileBytes);
    DropByteOrderMark(&read.text);
    return read;
}

}  // namespace tidepool
