#include "tidepool/pipeline/ValidationCache.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

namespace tidepool::pipeline {
namespace {

// Sets an environment variable for one test and restores it after.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) {
            old_ = old;
        }
        if (value != nullptr) {
            setenv(name, value, 1);
        } else {
            unsetenv(name);
        }
    }
    ~ScopedEnv() {
        if (old_) {
            setenv(name_, old_->c_str(), 1);
        } else {
            unsetenv(name_);
        }
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST(ValidationCacheTest, NoCacheMeansNone) {
    EXPECT_EQ(OpenValidationCache({"/tmp/x", true}), nullptr);
    EXPECT_FALSE(CacheWarning(nullptr).has_value());
}

TEST(ValidationCacheTest, TheFolderGivenWins) {
    const ScopedEnv xdg("XDG_CACHE_HOME", "/xdg");
    const auto cache = OpenValidationCache({"/given", false});
    ASSERT_NE(cache, nullptr);
    EXPECT_EQ(cache->Folder(), "/given");
}

TEST(ValidationCacheTest, AnAbsoluteXdgCacheHomeComesBeforeHome) {
    const ScopedEnv xdg("XDG_CACHE_HOME", "/xdg");
    const ScopedEnv home("HOME", "/home/u");
    const auto cache = OpenValidationCache({});
    ASSERT_NE(cache, nullptr);
    EXPECT_EQ(cache->Folder(), "/xdg/tidepool");
}

TEST(ValidationCacheTest, ARelativeXdgCacheHomeIsIgnored) {
    const ScopedEnv xdg("XDG_CACHE_HOME", "relative");
    const ScopedEnv home("HOME", "/home/u");
    const auto cache = OpenValidationCache({});
    ASSERT_NE(cache, nullptr);
    EXPECT_EQ(cache->Folder(), "/home/u/.cache/tidepool");
}

TEST(ValidationCacheTest, NoFolderCanBeNamedWithoutXdgOrHome) {
    const ScopedEnv xdg("XDG_CACHE_HOME", nullptr);
    const ScopedEnv home("HOME", nullptr);
    EXPECT_EQ(OpenValidationCache({}), nullptr);
}

}  // namespace
}  // namespace tidepool::pipeline
