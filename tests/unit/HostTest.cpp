// What the stages ask of the machine (pipeline/include/tidepool/pipeline/Host.h): the source
// revision, inside and outside a repository, the default job count and the CPU's name.
#include "tidepool/pipeline/Host.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <thread>

#include "TempDir.h"

namespace tidepool::pipeline {
namespace {

TEST(HostTest, GitRevisionOutsideARepositoryIsUnknown) {
    const testing::TempDir dir;
    EXPECT_EQ(GitRevision(dir.Path()), "unknown");
    EXPECT_EQ(GitRevision(dir.Path() / "no-such-folder"), "unknown");
}

TEST(HostTest, AQuoteInTheFolderNameCannotRunACommand) {
    const testing::TempDir dir;
    const std::filesystem::path marker = dir.Path() / "ran";
    // Unquoted, this name would end git's argument and run `touch`.
    const std::filesystem::path folder =
            dir.Path() / ("x'; touch '" + marker.string() + "'; echo '");
    EXPECT_EQ(GitRevision(folder), "unknown");
    EXPECT_FALSE(std::filesystem::exists(marker));
}

TEST(HostTest, AFolderWithAQuoteInItsNameIsStillAskedForItsRevision) {
    const std::filesystem::path root = TIDEPOOL_SOURCE_ROOT;
    if (!std::filesystem::exists(root / ".git") || GitRevision(root) == "unknown") {
        GTEST_SKIP() << "the sources are not a git checkout, or git is not installed";
    }
    const testing::TempDir dir;
    const std::filesystem::path link = dir.Path() / "it's here";
    std::filesystem::create_directory_symlink(root, link);
    EXPECT_EQ(GitRevision(link), GitRevision(root));
}

TEST(HostTest, GitRevisionOfTheSourceTreeIsAFullCommitHashWithoutTheNewline) {
    const std::filesystem::path root = TIDEPOOL_SOURCE_ROOT;
    if (!std::filesystem::exists(root / ".git")) {
        GTEST_SKIP() << "the sources are not a git checkout";
    }
    const std::string revision = GitRevision(root);
    if (revision == "unknown") {
        GTEST_SKIP() << "git is not installed";
    }
    EXPECT_EQ(revision.size(), 40U) << revision;
    EXPECT_TRUE(std::all_of(revision.begin(), revision.end(), [](char c) {
        return std::isxdigit(static_cast<unsigned char>(c));
    })) << revision;
}

TEST(HostTest, DefaultJobsIsOnePerCoreAndNeverZero) {
    const unsigned cores = std::thread::hardware_concurrency();
    EXPECT_EQ(DefaultJobs(), cores == 0 ? 1 : static_cast<int>(cores));
    EXPECT_GE(DefaultJobs(), 1);
}

TEST(HostTest, CpuModelIsANameWithoutTheLeadingBlanksOrUnknown) {
    const std::string model = CpuModel();
    ASSERT_FALSE(model.empty());
    EXPECT_NE(model.front(), ' ');
    EXPECT_EQ(model.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace tidepool::pipeline
