#include "tidepool/pipeline/ValidationCache.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
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

TEST(ValidationCacheTest, TheDefaultFolderFollowsTheXdgRules) {
    struct Case {
        const char* xdg;     // XDG_CACHE_HOME; null: unset
        const char* home;    // HOME; null: unset
        const char* folder;  // the cache's folder; null: no cache
        const char* why;
    };
    const Case cases[] = {
            {"/xdg", "/home/u", "/xdg/tidepool", "an absolute XDG_CACHE_HOME comes first"},
            {"relative", "/home/u", "/home/u/.cache/tidepool", "a relative one is ignored"},
            {nullptr, "/home/u", "/home/u/.cache/tidepool", "else HOME"},
            {nullptr, "relative", nullptr, "a relative HOME names no folder"},
            {nullptr, nullptr, nullptr, "nothing names a folder"},
    };
    for (const Case& c : cases) {
        const ScopedEnv xdg("XDG_CACHE_HOME", c.xdg);
        const ScopedEnv home("HOME", c.home);
        const std::unique_ptr<base::ContentCache> cache = OpenValidationCache({});
        if (c.folder == nullptr) {
            EXPECT_EQ(cache, nullptr) << c.why;
        } else {
            ASSERT_NE(cache, nullptr) << c.why;
            EXPECT_EQ(cache->Folder(), c.folder) << c.why;
        }
    }
}

}  // namespace
}  // namespace tidepool::pipeline
