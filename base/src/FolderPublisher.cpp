#include "tidepool/base/FolderPublisher.h"

#include "tidepool/base/AtomicFile.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tidepool::base {
namespace {

namespace fs = std::filesystem;

std::string ErrnoMessage(int error) {
    return std::error_code(error, std::generic_category()).message();
}

PublishError Io(std::string message) {
    return {PublishFailure::kIo, std::move(message)};
}

// "out/" and "out" name one folder; the staging name is built from the last component.
fs::path Normalised(const fs::path& target) {
    fs::path t = target.lexically_normal();
    while (!t.empty() && !t.has_filename() && t != t.root_path()) {
        t = t.parent_path();
    }
    return t;
}

fs::path ParentOf(const fs::path& target) {
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// ".<name>.staging." and ".<name>.old." followed by "<pid>.<6 mkdtemp characters>".
// Built by appending: GCC 12 warns falsely (-Wrestrict) about `"." + string`.
std::string Prefix(const fs::path& target, const char* kind) {
    std::string prefix(1, '.');
    prefix += target.filename().string();
    prefix += kind;
    return prefix;
}
std::string StagingPrefix(const fs::path& target) {
    return Prefix(target, ".staging.");
}
std::string OldPrefix(const fs::path& target) {
    return Prefix(target, ".old.");
}

void FsyncFolder(const fs::path& folder) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

// The owning process id of a leftover named `<prefix><pid>.XXXXXX`, or 0 when the name does not
// follow the pattern exactly (then it is not ours and is never touched).
pid_t OwnerOf(const std::string& name, const std::string& prefix) {
    if (name.compare(0, prefix.size(), prefix) != 0) {
        return 0;
    }
    const std::string rest = name.substr(prefix.size());
    const std::size_t dot = rest.find('.');
    if (dot == std::string::npos || dot == 0 || dot > 9 || rest.size() - dot - 1 != 6) {
        return 0;
    }
    pid_t pid = 0;
    for (std::size_t i = 0; i < dot; ++i) {
        if (rest[i] < '0' || rest[i] > '9') {
            return 0;
        }
        pid = pid * 10 + (rest[i] - '0');
    }
    return pid;
}

bool ProcessAlive(pid_t pid) {
    return ::kill(pid, 0) == 0 || errno == EPERM;
}

fs::path MakeUniqueFolder(const fs::path& parent, const std::string& prefix, int* error) {
    std::string name = (parent / (prefix + std::to_string(::getpid()) + ".XXXXXX")).string();
    if (::mkdtemp(name.data()) == nullptr) {
        *error = errno;
        return {};
    }
    // mkdtemp makes it 0700; published, it is read by the user's other tools and web servers, as
    // a folder the usual umask makes (WriteFileAtomically gives files 0644 for the same reason).
    if (::chmod(name.c_str(), 0755) != 0) {
        *error = errno;
        ::rmdir(name.c_str());
        return {};
    }
    return name;
}

}  // namespace

bool IsTidepoolOutput(const fs::path& folder) {
    std::ifstream in(folder / kOutputMarkerFile);
    std::string line;
    return in && std::getline(in, line) && line == kOutputMarkerLine;
}

std::optional<fs::path> FileInPlaceOfFolder(const fs::path& folder) {
    std::error_code ec;
    for (fs::path p = folder; !p.empty(); p = p.parent_path()) {
        if (fs::exists(p, ec)) {
            return fs::is_directory(p, ec) ? std::nullopt : std::optional<fs::path>(p);
        }
        if (p == p.parent_path()) {
            break;
        }
    }
    return std::nullopt;
}

PublishError CheckFolderPath(const fs::path& folder) {
    const std::optional<fs::path> file = FileInPlaceOfFolder(folder);
    if (!file) {
        return {};
    }
    return {PublishFailure::kRefused,
            (*file == folder ? "" : folder.string() + ": ") + file->string() +
                    " is a file, not a folder; nothing was changed. Choose another --out folder."};
}

PublishError CheckReplaceable(const fs::path& folder) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(folder, ec);
    if (ec == std::errc::not_a_directory) {
        return CheckFolderPath(folder);  // a file where one of its folders belongs
    }
    if (ec && ec != std::errc::no_such_file_or_directory) {
        return Io(folder.string() + ": cannot inspect: " + ec.message());
    }
    if (!fs::exists(status)) {
        return {};
    }
    if (!fs::is_directory(status)) {
        return {PublishFailure::kRefused,
                folder.string() +
                        ": exists and is not a folder; nothing was changed. Choose "
                        "another --out folder."};
    }
    if (IsTidepoolOutput(folder) || fs::is_empty(folder, ec)) {
        return {};
    }
    return {PublishFailure::kRefused,
            folder.string() + ": exists and was not written by tidepool (it has no " +
                    kOutputMarkerFile +
                    " marker); nothing was changed. Choose another --out "
                    "folder, or move or delete this one yourself."};
}

std::string WriteOutputMarker(const fs::path& folder, const std::string& writer) {
    return WriteFileAtomically(folder / kOutputMarkerFile,
                               std::string(kOutputMarkerLine) + "\nwritten by: " + writer +
                                       "\nThis folder is replaced whole by the next run; do not "
                                       "keep other files in it.\n");
}

int RemoveStaleStaging(const fs::path& raw_target) {
    const fs::path target = Normalised(raw_target);
    // A killed run's process id is gone; a live id on a folder older than this belongs to a
    // reused id, since no tidepool run lasts a week (the full default run takes about an hour).
    constexpr auto kMaxAge = std::chrono::hours(24 * 7);
    std::error_code ec;
    int removed = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(ParentOf(target), ec)) {
        const std::string name = entry.path().filename().string();
        pid_t owner = OwnerOf(name, StagingPrefix(target));
        if (owner == 0) {
            owner = OwnerOf(name, OldPrefix(target));
        }
        if (owner == 0 || owner == ::getpid()) {
            continue;
        }
        std::error_code time_ec;
        const auto age = fs::file_time_type::clock::now() - entry.last_write_time(time_ec);
        if (!ProcessAlive(owner) || (!time_ec && age > kMaxAge)) {
            std::error_code remove_ec;
            fs::remove_all(entry.path(), remove_ec);
            removed += remove_ec ? 0 : 1;
        }
    }
    return removed;
}

std::unique_ptr<FolderPublisher> FolderPublisher::Begin(const fs::path& raw_target,
                                                        const std::string& writer,
                                                        PublishError* error) {
    const fs::path target = Normalised(raw_target);
    *error = CheckReplaceable(target);
    if (error->Failed()) {
        return nullptr;
    }
    const fs::path parent = ParentOf(target);
    std::error_code ec;
    fs::path created;
    for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created = p;
        if (p == p.parent_path()) {
            break;
        }
    }
    fs::create_directories(parent, ec);
    if (ec) {
        *error = Io(parent.string() + ": cannot create folder: " + ec.message());
        return nullptr;
    }
    RemoveStaleStaging(target);
    int system_error = 0;
    fs::path staging = MakeUniqueFolder(parent, StagingPrefix(target), &system_error);
    if (staging.empty()) {
        *error = Io(target.string() +
                    ": cannot create a staging folder beside it: " + ErrnoMessage(system_error));
        return nullptr;
    }
    std::unique_ptr<FolderPublisher> publisher(new FolderPublisher(target, staging, writer));
    publisher->created_ = created;
    return publisher;
}

FolderPublisher::~FolderPublisher() {
    Abandon();
}

void FolderPublisher::Abandon() {
    if (!done_) {
        std::error_code ec;
        fs::remove_all(staging_, ec);
        done_ = true;
        // Innermost first; fs::remove leaves a folder that something else has meanwhile filled.
        if (!created_.empty()) {
            for (fs::path p = ParentOf(target_);; p = p.parent_path()) {
                if (!fs::remove(p, ec) || p == created_ || p == p.parent_path()) {
                    break;
                }
            }
        }
    }
}

PublishError FolderPublisher::Publish() {
    if (done_) {
        return Io(target_.string() + ": already published or abandoned");
    }
    if (std::string e = WriteOutputMarker(staging_, writer_); !e.empty()) {
        Abandon();
        return Io(e);
    }
    FsyncFolder(staging_);
    const fs::path parent = ParentOf(target_);
    // Each round either publishes or finds that a concurrent publisher changed the target
    // between two renames; a few rounds settle any realistic number of racing runs.
    for (int round = 0; round < 16; ++round) {
        if (PublishError check = CheckReplaceable(target_); check.Failed()) {
            Abandon();
            return check;
        }
        if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_NOREPLACE) ==
            0) {
            done_ = true;
            FsyncFolder(parent);
            return {};
        }
        int error = errno;
        if (error == EEXIST || error == ENOTEMPTY) {
            // Swapped in one step, so the target is never missing; the staging name then holds
            // the previous folder, which is deleted (a crash here leaves it as stale staging).
            if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(),
                            RENAME_EXCHANGE) == 0) {
                FsyncFolder(parent);
                std::error_code ec;
                fs::remove_all(staging_, ec);
                done_ = true;
                return {};
            }
            error = errno;
            if (error == ENOENT) {
                continue;  // the target vanished between the two renames: try again
            }
        }
        if (error != EINVAL && error != ENOSYS) {
            Abandon();
            return Io(target_.string() + ": cannot publish: " + ErrnoMessage(error));
        }
        // A file system without renameat2's flags: move the target aside, then rename.
        int mk_error = 0;
        const fs::path old = MakeUniqueFolder(parent, OldPrefix(target_), &mk_error);
        if (old.empty()) {
            Abandon();
            return Io(target_.string() + ": cannot publish: " + ErrnoMessage(mk_error));
        }
        if (::rename(target_.c_str(), old.c_str()) != 0 && errno != ENOENT) {
            const int rename_error = errno;
            std::error_code ec;
            fs::remove_all(old, ec);
            Abandon();
            return Io(target_.string() + ": cannot replace: " + ErrnoMessage(rename_error));
        }
        const bool published = ::rename(staging_.c_str(), target_.c_str()) == 0;
        const int publish_error = errno;
        std::error_code ec;
        fs::remove_all(old, ec);
        if (published) {
            done_ = true;
            FsyncFolder(parent);
            return {};
        }
        if (publish_error != EEXIST && publish_error != ENOTEMPTY) {
            Abandon();
            return Io(target_.string() + ": cannot publish: " + ErrnoMessage(publish_error));
        }
    }
    Abandon();
    return Io(target_.string() + ": cannot publish: other runs kept replacing it");
}

}  // namespace tidepool::base
