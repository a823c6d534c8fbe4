#include "tidepool/pipeline/ValidationCache.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "TempDir.h"
#include <pwd.h>
#include <unistd.h>

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

TEST(ValidationCacheTest, ALinkToNowhereAsTheFolderIsNamedAsSuch) {
    testing::TempDir dir;
    const std::filesystem::path link = dir.Path() / "cache";
    std::filesystem::create_symlink(dir.Path() / "gone", link);
    const auto cache = OpenValidationCache({link.string(), false});
    ASSERT_NE(cache, nullptr);
    cache->Store(std::string(64, 'a'), "payload");
    const std::optional<Diagnostic> warning = CacheWarning(cache.get());
    ASSERT_TRUE(warning.has_value());
    EXPECT_NE(warning->message.find("it is a link to " + (dir.Path() / "gone").string() +
                                    ", which does not exist"),
              std::string::npos)
            << warning->message;
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
        std::string folder;  // the cache's folder
        const char* why;
    };
    // Where no variable names a folder, the home folder the password database gives the user.
    const struct passwd* account = ::getpwuid(::getuid());
    ASSERT_NE(account, nullptr);
    const std::string account_cache = std::string(account->pw_dir) + "/.cache/tidepool";
    const Case cases[] = {
            {"/xdg", "/home/u", "/xdg/tidepool", "an absolute XDG_CACHE_HOME comes first"},
            {"relative", "/home/u", "/home/u/.cache/tidepool", "a relative one is ignored"},
            {nullptr, "/home/u", "/home/u/.cache/tidepool", "else HOME"},
            {nullptr, "relative", account_cache, "a relative HOME is ignored"},
            {nullptr, "", account_cache, "so is an empty one"},
            {nullptr, nullptr, account_cache, "and an unset one"},
    };
    for (const Case& c : cases) {
        const ScopedEnv xdg("XDG_CACHE_HOME", c.xdg);
        const ScopedEnv home("HOME", c.home);
        const std::unique_ptr<base::ContentCache> cache = OpenValidationCache({});
        ASSERT_NE(cache, nullptr) << c.why;
        EXPECT_EQ(cache->Folder(), c.folder) << c.why;
    }
}

}  // namespace
}  // namespace tidepool::pipeline
