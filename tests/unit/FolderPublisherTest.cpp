// The one folder publisher: whole folders swapped in, only tidepool's own folders replaced,
// staging names unique and cleaned up, concurrent publishers all succeeding.
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/FolderPublisher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using tidepool::base::FolderPublisher;
using tidepool::base::PublishError;
using tidepool::base::PublishFailure;
using tidepool::base::WriteFileAtomically;
using tidepool::testing::FolderEntries;
using tidepool::testing::ReadText;
using tidepool::testing::TempDir;

// Publishes `target` holding one file `name` with `content`.
PublishError PublishOne(const std::filesystem::path& target, const std::string& name,
                        const std::string& content) {
    PublishError error;
    std::unique_ptr<FolderPublisher> publisher = FolderPublisher::Begin(target, "test", &error);
    if (!publisher) {
        return error;
    }
    if (std::string e = WriteFileAtomically(publisher->Staging() / name, content); !e.empty()) {
        return {PublishFailure::kIo, e};
    }
    return publisher->Publish();
}

TEST(FolderPublisherTest, PublishesANewFolderMarkedAsTidepoolsOutput) {
    TempDir dir;
    const PublishError error = PublishOne(dir.Path() / "out", "results.json", "{}");
    ASSERT_FALSE(error.Failed()) << error.message;
    EXPECT_EQ(ReadText(dir.Path() / "out/results.json"), "{}");
    EXPECT_TRUE(tidepool::base::IsTidepoolOutput(dir.Path() / "out"));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out"});
}

// mkdtemp's 0700 kept other users (a web server showing the report) out of published folders.
TEST(FolderPublisherTest, APublishedFolderIsReadableByOthersAsTheUsualUmaskMakesIt) {
    TempDir dir;
    ASSERT_FALSE(PublishOne(dir.Path() / "out", "results.json", "{}").Failed());
    struct stat published {};
    ASSERT_EQ(::stat((dir.Path() / "out").c_str(), &published), 0);
    EXPECT_EQ(published.st_mode & 07777, 0755u);
}

TEST(FolderPublisherTest, ReplacesItsOwnEarlierOutputWhole) {
    TempDir dir;
    ASSERT_FALSE(PublishOne(dir.Path() / "out", "old.txt", "old").Failed());
    const PublishError error = PublishOne(dir.Path() / "out", "new.txt", "new");
    ASSERT_FALSE(error.Failed()) << error.message;
    EXPECT_EQ(FolderEntries(dir.Path() / "out"),
              (std::vector<std::string>{".tidepool-output", "new.txt"}));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out"});
}

TEST(FolderPublisherTest, TrailingSlashNamesTheSameFolder) {
    TempDir dir;
    ASSERT_FALSE(PublishOne(dir.Path() / "out", "a.txt", "a").Failed());
    const PublishError error = PublishOne(dir.Path().string() + "/out/", "b.txt", "b");
    ASSERT_FALSE(error.Failed()) << error.message;
    EXPECT_TRUE(std::filesystem::exists(dir.Path() / "out/b.txt"));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out"});
}

TEST(FolderPublisherTest, EmptyFolderIsReplaced) {
    TempDir dir;
    std::filesystem::create_directories(dir.Path() / "out");
    EXPECT_FALSE(PublishOne(dir.Path() / "out", "a.txt", "a").Failed());
}

// A file named like tidepool's outputs (manifest.json, data.json, results.json) proves nothing;
// only the marker does.
TEST(FolderPublisherTest, FolderWithoutTheMarkerIsRefusedAndLeftUntouched) {
    TempDir dir;
    dir.Write("out/manifest.json", "mine");
    const PublishError error = PublishOne(dir.Path() / "out", "new.txt", "new");
    EXPECT_EQ(error.failure, PublishFailure::kRefused);
    EXPECT_NE(error.message.find((dir.Path() / "out").string()), std::string::npos);
    EXPECT_NE(error.message.find("not written by tidepool"), std::string::npos) << error.message;
    EXPECT_EQ(FolderEntries(dir.Path() / "out"), std::vector<std::string>{"manifest.json"});
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out"});
}

TEST(FolderPublisherTest, MarkerWithTheWrongTextIsRefused) {
    TempDir dir;
    dir.Write("out/.tidepool-output", "something else\n");
    dir.Write("out/keep.txt", "mine");
    EXPECT_EQ(PublishOne(dir.Path() / "out", "a", "a").failure, PublishFailure::kRefused);
    EXPECT_EQ(ReadText(dir.Path() / "out/keep.txt"), "mine");
}

TEST(FolderPublisherTest, FileInPlaceOfTheFolderIsRefused) {
    TempDir dir;
    dir.Write("out", "a file");
    EXPECT_EQ(PublishOne(dir.Path() / "out", "a", "a").failure, PublishFailure::kRefused);
    EXPECT_EQ(ReadText(dir.Path() / "out"), "a file");
}

TEST(FolderPublisherTest, UnpublishedStagingIsRemoved) {
    TempDir dir;
    {
        PublishError error;
        std::unique_ptr<FolderPublisher> publisher =
                FolderPublisher::Begin(dir.Path() / "out", "test", &error);
        ASSERT_TRUE(publisher);
        ASSERT_EQ(WriteFileAtomically(publisher->Staging() / "a.txt", "a"), "");
        EXPECT_EQ(FolderEntries(dir.Path()).size(), 1u);
    }
    EXPECT_TRUE(FolderEntries(dir.Path()).empty());
}

TEST(FolderPublisherTest, UnpublishedStagingTakesTheParentFoldersItCreatedWithIt) {
    TempDir dir;
    dir.Write("kept/file.txt", "mine");
    {
        PublishError error;
        std::unique_ptr<FolderPublisher> publisher =
                FolderPublisher::Begin(dir.Path() / "kept/a/b/out", "test", &error);
        ASSERT_TRUE(publisher) << error.message;
    }
    EXPECT_EQ(FolderEntries(dir.Path() / "kept"), std::vector<std::string>{"file.txt"});
}

// A killed run's staging folder is named after its dead process; a reused process id can never
// make it publishable, since every staging name is unique (mkdtemp) and is only ever removed.
TEST(FolderPublisherTest, StaleStagingOfDeadProcessesIsRemovedAndOthersKept) {
    TempDir dir;
    const pid_t dead = ::fork();
    if (dead == 0) {
        ::_exit(0);
    }
    ::waitpid(dead, nullptr, 0);
    const std::string d = std::to_string(dead);
    const std::string live = std::to_string(::getppid());
    dir.Write(".out.staging." + d + ".abcdef/old.txt", "stale");
    dir.Write(".out.old." + d + ".ghijkl/old.txt", "stale");
    dir.Write(".out.staging." + live + ".mnopqr/new.txt", "in progress");
    dir.Write(".out.staging.notapid/mine.txt", "a user's");
    dir.Write(".other.staging." + d + ".abcdef/x.txt", "another target's");
    EXPECT_EQ(tidepool::base::RemoveStaleStaging(dir.Path() / "out"), 2);
    EXPECT_EQ(
            FolderEntries(dir.Path()),
            (std::vector<std::string>{".other.staging." + d + ".abcdef",
                                      ".out.staging." + live + ".mnopqr", ".out.staging.notapid"}));
}

// Before, two `expand --out D` at once failed about 1 in 60 with "Directory not empty" and
// leaked staging and .old folders.
TEST(FolderPublisherTest, ConcurrentPublishersAllSucceedAndLeaveNothingBehind) {
    TempDir dir;
    std::vector<std::thread> publishers;
    std::vector<std::string> errors;
    std::mutex mutex;
    for (int p = 0; p < 6; ++p) {
        publishers.emplace_back([&, p] {
            for (int i = 0; i < 25; ++i) {
                const PublishError e =
                        PublishOne(dir.Path() / "out", "file.txt", std::to_string(p));
                if (e.Failed()) {
                    const std::lock_guard<std::mutex> lock(mutex);
                    errors.push_back(e.message);
                }
            }
        });
    }
    for (std::thread& t : publishers) {
        t.join();
    }
    EXPECT_TRUE(errors.empty()) << errors.front();
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out"});
    EXPECT_EQ(FolderEntries(dir.Path() / "out"),
              (std::vector<std::string>{".tidepool-output", "file.txt"}));
}

}  // namespace
