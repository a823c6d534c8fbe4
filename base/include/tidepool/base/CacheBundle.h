// Many small ContentCache results read and written as one entry. A validation looks up hundreds
// of stage and link results; one file each meant hundreds of opens on a warm run and, on a cold
// run, hundreds of new files and folders, whose creation cost more than half of the run.
#pragma once

#include "tidepool/base/ContentCache.h"

#include <optional>
#include <string>
#include <unordered_map>

namespace tidepool::base {

/// The results one run of a job looked up or stored, kept in `cache` as one entry under
/// `bundle_key` (a digest of what the run will look up). When that entry is absent, the bundle
/// that `lineage_key` (a name for the job, e.g. its configuration file) last pointed at is read
/// instead, so a run whose inputs changed still finds the results that did not. Every result
/// inside is found by its own key, so reading the bundle of another run can cost misses, never
/// a wrong result; a bundle that is corrupt is a miss of all it held. Not thread-safe.
class CacheBundle {
public:
    /// Reads the bundle (or the lineage's) from `cache`, which must outlive this object.
    CacheBundle(ContentCache& cache, std::string bundle_key, std::string lineage_key);

    /// The payload stored under `key` in the bundle read, or none.
    std::optional<std::string> Load(const std::string& key);

    /// Adds `payload` under `key` to the bundle Save writes.
    void Store(const std::string& key, std::string payload);

    /// Writes the results this run used (found or stored) as the bundle under `bundle_key`, and
    /// points the lineage at it, unless the bundle read was that one and held them all already.
    /// Failures are recorded in the cache's Stats().error.
    void Save();

    /// The bundle's text for `entries` and back; exposed for tests. Decode gives none for text
    /// that is not a whole bundle.
    static std::string Encode(const std::unordered_map<std::string, std::string>& entries);
    static std::optional<std::unordered_map<std::string, std::string>> Decode(
            const std::string& text);

private:
    ContentCache& cache_;
    std::string bundle_key_;
    std::string lineage_key_;
    std::unordered_map<std::string, std::string> read_;  // the bundle read
    std::unordered_map<std::string, std::string> used_;  // what this run found or stored
    bool read_is_current_ = false;                       // read_ is the entry under bundle_key_
    bool changed_ = false;                               // a Load missed or a Store happened
};

}  // namespace tidepool::base
