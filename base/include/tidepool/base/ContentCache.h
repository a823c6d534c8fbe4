// A folder of small results named by the digest of everything that decides them, shared by
// concurrent processes and bounded in size. Entries carry their own checksum: one that is
// truncated, overwritten or from another format is reported as corrupt and never trusted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace tidepool::base {

/// What a ContentCache did since it was made.
struct ContentCacheStats {
    std::uint64_t hits = 0;
    std::uint64_t misses = 0;   // absent or corrupt entries
    std::uint64_t corrupt = 0;  // entries that failed their checksum or format (also misses)
    std::uint64_t stored = 0;
    std::uint64_t evicted = 0;
    std::string error;  // the first failure to write or trim, "" when none
};

/// Entries live in `folder`/v1/<first two digits of the key>/<key>, each written to a temp file
/// and renamed into place (base/AtomicFile.h), so a concurrent reader sees a whole entry or none.
/// A failure to read is a miss and a failure to write is recorded in Stats().error: a cache that
/// does not work costs time, never a wrong result. Thread-safe.
class ContentCache {
public:
    /// 64 MiB holds the results of hundreds of variant matrices the size of the default one
    /// (about 0.5 MB of entries) while staying negligible on any disk.
    static constexpr std::uint64_t kDefaultMaxBytes = std::uint64_t{64} << 20;

    /// A cache in `folder` (created on the first Store) that Trim keeps under `max_bytes`.
    explicit ContentCache(std::filesystem::path folder, std::uint64_t max_bytes = kDefaultMaxBytes);

    /// The folder given at construction.
    const std::filesystem::path& Folder() const { return folder_; }

    /// The payload stored under `key` (lowercase hex, at least 8 digits), or none when absent,
    /// unreadable or corrupt (counted in Stats().corrupt; the next Store of the key replaces it).
    std::optional<std::string> Load(std::string_view key);

    /// True when the folder holds no entries at all (absent, unreadable, or never stored into), so
    /// that no Load can hit; a cache whose entries were all trimmed may still say false.
    bool Empty() const;

    /// Stores `payload` under `key` atomically (last writer wins; concurrent writers of one key
    /// store the same content, since the key names it).
    void Store(std::string_view key, std::string_view payload);

    /// Deletes the least recently used entries (oldest modification time; a hit refreshes it)
    /// and stale temp files until the folder holds at most 3/4 of the bound, when it holds more
    /// than the bound. Entries another process deletes first are skipped.
    void Trim();

    /// Counts and the first error, for the caller to print.
    ContentCacheStats Stats() const;

    /// The path of `key`'s entry (for tests and tools; it may not exist).
    std::filesystem::path EntryPath(std::string_view key) const;

private:
    void RecordError(const std::string& error);

    std::filesystem::path folder_;
    std::uint64_t max_bytes_;
    mutable std::mutex mutex_;
    ContentCacheStats stats_;
};

}  // namespace tidepool::base
