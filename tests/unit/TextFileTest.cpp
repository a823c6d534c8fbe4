#include "tidepool/TextFile.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "TempDir.h"
#include <sys/stat.h>

namespace tidepool {
namespace {

using testing::TempDir;

TEST(TextFileTest, FifoIsRefusedWithoutBlocking) {
    TempDir dir;
    const std::filesystem::path fifo = dir.Path() / "pipe.yaml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const TextFileRead read = ReadTextFile(fifo);
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(read.error, "is a FIFO (named pipe), not a regular file");
}

TEST(TextFileTest, FolderAndMissingPathSayWhichTheyAre) {
    TempDir dir;
    EXPECT_EQ(ReadTextFile(dir.Path()).error, "is a folder, not a file");
    EXPECT_EQ(ReadTextFile(dir.Path() / "none").error, "no such file");
}

TEST(TextFileTest, ShaderLosesItsByteOrderMarkAndNothingElse) {
    TempDir dir;
    const TextFileRead read = ReadShaderFile(dir.Write("a.vsh", "\xEF\xBB\xBF#version 100\n"));
    ASSERT_TRUE(read.ok);
    EXPECT_EQ(read.text, "#version 100\n");
    EXPECT_EQ(ReadTextFile(dir.Path() / "a.vsh").text, "\xEF\xBB\xBF#version 100\n");
}

// Before, any size was read whole: a 50 MB shader took 3.35 GB before glslang's token limit
// refused it.
TEST(TextFileTest, AShaderLargerThanTheBoundIsRefusedUnreadAndOneAtItIsRead) {
    TempDir dir;
    const std::filesystem::path at = dir.Write("at.fsh", "");
    std::filesystem::resize_file(at, kMaxShaderFileBytes);
    EXPECT_TRUE(ReadShaderFile(at).ok);
    const std::filesystem::path past = dir.Write("past.fsh", "");
    std::filesystem::resize_file(past, kMaxShaderFileBytes + 1);
    const TextFileRead read = ReadShaderFile(past);
    EXPECT_FALSE(read.ok);
    EXPECT_EQ(read.text, "");
    EXPECT_EQ(read.error, "is 4194305 bytes, more than the 4194304 tidepool reads of such a file");
    // Other files have no bound unless given one.
    EXPECT_TRUE(ReadTextFile(past).ok);
}

}  // namespace
}  // namespace tidepool
