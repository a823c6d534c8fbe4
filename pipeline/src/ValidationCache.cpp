#include "tidepool/pipeline/ValidationCache.h"

#include "tidepool/pipeline/Outcome.h"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

namespace tidepool::pipeline {

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
    return Message(Severity::kWarning,
                   fmt::format("validation cache {}: {} (results were not kept; use --cache DIR "
                               "or --no-cache)",
                               cache->Folder().string(), stats.error));
}

}  // namespace tidepool::pipeline
