#include "tidepool/base/AtomicFile.h"

#include <cerrno>
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

}  // namespace

std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view content,
                                Durability durability) {
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
        return path.string() + ": cannot write: " + SystemError(errno);
    }
    auto fail = [&](const std::string& what, int error) {
        ::close(fd);
        ::unlink(temp.c_str());
        return path.string() + ": " + what + ": " + SystemError(error);
    };
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return fail("cannot write", errno);
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    // mkstemp creates 0600, but outputs are read by the user's other tools and web servers; 0644
    // is what the usual umask gives. (Reading the umask would mean setting it, which races with
    // other threads creating files.)
    if (::fchmod(fd, 0644) != 0) {
        return fail("cannot set permissions", errno);
    }
    if (durability == Durability::kSynced && ::fsync(fd) != 0) {
        return fail("cannot write", errno);
    }
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        return path.string() + ": cannot write: " + SystemError(error);
    }
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        return path.string() + ": cannot replace: " + SystemError(error);
    }
    if (durability == Durability::kSynced) {
        SyncFolder(folder);
    }
    return {};
}

}  // namespace tidepool::base
