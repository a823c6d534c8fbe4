#include "tidepool/TextFile.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tidepool
