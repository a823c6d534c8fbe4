#include "tidepool/base/ContentCache.h"
#include "tidepool/base/Sha256.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "TempDir.h"
#include <sys/stat.h>

namespace tidepool::base {
namespace {

using testing::TempDir;

std::string EntryKey(const std::string& name) {
    return Sha256Hex(name);
}

std::string ReadBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Stores `count` entries of `payload` under EntryKey("0"), EntryKey("1"), ...; entry i was last
// used count - i hours ago, so entry 0 is the least recently used.
void StoreAged(ContentCache& cache, int count, const std::string& payload) {
    const auto now = std::filesystem::file_time_type::clock::now();
    for (int i = 0; i < count; ++i) {
        const std::string key = EntryKey(std::to_string(i));
        cache.Store(key, payload);
        std::filesystem::last_write_time(cache.EntryPath(key), now - std::chrono::hours(count - i));
    }
}

TEST(ContentCacheTest, StoredPayloadIsLoadedBackByteForByte) {
    TempDir dir;
    ContentCache cache(dir.Path() / "cache");
    const std::string payload("binary\0payload\nwith\xff bytes", 26);
    cache.Store(EntryKey("a"), payload);
    EXPECT_EQ(cache.Load(EntryKey("a")), payload);
    const ContentCacheStats stats = cache.Stats();
    EXPECT_EQ(stats.stored, 1U);
    EXPECT_EQ(stats.hits, 1U);
    EXPECT_EQ(stats.misses, 0U);
    EXPECT_EQ(stats.error, "");
}

TEST(ContentCacheTest, AbsentKeyIsAMissAndNotCorrupt) {
    TempDir dir;
    ContentCache cache(dir.Path());
    EXPECT_FALSE(cache.Load(EntryKey("absent")));
    EXPECT_EQ(cache.Stats().misses, 1U);
    EXPECT_EQ(cache.Stats().corrupt, 0U);
}

TEST(ContentCacheTest, IsEmptyUntilTheFirstStore) {
    TempDir dir;
    ContentCache absent(dir.Path() / "not-yet");
    EXPECT_TRUE(absent.Empty());
    std::filesystem::create_directories(dir.Path() / "made" / "v1");
    ContentCache made(dir.Path() / "made");
    EXPECT_TRUE(made.Empty());
    made.Store(EntryKey("a"), "payload");
    EXPECT_FALSE(made.Empty());
    EXPECT_FALSE(ContentCache(dir.Path() / "made").Empty());
}

TEST(ContentCacheTest, KeyThatIsNotHexIsNeverAPath) {
    TempDir dir;
    ContentCache cache(dir.Path());
    cache.Store("../../escape", "x");
    EXPECT_NE(cache.Stats().error, "");
    EXPECT_FALSE(cache.Load("../../escape"));
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "escape"));
}

// Every way an entry can go bad: each is a miss counted as corrupt, never a wrong payload, and
// the next Store of the key makes it whole again.
TEST(ContentCacheTest, DamagedEntryIsCorruptAndTheNextStoreReplacesIt) {
    const std::string payload = "the payload of a stage";
    struct Damage {
        const char* why;
        std::string (*apply)(const std::string& entry);
    };
    const Damage damages[] = {
            {"truncated", [](const std::string& e) { return e.substr(0, e.size() - 3); }},
            {"payload byte flipped",
             [](const std::string& e) {
                 std::string d = e;
                 d.back() = static_cast<char>(d.back() ^ 1);
                 return d;
             }},
            {"bytes appended", [](const std::string& e) { return e + "junk"; }},
            {"empty file", [](const std::string&) { return std::string(); }},
            {"another format",
             [](const std::string& e) {
                 std::string d = e;
                 d[0] = 'x';
                 return d;
             }},
    };
    for (const Damage& damage : damages) {
        SCOPED_TRACE(damage.why);
        TempDir dir;
        ContentCache cache(dir.Path());
        cache.Store(EntryKey("k"), payload);
        const std::filesystem::path path = cache.EntryPath(EntryKey("k"));
        WriteBytes(path, damage.apply(ReadBytes(path)));
        EXPECT_FALSE(cache.Load(EntryKey("k")));
        EXPECT_EQ(cache.Stats().corrupt, 1U);
        cache.Store(EntryKey("k"), payload);
        EXPECT_EQ(cache.Load(EntryKey("k")), payload);
    }
}

// Before, an entry's file was opened and read whole whatever it was: a pipe in its place blocked
// the open for good, and a link to /dev/zero or a huge sparse file read until memory ran out.
TEST(ContentCacheTest, WhatIsNoRegularFileOrLargerThanTheCacheIsCorruptUnreadAndReplaced) {
    const std::string payload = "the payload of a link";
    struct Node {
        const char* why;
        void (*make)(const std::filesystem::path& path);
    };
    const Node nodes[] = {
            {"a named pipe", [](const std::filesystem::path& p) { ::mkfifo(p.c_str(), 0600); }},
            {"a link to /dev/zero",
             [](const std::filesystem::path& p) {
                 std::filesystem::create_symlink("/dev/zero", p);
             }},
            {"a folder",
             [](const std::filesystem::path& p) { std::filesystem::create_directory(p); }},
            {"a sparse file past the bound",
             [](const std::filesystem::path& p) {
                 WriteBytes(p, "x");
                 std::filesystem::resize_file(p, std::uintmax_t{1} << 20);
             }},
    };
    for (const Node& node : nodes) {
        SCOPED_TRACE(node.why);
        TempDir dir;
        ContentCache cache(dir.Path(), std::uint64_t{64} << 10);
        cache.Store(EntryKey("k"), payload);
        const std::filesystem::path path = cache.EntryPath(EntryKey("k"));
        std::filesystem::remove(path);
        node.make(path);
        EXPECT_FALSE(cache.Load(EntryKey("k")));
        EXPECT_EQ(cache.Stats().corrupt, 1U);
        cache.Store(EntryKey("k"), payload);
        EXPECT_EQ(cache.Stats().error, "");
        EXPECT_EQ(cache.Load(EntryKey("k")), payload);
        EXPECT_FALSE(std::filesystem::is_symlink(path));
    }
}

TEST(ContentCacheTest, EntryOfAnotherKeyIsNotTrusted) {
    TempDir dir;
    ContentCache cache(dir.Path());
    cache.Store(EntryKey("a"), "payload of a");
    std::filesystem::create_directories(cache.EntryPath(EntryKey("b")).parent_path());
    std::filesystem::copy_file(cache.EntryPath(EntryKey("a")), cache.EntryPath(EntryKey("b")));
    EXPECT_FALSE(cache.Load(EntryKey("b")));
    EXPECT_EQ(cache.Stats().corrupt, 1U);
}

TEST(ContentCacheTest, TrimEvictsLeastRecentlyUsedEntriesUntilUnderTheBound) {
    TempDir dir;
    const std::string payload(1000, 'p');
    // Ten entries of about 1.1 kB under a 5 kB bound: Trim keeps the newest three (3/4 of 5 kB).
    ContentCache cache(dir.Path(), 5000);
    StoreAged(cache, 10, payload);
    cache.Trim();
    EXPECT_EQ(cache.Stats().evicted, 7U);
    for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(std::filesystem::exists(cache.EntryPath(EntryKey(std::to_string(i)))), i >= 7)
                << i;
    }
    cache.Trim();  // under the bound now: nothing more goes
    EXPECT_EQ(cache.Stats().evicted, 7U);
}

TEST(ContentCacheTest, TrimCountsAndDeletesOnlyTheCachesOwnFiles) {
    TempDir dir;
    const std::string payload(1000, 'p');
    ContentCache cache(dir.Path(), 2500);
    StoreAged(cache, 3, payload);
    const auto long_ago = std::filesystem::file_time_type::clock::now() - std::chrono::hours(48);
    const std::string key = EntryKey("0");
    const std::filesystem::path shard = cache.EntryPath(key).parent_path();
    // The user's files in the folder, old and large: neither counted nor deleted.
    const std::vector<std::filesystem::path> theirs = {
            dir.Path() / "v1" / "api" / "handler.py", dir.Path() / "v1" / "assets" / "big.bin",
            shard / "notes.txt", shard / ".hidden", shard / ("." + key + ".tmp.x")};
    for (const std::filesystem::path& path : theirs) {
        std::filesystem::create_directories(path.parent_path());
        WriteBytes(path, std::string(path.filename() == "big.bin" ? 100000 : 10, 'u'));
        std::filesystem::last_write_time(path, long_ago);
    }
    // An entry's temp file left by a writer that died an hour ago or more: the cache's own.
    const std::filesystem::path stale = shard / ("." + key + ".tmp.AbC123");
    WriteBytes(stale, "half an entry");
    std::filesystem::last_write_time(stale, long_ago);
    // A shard reached through a link is not the cache's: what it links to is left alone.
    const std::filesystem::path elsewhere = dir.Path() / "elsewhere";
    std::filesystem::create_directories(elsewhere);
    WriteBytes(elsewhere / EntryKey("x"), payload + payload + payload);
    std::filesystem::last_write_time(elsewhere / EntryKey("x"), long_ago);
    std::filesystem::create_directory_symlink(elsewhere,
                                              dir.Path() / "v1" / EntryKey("x").substr(0, 2));

    cache.Trim();
    for (const std::filesystem::path& path : theirs) {
        EXPECT_TRUE(std::filesystem::exists(path)) << path;
    }
    EXPECT_TRUE(std::filesystem::exists(elsewhere / EntryKey("x")));
    EXPECT_FALSE(std::filesystem::exists(stale));
    // Three entries of about 1.1 kB over a 2.5 kB bound, trimmed to 3/4 of it: the two oldest
    // go, as they would without the rest.
    EXPECT_EQ(cache.Stats().evicted, 2U);
    EXPECT_FALSE(std::filesystem::exists(cache.EntryPath(EntryKey("1"))));
    EXPECT_TRUE(std::filesystem::exists(cache.EntryPath(EntryKey("2"))));
}

TEST(ContentCacheTest, HitRefreshesAnOldEntrySoTrimKeepsIt) {
    TempDir dir;
    const std::string payload(1000, 'p');
    ContentCache cache(dir.Path(), 2500);
    StoreAged(cache, 3, payload);
    ASSERT_TRUE(cache.Load(EntryKey("0")));  // the oldest, used again
    cache.Trim();
    EXPECT_TRUE(std::filesystem::exists(cache.EntryPath(EntryKey("0"))));
    EXPECT_FALSE(std::filesystem::exists(cache.EntryPath(EntryKey("1"))));
}

TEST(ContentCacheTest, UnwritableFolderIsAnErrorAndEveryLoadAMiss) {
    TempDir dir;
    dir.Write("file", "a file where the cache folder should be");
    ContentCache cache(dir.Path() / "file" / "cache");
    cache.Store(EntryKey("a"), "payload");
    EXPECT_NE(cache.Stats().error.find("file"), std::string::npos) << cache.Stats().error;
    EXPECT_FALSE(cache.Load(EntryKey("a")));
}

TEST(ContentCacheTest, ConcurrentWritersAndReadersOfOneKeyNeverSeeHalfAnEntry) {
    TempDir dir;
    ContentCache cache(dir.Path());
    const std::string payload(100000, 'x');
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
        threads.emplace_back([&cache, &payload, t] {
            for (int i = 0; i < 50; ++i) {
                if (t % 2 == 0) {
                    cache.Store(EntryKey("shared"), payload);
                } else if (std::optional<std::string> loaded = cache.Load(EntryKey("shared"))) {
                    EXPECT_EQ(*loaded, payload);
                }
            }
        });
    }
    for (std::thread& thread : threads) {
        thread.join();
    }
    EXPECT_EQ(cache.Stats().corrupt, 0U);
    EXPECT_EQ(cache.Stats().error, "");
}

}  // namespace
}  // namespace tidepool::base
