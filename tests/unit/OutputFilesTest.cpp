#include "tidepool/pipeline/OutputFiles.h"

#include <gtest/gtest.h>

#include "FileContents.h"
#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::ReadText;
using testing::TempDir;

TEST(OutputFilesTest, RefusesToReplaceAFileOfAnotherSchemaAndChangesNothing) {
    const TempDir dir;
    const std::filesystem::path path = dir.Write("stability.json", "{\"name\": \"mine\"}");
    const Outcome outcome = WriteOwnJson(dir.Path(), "stability.json", "tidepool.stability",
                                         "stability report", "{}");
    EXPECT_EQ(outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(outcome.diagnostics),
              "error: " + path.string() +
                      ": exists and is not a tidepool stability report (no \"schema\": "
                      "\"tidepool.stability\"); nothing was changed. Choose another --out "
                      "folder, or move the file yourself.\n");
    EXPECT_EQ(ReadText(path), "{\"name\": \"mine\"}");
}

TEST(OutputFilesTest, ReplacesItsOwnFileAndChecksWithoutWriting) {
    const TempDir dir;
    const std::filesystem::path path =
            dir.Write("manifest.json", "{\"schema\": \"tidepool.manifest\"}");
    EXPECT_EQ(WriteManifest(dir.Path(), "new", true).status, Status::kOk);
    EXPECT_EQ(ReadText(path), "{\"schema\": \"tidepool.manifest\"}");
    EXPECT_EQ(WriteManifest(dir.Path(), "new").status, Status::kOk);
    EXPECT_EQ(ReadText(path), "new");
}

TEST(OutputFilesTest, AFailedWriteIsAnEnvironmentErrorWithItsPrefix) {
    const TempDir dir;
    dir.Write("file", "x");
    Outcome outcome;
    EXPECT_FALSE(WriteFile(dir.Path() / "file" / "below", "text", &outcome, "--depfile: "));
    EXPECT_EQ(outcome.status, Status::kEnvironment);
    EXPECT_EQ(Formatted(outcome.diagnostics).rfind("error: --depfile: ", 0), 0U)
            << Formatted(outcome.diagnostics);
}

TEST(OutputFilesTest, PublishingIntoAFolderOfSomeoneElsesIsRefusedAsUsage) {
    const TempDir dir;
    dir.Write("out/precious.txt", "x");
    Outcome outcome;
    EXPECT_EQ(BeginPublishing(dir.Path() / "out", "tidepool test", &outcome), nullptr);
    EXPECT_EQ(outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(outcome.diagnostics));
}

TEST(OutputFilesTest, PublishedFolderHoldsWhatWasStaged) {
    const TempDir dir;
    Outcome outcome;
    const std::unique_ptr<base::FolderPublisher> publisher =
            BeginPublishing(dir.Path() / "out", "tidepool test", &outcome);
    ASSERT_NE(publisher, nullptr) << Formatted(outcome.diagnostics);
    ASSERT_TRUE(WriteFile(publisher->Staging() / "a.txt", "a", &outcome));
    ASSERT_TRUE(Publish(*publisher, &outcome)) << Formatted(outcome.diagnostics);
    EXPECT_EQ(ReadText(dir.Path() / "out" / "a.txt"), "a");
    EXPECT_EQ(outcome.status, Status::kOk);
}

}  // namespace
}  // namespace tidepool::pipeline
