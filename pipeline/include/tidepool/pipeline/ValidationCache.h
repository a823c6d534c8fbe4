// The validation cache a stage uses: where it lives, and what to say when it did not work.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/base/ContentCache.h"

#include <memory>
#include <optional>
#include <string>

namespace tidepool::pipeline {

/// --cache DIR and --no-cache as a command received them.
struct CacheChoice {
    std::string folder;  // --cache; "" for the default folder
    bool off = false;    // --no-cache
};

/// The validation cache `choice` asks for: its folder, else $XDG_CACHE_HOME/tidepool (when
/// absolute), else $HOME/.cache/tidepool (when absolute), else .cache/tidepool in the home folder
/// the password database gives the user; none when off or when no folder can be named.
std::unique_ptr<base::ContentCache> OpenValidationCache(const CacheChoice& choice);

/// "warning: validation cache DIR: ..." when `cache` could not be written or trimmed
/// (validation itself is unaffected); none otherwise, and for no cache.
std::optional<Diagnostic> CacheWarning(const base::ContentCache* cache);

}  // namespace tidepool::pipeline
