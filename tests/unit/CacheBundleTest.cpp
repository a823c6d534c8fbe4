#include "tidepool/base/CacheBundle.h"
#include "tidepool/base/Sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "TempDir.h"

namespace tidepool::base {
namespace {

using testing::TempDir;

std::string Key(const std::string& name) {
    return Sha256Hex(name);
}

TEST(CacheBundleTest, StoredResultsAreFoundByTheNextRunFromOneEntry) {
    TempDir dir;
    ContentCache cache(dir.Path() / "cache");
    {
        CacheBundle cold(cache, Key("run"), Key("job"));
        EXPECT_FALSE(cold.Load(Key("a")));
        cold.Store(Key("a"), "payload a");
        cold.Store(Key("b"), std::string("b\n\0with a NUL", 13));
        cold.Save();
    }
    EXPECT_EQ(cache.Stats().stored, 2U) << "one bundle and its lineage, not one file per result";
    ContentCache reopened(dir.Path() / "cache");
    CacheBundle warm(reopened, Key("run"), Key("job"));
    EXPECT_EQ(warm.Load(Key("a")), "payload a");
    EXPECT_EQ(warm.Load(Key("b")), std::string("b\n\0with a NUL", 13));
    warm.Save();
    EXPECT_EQ(reopened.Stats().stored, 0U) << "a run that found everything writes nothing";
    EXPECT_EQ(reopened.Stats().hits, 1U);
}

TEST(CacheBundleTest, ChangedRunFindsTheUnchangedResultsThroughTheLineage) {
    TempDir dir;
    ContentCache cache(dir.Path() / "cache");
    {
        CacheBundle first(cache, Key("run 1"), Key("job"));
        first.Store(Key("kept"), "kept result");
        first.Store(Key("edited"), "old result");
        first.Save();
    }
    {
        CacheBundle second(cache, Key("run 2"), Key("job"));
        EXPECT_EQ(second.Load(Key("kept")), "kept result");
        EXPECT_FALSE(second.Load(Key("edited 2")));
        second.Store(Key("edited 2"), "new result");
        second.Save();
    }
    // The second bundle holds only what its run used: the old result is not carried forward.
    CacheBundle third(cache, Key("run 2"), Key("another job"));
    EXPECT_EQ(third.Load(Key("kept")), "kept result");
    EXPECT_EQ(third.Load(Key("edited 2")), "new result");
    EXPECT_FALSE(third.Load(Key("edited")));
}

TEST(CacheBundleTest, CorruptBundleIsAMissOfEverythingAndIsRewritten) {
    TempDir dir;
    ContentCache cache(dir.Path() / "cache");
    {
        CacheBundle first(cache, Key("run"), Key("job"));
        first.Store(Key("a"), "payload a");
        first.Save();
    }
    {
        std::fstream file(cache.EntryPath(Key("run")),
                          std::ios::binary | std::ios::in | std::ios::out);
        file.seekp(-1, std::ios::end);
        file.put('\x7f');
    }
    ContentCache damaged_cache(dir.Path() / "cache");
    {
        CacheBundle damaged(damaged_cache, Key("run"), Key("job"));
        EXPECT_FALSE(damaged.Load(Key("a")));
        damaged.Store(Key("a"), "payload a");
        damaged.Save();
    }
    EXPECT_GE(damaged_cache.Stats().corrupt, 1U);
    ContentCache again(dir.Path() / "cache");
    CacheBundle repaired(again, Key("run"), Key("job"));
    EXPECT_EQ(repaired.Load(Key("a")), "payload a");
    EXPECT_EQ(again.Stats().corrupt, 0U);
}

TEST(CacheBundleTest, TextThatIsNotAWholeBundleDoesNotDecode) {
    const std::string good = CacheBundle::Encode({{"ab", "xyz"}, {"cd", ""}});
    ASSERT_TRUE(CacheBundle::Decode(good));
    EXPECT_EQ(CacheBundle::Decode(good)->at("ab"), "xyz");
    for (const std::string& bad :
         {good.substr(0, good.size() - 1), std::string("ab 4\nxyz"), std::string("ab x\nxyz"),
          std::string(" 3\nxyz"), std::string("ab 3"), std::string("ab -1\n")}) {
        EXPECT_FALSE(CacheBundle::Decode(bad)) << bad;
    }
    EXPECT_TRUE(CacheBundle::Decode(""));
}

}  // namespace
}  // namespace tidepool::base
