// Every tidepool the CLI tests run keeps its validation cache in a folder of this test process,
// removed at the end, never in the user's ~/.cache: $XDG_CACHE_HOME is set before any test runs
// and inherited by the commands the tests start. Mesa's shader cache is pinned where it was
// (MESA_SHADER_CACHE_DIR), since it also follows $XDG_CACHE_HOME: a cold Mesa cache makes the
// first render of a test several times slower than the next, which timing-based tests (killing
// a render at random points within one run's time) rely on not happening.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace {

class CacheHome : public ::testing::Environment {
public:
    CacheHome()
        : path_(std::filesystem::temp_directory_path() /
                ("tidepool-cli-cache-" + std::to_string(::getpid()))) {
        const char* xdg = std::getenv("XDG_CACHE_HOME");
        const char* home = std::getenv("HOME");
        if (std::getenv("MESA_SHADER_CACHE_DIR") == nullptr &&
            (xdg != nullptr || home != nullptr)) {
            const std::filesystem::path mesa =
                    xdg != nullptr ? std::filesystem::path(xdg) / "mesa_shader_cache"
                                   : std::filesystem::path(home) / ".cache" / "mesa_shader_cache";
            ::setenv("MESA_SHADER_CACHE_DIR", mesa.c_str(), 1);
        }
        ::setenv("XDG_CACHE_HOME", path_.c_str(), 1);
    }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }

private:
    std::filesystem::path path_;
};

// Registered during static initialisation, so the variable is set before main.
[[maybe_unused]] ::testing::Environment* const kCacheHome =
        ::testing::AddGlobalTestEnvironment(new CacheHome);

}  // namespace
