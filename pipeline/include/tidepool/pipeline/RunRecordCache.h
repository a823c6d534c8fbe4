// Whole runs of a command kept in the validation cache, in the manner of ccache's direct mode: a
// warm run with the same options over files with the same bytes repeats what the first run
// printed and wrote, without loading the configuration, expanding it or assembling a stage.
#pragma once

#include "tidepool/base/ContentCache.h"

#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tidepool::pipeline {

/// Everything a run printed and wrote: enough to repeat it byte for byte.
struct RunRecord {
    std::string out;  // what it printed on stdout
    std::string err;  // what it printed on stderr
    int exit_code = 0;
    std::optional<std::string> manifest;     // manifest.json's text, when --out wrote one
    std::optional<std::string> depfile;      // the depfile's text, when --depfile wrote one
    std::optional<std::string> report_file;  // --output-file's text, when written

    bool operator==(const RunRecord& other) const;
};

/// A file a run read and the SHA-256 of its bytes.
struct ReadFileDigest {
    std::string path;
    std::string sha256;
};

/// One command's run record in `cache`, under a key made of `key_text` (the command, every
/// option that decides its output, the working directory, tidepool's and glslang's identity).
/// The entry also lists the files the run read with their digests: a record is repeated only
/// while every one of them still has the same bytes. One record per key: a run that misses
/// replaces it. Not thread-safe.
class RunRecordCache {
public:
    /// The record's place in `cache`, which must outlive this object.
    RunRecordCache(base::ContentCache& cache, const std::string& key_text);

    /// The record kept under the key, when every file it lists still reads with the same digest;
    /// none when absent, corrupt (counted in the cache's Stats().corrupt), or a file changed or
    /// cannot be read.
    std::optional<RunRecord> Find();

    /// Keeps `record` with the digests of `files_read`, replacing any record under the key. Keeps
    /// nothing (false) when a file cannot be read, or was modified at or after `started` (the
    /// run may have read it before the change, and the digest taken now would not name what it
    /// read). Store failures are recorded in the cache's Stats().error.
    bool Keep(const std::vector<std::filesystem::path>& files_read, const timespec& started,
              const RunRecord& record);

    /// The time to pass to Keep as `started`, taken before the run reads its first file: the
    /// clock the kernel stamps file changes with, so a change after it is never stamped before.
    static timespec StartTime();

    /// The cache key (for tests).
    const std::string& Key() const { return key_; }

    /// A record's entry text and back; exposed for tests. Decode gives none for text that is not
    /// a whole entry.
    static std::string Encode(const std::vector<ReadFileDigest>& files, const RunRecord& record);
    static std::optional<std::pair<std::vector<ReadFileDigest>, RunRecord>> Decode(
            std::string_view text);

private:
    base::ContentCache& cache_;
    std::string key_;
};

}  // namespace tidepool::pipeline
