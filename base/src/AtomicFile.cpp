#include "tidepool/base/AtomicFile.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tidepool::base {
namespace {

std::string SystemError(int error) {
    return std::error_code(error, std::generic_category()).message();
}

// fsync of a folder makes a rename inside it survive a power cut, not only a process crash.
void SyncFolder(const std::filesystem::path& folder) {
    const int fd =
            ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

// Writes all of `content` to `fd`; 0 on success, else the errno of the failed write.
int WriteAll(int fd, std::string_view content) {
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return errno;
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    return 0;
}

// The file a write through `path` would change: `path` with its symbolic links followed. A
// dangling link gives the path it names, followed as far as it goes; no link gives `path`.
std::filesystem::path FollowLinks(const std::filesystem::path& path) {
    if (char* real = ::realpath(path.c_str(), nullptr); real != nullptr) {
        std::filesystem::path resolved(real);
        std::free(real);
        return resolved;
    }
    std::filesystem::path followed = path;
    for (int hops = 0; hops < 40; ++hops) {  // Linux's own limit on links followed, ELOOP
        std::error_code ec;
        if (!std::filesystem::is_symlink(std::filesystem::symlink_status(followed, ec))) {
            return followed;
        }
        const std::filesystem::path target = std::filesystem::read_symlink(followed, ec);
        if (ec) {
            return followed;
        }
        followed = target.is_absolute() ? target : followed.parent_path() / target;
    }
    return followed;
}

}  // namespace

std::string WriteFileAtomically(const std::filesystem::path& given, std::string_view content,
                                Durability durability) {
    // A device, a pipe or a socket (`--output-file /dev/stdout`, a process substitution) is
    // written as it is: renaming a file over it would replace the node itself, and a stream has
    // no earlier content to keep whole. Through a link, the file it names is replaced, not the
    // link.
    struct stat existing {};
    const bool exists = ::stat(given.c_str(), &existing) == 0;
    if (exists && !S_ISREG(existing.st_mode) && !S_ISDIR(existing.st_mode)) {
        // A pipe nobody reads would block the open for good: refused at once instead.
        const int fd = ::open(given.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
        if (fd < 0) {
            return given.string() + ": cannot write: " +
                   (errno == ENXIO && S_ISFIFO(existing.st_mode)
                            ? std::string("a named pipe no process is reading")
                            : SystemError(errno));
        }
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
        const int error = WriteAll(fd, content);
        if (::close(fd) != 0 && error == 0) {
            return given.string() + ": cannot write: " + SystemError(errno);
        }
        return error == 0 ? std::string()
                          : given.string() + ": cannot write: " + SystemError(error);
    }
    const std::filesystem::path path = FollowLinks(given);
    std::error_code ec;
    const std::filesystem::path folder = path.parent_path();
    if (!folder.empty()) {
        std::filesystem::create_directories(folder, ec);
        if (ec) {
            return folder.string() + ": cannot create folder: " + ec.message();
        }
    }
    // Same folder as the destination, so the rename never crosses a file system; mkstemp makes the
    // name unique, so concurrent writers of one path never share (and truncate) a temp file.
    std::string name(1, '.');  // appended, not `"." + string`: GCC 12 warns falsely (-Wrestrict)
    name += path.filename().string();
    name += ".tmp.XXXXXX";
    std::string temp = (folder / name).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) {
        return given.string() + ": cannot write: " + SystemError(errno);
    }
    auto fail = [&](const std::string& what, int error) {
        ::close(fd);
        ::unlink(temp.c_str());
        return given.string() + ": " + what + ": " + SystemError(error);
    };
    if (const int error = WriteAll(fd, content); error != 0) {
        return fail("cannot write", error);
    }
    // mkstemp creates 0600, but outputs are read by the user's other tools and web servers; 0644
    // is what the usual umask gives. (Reading the umask would mean setting it, which races with
    // other threads creating files.) A file replaced keeps its own permissions.
    const mode_t mode = exists && S_ISREG(existing.st_mode) ? (existing.st_mode & 07777) : 0644;
    if (::fchmod(fd, mode) != 0) {
        return fail("cannot set permissions", errno);
    }
    if (durability == Durability::kSynced && ::fsync(fd) != 0) {
        return fail("cannot write", errno);
    }
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        return given.string() + ": cannot write: " + SystemError(error);
    }
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        return given.string() + ": cannot replace: " + SystemError(error);
    }
    if (durability == Durability::kSynced) {
        SyncFolder(folder);
    }
    return {};
}

}  // namespace tidepool::base
