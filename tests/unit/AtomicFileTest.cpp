// The one atomic file writer: whole files or nothing, unique temp names, errors naming the path.
#include "tidepool/base/AtomicFile.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using tidepool::base::WriteFileAtomically;
using tidepool::testing::FolderEntries;
using tidepool::testing::ReadText;
using tidepool::testing::TempDir;

TEST(AtomicFileTest, WritesTheContentCreatingFoldersAndLeavesNoTempFile) {
    TempDir dir;
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "a/b/out.txt", "hello"), "");
    EXPECT_EQ(ReadText(dir.Path() / "a/b/out.txt"), "hello");
    EXPECT_EQ(FolderEntries(dir.Path() / "a/b"), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFileTest, ReplacesAnEarlierFileWhole) {
    TempDir dir;
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "out.txt", std::string(10000, 'x')), "");
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "out.txt", "short"), "");
    EXPECT_EQ(ReadText(dir.Path() / "out.txt"), "short");
}

// RLIMIT_FSIZE with SIGXFSZ ignored makes write() fail with EFBIG, a stand-in for a full disk
// that needs no root and no special mount; a child process keeps the limit away from the suite.
TEST(AtomicFileTest, FailedWriteNamesThePathKeepsTheOldFileAndLeavesNoTempFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "results.json";
    ASSERT_EQ(WriteFileAtomically(path, "old"), "");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{1000, 1000};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        const std::string error = WriteFileAtomically(path, std::string(100000, 'x'));
        const bool named = error.find(path.string()) != std::string::npos &&
                           error.find("File too large") != std::string::npos;
        ::_exit(named ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "the error did not name the path and EFBIG";
    EXPECT_EQ(ReadText(path), "old");
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"results.json"});
}

TEST(AtomicFileTest, UnwritableFolderFailsNamingThePath) {
    if (::geteuid() == 0) {
        GTEST_SKIP() << "root writes into read-only folders";
    }
    TempDir dir;
    std::filesystem::create_directories(dir.Path() / "locked");
    std::filesystem::permissions(dir.Path() / "locked", std::filesystem::perms::owner_read |
                                                                std::filesystem::perms::owner_exec);
    const std::string error = WriteFileAtomically(dir.Path() / "locked/out.txt", "x");
    std::filesystem::permissions(dir.Path() / "locked", std::filesystem::perms::owner_all);
    EXPECT_NE(error.find((dir.Path() / "locked/out.txt").string()), std::string::npos) << error;
    EXPECT_NE(error.find("Permission denied"), std::string::npos) << error;
    EXPECT_TRUE(FolderEntries(dir.Path() / "locked").empty());
}

// Before, the temp name was fixed per process, so two writers of one path truncated each
// other's temp file and one could publish the other's half-written bytes.
TEST(AtomicFileTest, ConcurrentWritersOfOnePathEachPublishAWholeFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "out.txt";
    std::vector<std::thread> writers;
    std::vector<std::string> errors(8);
    for (int w = 0; w < 8; ++w) {
        writers.emplace_back([&, w] {
            const std::string content(20000 + static_cast<std::size_t>(w),
                                      static_cast<char>('a' + w));
            for (int i = 0; i < 20 && errors[static_cast<std::size_t>(w)].empty(); ++i) {
                errors[static_cast<std::size_t>(w)] = WriteFileAtomically(path, content);
            }
        });
    }
    for (std::thread& t : writers) {
        t.join();
    }
    for (const std::string& e : errors) {
        EXPECT_EQ(e, "");
    }
    const std::string content = ReadText(path);
    ASSERT_GE(content.size(), 20000u);
    EXPECT_EQ(content, std::string(content.size(), content[0]));
    EXPECT_EQ(content.size(), 20000u + static_cast<std::size_t>(content[0] - 'a'));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"out.txt"});
}

// `--output-file` may name a link, a device or a pipe. Before, the rename put a regular file in
// the node's place: `--output-file /dev/stdout` replaced the system's /dev/stdout link.
TEST(AtomicFileTest, ALinkKeepsPointingAtTheFileItNamesWhichIsReplaced) {
    TempDir dir;
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "real.json", "old"), "");
    std::filesystem::create_symlink("real.json", dir.Path() / "link.json");
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "link.json", "new"), "");
    EXPECT_TRUE(std::filesystem::is_symlink(dir.Path() / "link.json"));
    EXPECT_EQ(ReadText(dir.Path() / "real.json"), "new");
    // A dangling link: the file it names is made.
    std::filesystem::create_symlink("sub/later.json", dir.Path() / "dangling.json");
    ASSERT_EQ(WriteFileAtomically(dir.Path() / "dangling.json", "made"), "");
    EXPECT_TRUE(std::filesystem::is_symlink(dir.Path() / "dangling.json"));
    EXPECT_EQ(ReadText(dir.Path() / "sub/later.json"), "made");
}

// On a node of its own (null's device numbers), never the system's /dev/null: a regression
// would replace that for the whole machine.
TEST(AtomicFileTest, ADeviceIsWrittenToAndStaysADevice) {
    TempDir dir;
    const std::filesystem::path device = dir.Path() / "null";
    if (::mknod(device.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) != 0) {
        GTEST_SKIP() << "making a device node needs root";
    }
    ASSERT_EQ(WriteFileAtomically(device, "discarded"), "");
    struct stat after {};
    ASSERT_EQ(::stat(device.c_str(), &after), 0);
    EXPECT_TRUE(S_ISCHR(after.st_mode));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"null"});
}

TEST(AtomicFileTest, ANamedPipeIsWrittenToItsReaderAndOneWithoutAReaderIsRefused) {
    TempDir dir;
    const std::filesystem::path pipe = dir.Path() / "pipe";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    // Nobody reads it: refused at once, never a wait.
    const std::string error = WriteFileAtomically(pipe, "lost");
    EXPECT_NE(error.find(pipe.string()), std::string::npos) << error;
    EXPECT_NE(error.find("no process is reading"), std::string::npos) << error;
    // A reader: it gets the content, and the pipe stays a pipe.
    const int reader = ::open(pipe.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    ASSERT_EQ(WriteFileAtomically(pipe, "through"), "");
    char buffer[16] = {};
    EXPECT_EQ(::read(reader, buffer, sizeof buffer), 7);
    EXPECT_EQ(std::string(buffer), "through");
    ::close(reader);
    struct stat after {};
    ASSERT_EQ(::stat(pipe.c_str(), &after), 0);
    EXPECT_TRUE(S_ISFIFO(after.st_mode));
    EXPECT_EQ(FolderEntries(dir.Path()), std::vector<std::string>{"pipe"});
}

TEST(AtomicFileTest, AReplacedFileKeepsItsPermissionsAndANewOneGets0644) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "private.json";
    ASSERT_EQ(WriteFileAtomically(path, "old"), "");
    struct stat made {};
    ASSERT_EQ(::stat(path.c_str(), &made), 0);
    EXPECT_EQ(made.st_mode & 07777, 0644u);
    ASSERT_EQ(::chmod(path.c_str(), 0600), 0);
    ASSERT_EQ(WriteFileAtomically(path, "new"), "");
    struct stat replaced {};
    ASSERT_EQ(::stat(path.c_str(), &replaced), 0);
    EXPECT_EQ(replaced.st_mode & 07777, 0600u);
    EXPECT_EQ(ReadText(path), "new");
}

}  // namespace
