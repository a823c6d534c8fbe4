// Publishing an output folder whole: written under a private staging name beside the target,
// then swapped in with one rename, so a reader or a crash never sees half of it, and only
// folders that tidepool itself wrote are ever replaced.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace tidepool::base {

/// The file that marks a folder as tidepool's own output. Its first line is kOutputMarkerLine, a
/// text no user file holds by chance; the rest says which command wrote it.
inline constexpr const char* kOutputMarkerFile = ".tidepool-output";
inline constexpr const char* kOutputMarkerLine = "tidepool output folder, version 1";

/// Why publishing failed: the target is someone else's (a usage error: choose another folder),
/// or the file system failed (an environment error: disk full, permissions).
enum class PublishFailure { kNone, kRefused, kIo };

/// A failure and its message naming the folder, the system error and the fix.
struct PublishError {
    PublishFailure failure = PublishFailure::kNone;
    std::string message;

    bool Failed() const { return failure != PublishFailure::kNone; }
};

/// True when `folder` holds tidepool's marker file (see kOutputMarkerLine).
bool IsTidepoolOutput(const std::filesystem::path& folder);

/// Says whether `folder` may be replaced or written into by tidepool: it does not exist, is an
/// empty folder, or carries the marker. Refusals name the folder and the fix.
PublishError CheckReplaceable(const std::filesystem::path& folder);

/// The file that stands where `folder` or one of its parents belongs: the nearest of them that
/// exists, when it is not a folder. None when `folder` can be made.
std::optional<std::filesystem::path> FileInPlaceOfFolder(const std::filesystem::path& folder);

/// Says whether `folder` can be made (FileInPlaceOfFolder); a file in its way is refused
/// (kRefused), naming it and the fix.
PublishError CheckFolderPath(const std::filesystem::path& folder);

/// Writes the marker file into `folder`, naming `writer` (for example "tidepool render").
std::string WriteOutputMarker(const std::filesystem::path& folder, const std::string& writer);

/// One folder publication. Begin() checks the target, removes stale staging folders of earlier
/// killed runs, and creates a fresh uniquely named staging folder beside the target; the caller
/// writes into Staging(); Publish() marks it and swaps it in. Destroying an unpublished publisher
/// removes its staging folder.
class FolderPublisher {
public:
    /// Starts publishing `target` on behalf of `writer`; on failure `*error` says why and the
    /// result is null. Nothing is changed when the target is refused.
    static std::unique_ptr<FolderPublisher> Begin(const std::filesystem::path& target,
                                                  const std::string& writer, PublishError* error);

    FolderPublisher(const FolderPublisher&) = delete;
    FolderPublisher& operator=(const FolderPublisher&) = delete;
    ~FolderPublisher();

    /// The private folder to write into; it becomes Target() on Publish().
    const std::filesystem::path& Staging() const { return staging_; }
    const std::filesystem::path& Target() const { return target_; }

    /// Replaces the target with the staging folder in one rename (the previous folder, if any,
    /// is then deleted). Concurrent publishers of one target all succeed, the last one winning.
    /// Fails, leaving the previous target and nothing else, when the target has meanwhile become
    /// someone else's or the file system fails.
    PublishError Publish();

    /// Removes the staging folder without publishing (also done by the destructor), and the
    /// parent folders Begin() created for it, so a failed run leaves no empty folders.
    void Abandon();

private:
    FolderPublisher(std::filesystem::path target, std::filesystem::path staging, std::string writer)
        : target_(std::move(target)), staging_(std::move(staging)), writer_(std::move(writer)) {}

    std::filesystem::path target_;
    std::filesystem::path staging_;
    std::string writer_;
    std::filesystem::path created_;  // the outermost parent folder Begin() created, if any
    bool done_ = false;
};

/// Removes staging and swap leftovers of `target` that killed runs left beside it: only entries
/// named like this publisher's own (".<name>.staging.<pid>.<6 chars>") whose process is gone, or
/// that are older than a day. Returns how many were removed.
int RemoveStaleStaging(const std::filesystem::path& target);

}  // namespace tidepool::base
