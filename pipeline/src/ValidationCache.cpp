#include "tidepool/pipeline/ValidationCache.h"

#include "tidepool/pipeline/Outcome.h"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pwd.h>
#include <unistd.h>

namespace tidepool::pipeline {
namespace {

// The home folder the password database gives the user running this process, when absolute.
std::optional<std::string> AccountHome() {
    long size = ::sysconf(_SC_GETPW_R_SIZE_MAX);
    std::vector<char> buffer(static_cast<std::size_t>(size > 0 ? size : 16384));
    struct passwd entry {};
    struct passwd* found = nullptr;
    if (::getpwuid_r(::getuid(), &entry, buffer.data(), buffer.size(), &found) != 0 ||
        found == nullptr || found->pw_dir == nullptr || found->pw_dir[0] != '/') {
        return std::nullopt;
    }
    return std::string(found->pw_dir);
}

}  // namespace

std::unique_ptr<base::ContentCache> OpenValidationCache(const CacheChoice& choice) {
    if (choice.off) {
        return nullptr;
    }
    if (!choice.folder.empty()) {
        return std::make_unique<base::ContentCache>(choice.folder);
    }
    // The XDG base directory rules: a relative $XDG_CACHE_HOME is invalid and ignored.
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg != nullptr && xdg[0] == '/') {
        return std::make_unique<base::ContentCache>(std::filesystem::path(xdg) / "tidepool");
    }
    const char* home = std::getenv("HOME");
    if (home != nullptr && home[0] == '/') {
        return std::make_unique<base::ContentCache>(std::filesystem::path(home) / ".cache" /
                                                    "tidepool");
    }
    // No usable $HOME (unset, empty or relative, as under some service managers and `env -i`):
    // the user's home from the password database, as a login would set it.
    if (const std::optional<std::string> account_home = AccountHome()) {
        return std::make_unique<base::ContentCache>(std::filesystem::path(*account_home) /
                                                    ".cache" / "tidepool");
    }
    return nullptr;
}

std::optional<Diagnostic> CacheWarning(const base::ContentCache* cache) {
    if (cache == nullptr) {
        return std::nullopt;
    }
    const base::ContentCacheStats stats = cache->Stats();
    if (stats.error.empty()) {
        return std::nullopt;
    }
    // A link to nowhere fails as "File exists" deep inside it; say what it is instead.
    std::string error = stats.error;
    std::error_code ec;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(cache->Folder(), ec)) &&
        !std::filesystem::exists(cache->Folder(), ec)) {
        error = fmt::format("it is a link to {}, which does not exist",
                            std::filesystem::read_symlink(cache->Folder(), ec).string());
    }
    return Message(Severity::kWarning,
                   fmt::format("validation cache {}: {} (results were not kept; use --cache DIR "
                               "or --no-cache)",
                               cache->Folder().string(), error));
}

}  // namespace tidepool::pipeline
