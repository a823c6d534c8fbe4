#include "tidepool/base/FileKind.h"

#include <cerrno>
#include <cstring>

#include <sys/stat.h>

namespace tidepool::base {

std::string KindProblem(mode_t mode) {
    if (S_ISDIR(mode)) {
        return "is a folder, not a file";
    }
    if (S_ISFIFO(mode)) {
        return "is a FIFO (named pipe), not a regular file";
    }
    if (S_ISSOCK(mode)) {
        return "is a socket, not a regular file";
    }
    if (S_ISCHR(mode) || S_ISBLK(mode)) {
        return "is a device, not a regular file";
    }
    return S_ISREG(mode) ? "" : "is not a regular file";
}

std::string WhyNotARegularFile(const std::filesystem::path& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
        return errno == ENOENT ? "no such file" : std::strerror(errno);
    }
    return KindProblem(info.st_mode);
}

}  // namespace tidepool::base
