#include "tidepool/base/ContentCache.h"

#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/Sha256.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <ctime>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tidepool::base {
namespace {

// The first line of every entry; a change of the layout below changes it (and the v1 folder).
constexpr std::string_view kMagic = "tidepool-cache-entry 1\n";

// A hit refreshes an entry's time for Trim only when it is older than this, so a warm run costs
// one system call per entry at most once an hour.
constexpr std::time_t kRefreshSeconds = 3600;

// Temp files older than this belong to a writer that died; younger ones may be mid-write.
constexpr std::time_t kStaleTempSeconds = 3600;

bool IsKey(std::string_view key) {
    return key.size() >= 8 && std::all_of(key.begin(), key.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// What a file in the cache's folder is to Trim, from its name in shard folder `shard`.
enum class CacheFile {
    kEntry,  // a key's entry: its name is the key, filed under the key's first two digits
    kTemp,   // an entry's temp file, as WriteFileAtomically names it: ".<key>.tmp.XXXXXX"
    kOther,  // anything else, which Trim neither counts nor deletes
};

CacheFile KindOf(std::string_view shard, std::string_view name) {
    if (IsKey(name) && name.substr(0, 2) == shard) {
        return CacheFile::kEntry;
    }
    constexpr std::string_view kTempInfix = ".tmp.";
    constexpr std::size_t kUniqueLength = 6;  // mkstemp's XXXXXX
    if (name.size() > 1 + kTempInfix.size() + kUniqueLength && name[0] == '.') {
        const std::string_view key =
                name.substr(1, name.size() - 1 - kTempInfix.size() - kUniqueLength);
        if (name.substr(1 + key.size(), kTempInfix.size()) == kTempInfix && IsKey(key) &&
            key.substr(0, 2) == shard) {
            return CacheFile::kTemp;
        }
    }
    return CacheFile::kOther;
}

// Whether `name` is a shard folder's: the first two digits of the keys filed in it.
bool IsShard(std::string_view name) {
    return name.size() == 2 && std::all_of(name.begin(), name.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// Reads the whole of `fd`; false on a read error or past `limit` bytes.
bool ReadAll(int fd, std::uint64_t limit, std::string* text) {
    char buffer[16384];
    for (;;) {
        if (text->size() > limit) {
            return false;
        }
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return false;
        }
        if (n == 0) {
            return true;
        }
        text->append(buffer, static_cast<std::size_t>(n));
    }
}

// Takes "<name> <value>\n" off the front of `text`.
bool TakeField(std::string_view* text, std::string_view name, std::string_view* value) {
    const std::size_t end = text->find('\n');
    if (end == std::string_view::npos || text->substr(0, name.size()) != name ||
        end <= name.size() || (*text)[name.size()] != ' ') {
        return false;
    }
    *value = text->substr(name.size() + 1, end - name.size() - 1);
    text->remove_prefix(end + 1);
    return true;
}

// The payload of an entry for `key`, or none when the text is not a whole, matching entry.
std::optional<std::string> ParseEntry(std::string_view text, std::string_view key) {
    if (text.substr(0, kMagic.size()) != kMagic) {
        return std::nullopt;
    }
    text.remove_prefix(kMagic.size());
    std::string_view stored_key;
    std::string_view size_text;
    std::string_view digest;
    if (!TakeField(&text, "key", &stored_key) || stored_key != key ||
        !TakeField(&text, "size", &size_text) || !TakeField(&text, "sha256", &digest)) {
        return std::nullopt;
    }
    std::size_t size = 0;
    const auto parsed =
            std::from_chars(size_text.data(), size_text.data() + size_text.size(), size);
    if (parsed.ec != std::errc() || parsed.ptr != size_text.data() + size_text.size() ||
        text.size() != size || Sha256Hex(text) != digest) {
        return std::nullopt;
    }
    return std::string(text);
}

}  // namespace

ContentCache::ContentCache(std::filesystem::path folder, std::uint64_t max_bytes)
    : folder_(std::move(folder)), max_bytes_(max_bytes) {}

std::filesystem::path ContentCache::EntryPath(std::string_view key) const {
    return folder_ / "v1" / std::string(key.substr(0, 2)) / std::string(key);
}

bool ContentCache::Empty() const {
    std::error_code error;
    const std::filesystem::directory_iterator entries(folder_ / "v1", error);
    return error || entries == std::filesystem::directory_iterator();
}

std::optional<std::string> ContentCache::Load(std::string_view key) {
    std::optional<std::string> payload;
    bool corrupt = false;
    if (IsKey(key)) {
        // An entry is a regular file no larger than the whole cache. Anything else in its place
        // (a link, a pipe, a device, a file grown past the bound) is corrupt and never read:
        // a pipe would block the open, /dev/zero or a huge sparse file would fill the memory.
        const int fd =
                ::open(EntryPath(key).c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW);
        corrupt = fd < 0 && errno == ELOOP;  // a symbolic link
        if (fd >= 0) {
            struct stat info {};
            std::string text;
            const bool readable = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) &&
                                  static_cast<std::uint64_t>(info.st_size) <= max_bytes_ &&
                                  ReadAll(fd, max_bytes_, &text);
            if (readable) {
                payload = ParseEntry(text, key);
            }
            corrupt = !payload;
            if (payload && std::time(nullptr) - info.st_mtime > kRefreshSeconds) {
                ::futimens(fd, nullptr);  // most recently used: the last to be trimmed
            }
            ::close(fd);
        }
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    ++(payload ? stats_.hits : stats_.misses);
    stats_.corrupt += corrupt ? 1 : 0;
    return payload;
}

void ContentCache::Store(std::string_view key, std::string_view payload) {
    if (!IsKey(key)) {
        RecordError("internal error: cache key '" + std::string(key) + "' is not hex");
        return;
    }
    std::string entry(kMagic);
    entry += "key ";
    entry += key;
    entry += "\nsize " + std::to_string(payload.size()) + "\nsha256 " + Sha256Hex(payload) + "\n";
    entry += payload;
    // Unsynced: after a power cut an entry may be lost or truncated, and the checksum turns a
    // truncated one into a miss; fsync would cost milliseconds per entry.
    // What is in an entry's place and no regular file (Load counts it corrupt) goes first: the
    // write would go through a link or into a device or pipe, and leave it in place.
    const std::filesystem::path path = EntryPath(key);
    struct stat existing {};
    if (::lstat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
    const std::string error = WriteFileAtomically(path, entry, Durability::kUnsynced);
    if (!error.empty()) {
        RecordError(error);
        return;
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.stored;
}

void ContentCache::Trim() {
    struct File {
        std::filesystem::path path;
        std::time_t mtime;
        std::uint64_t size;
    };
    std::vector<File> files;
    std::uint64_t total = 0;
    const std::time_t now = std::time(nullptr);
    // Only the cache's own files count, and only they are deleted: the folder may be one the
    // user also keeps other files in (`--cache .`), and a file not named as an entry is theirs.
    // Shard folders are read where they are, never through a link.
    std::error_code ec;
    for (std::filesystem::directory_iterator shard(folder_ / "v1", ec), end; !ec && shard != end;
         shard.increment(ec)) {
        const std::string shard_name = shard->path().filename().string();
        struct stat shard_info {};
        if (!IsShard(shard_name) || ::lstat(shard->path().c_str(), &shard_info) != 0 ||
            !S_ISDIR(shard_info.st_mode)) {
            continue;
        }
        std::error_code shard_ec;
        for (std::filesystem::directory_iterator it(shard->path(), shard_ec), last;
             !shard_ec && it != last; it.increment(shard_ec)) {
            const CacheFile kind = KindOf(shard_name, it->path().filename().string());
            struct stat info {};
            if (kind == CacheFile::kOther || ::lstat(it->path().c_str(), &info) != 0 ||
                !S_ISREG(info.st_mode)) {
                continue;
            }
            if (kind == CacheFile::kTemp && now - info.st_mtime > kStaleTempSeconds) {
                ::unlink(it->path().c_str());  // left by a writer that died
                continue;
            }
            const auto size = static_cast<std::uint64_t>(info.st_size);
            total += size;
            if (kind == CacheFile::kEntry) {
                files.push_back({it->path(), info.st_mtime, size});
            }
        }
    }
    if (total <= max_bytes_) {
        return;
    }
    // Down to 3/4 of the bound, so that a full cache is not trimmed again on every run.
    const std::uint64_t target = max_bytes_ / 4 * 3;
    std::sort(files.begin(), files.end(),
              [](const File& a, const File& b) { return a.mtime < b.mtime; });
    std::uint64_t evicted = 0;
    for (const File& file : files) {
        if (total <= target) {
            break;
        }
        if (::unlink(file.path.c_str()) == 0) {
            total -= file.size;
            ++evicted;
        } else if (errno == ENOENT) {
            total -= file.size;  // another process trimmed it first
        }
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    stats_.evicted += evicted;
}

ContentCacheStats ContentCache::Stats() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
}

void ContentCache::RecordError(const std::string& error) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stats_.error.empty()) {
        stats_.error = error;
    }
}

}  // namespace tidepool::base
