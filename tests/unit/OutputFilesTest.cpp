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

// What CheckPlannedOutputs says of `outputs` against the inputs, "" when it accepts them.
std::string PlannedOutputsError(const std::vector<PlannedOutput>& outputs,
                                const std::vector<std::filesystem::path>& inputs) {
    Outcome outcome;
    const bool ok = CheckPlannedOutputs(outputs, inputs, &outcome);
    EXPECT_EQ(ok, outcome.status == Status::kOk);
    EXPECT_EQ(ok, outcome.diagnostics.empty());
    return ok ? "" : Formatted(outcome.diagnostics);
}

TEST(OutputFilesTest, AnOutputThatWouldReplaceAnInputOrAnotherOutputIsRefused) {
    const TempDir dir;
    const std::filesystem::path config = dir.Write("v.yaml", "x");
    const std::filesystem::path shader = dir.Write("s/a.fsh", "x");
    std::filesystem::create_symlink(config, dir.Path() / "link.yaml");
    const std::filesystem::path manifest = dir.Path() / "o" / "manifest.json";
    const std::vector<std::filesystem::path> inputs{config, shader};
    EXPECT_EQ(PlannedOutputsError({{"--out", manifest}, {"--depfile", dir.Path() / "o.d"}}, inputs),
              "");
    EXPECT_EQ(PlannedOutputsError({{"--depfile", config}}, inputs),
              "error: --depfile: " + config.string() +
                      " is a file this command reads; writing it would replace it: choose "
                      "another path\n");
    // The same file by another path: through a link, or with "..".
    EXPECT_NE(PlannedOutputsError({{"--depfile", dir.Path() / "link.yaml"}}, inputs), "");
    EXPECT_NE(PlannedOutputsError({{"--output-file", dir.Path() / "o" / ".." / "s" / "a.fsh"}},
                                  inputs),
              "");
    EXPECT_EQ(PlannedOutputsError({{"--out", manifest}, {"--depfile", manifest}}, inputs),
              "error: --depfile: " + manifest.string() +
                      " is also where --out writes; give each output its own path\n");
    EXPECT_EQ(PlannedOutputsError({{"--out", manifest}, {"--depfile", dir.Path() / "o"}}, inputs),
              "error: --depfile: " + (dir.Path() / "o").string() +
                      " is the folder --out writes manifest.json into; give the path of a file "
                      "beside it\n");
    // A stream is written as one, not replaced: two outputs may share /dev/null.
    EXPECT_EQ(PlannedOutputsError({{"--depfile", "/dev/null"}, {"--output-file", "/dev/null"}},
                                  inputs),
              "");
}

TEST(OutputFilesTest, AnOutputThatIsAFolderOrLiesBelowAFileIsRefused) {
    const TempDir dir;
    const std::filesystem::path file = dir.Write("file", "x");
    EXPECT_EQ(
            PlannedOutputsError({{"--depfile", dir.Path()}}, {}),
            "error: --depfile: " + dir.Path().string() + " is a folder; give the path of a file\n");
    EXPECT_EQ(PlannedOutputsError({{"--output-file", file / "sub" / "x.json"}}, {}),
              "error: --output-file: " + (file / "sub" / "x.json").string() + ": " + file.string() +
                      " is a file, not a folder; choose another path\n");
    EXPECT_EQ(PlannedOutputsError({{"--output-file", dir.Path() / "new" / "x.json"}}, {}), "");
}

TEST(OutputFilesTest, PublishingBelowAFileIsRefusedAsUsage) {
    const TempDir dir;
    const std::filesystem::path file = dir.Write("file", "x");
    Outcome outcome;
    EXPECT_EQ(BeginPublishing(file / "out", "tidepool test", &outcome), nullptr);
    EXPECT_EQ(outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(outcome.diagnostics),
              "error: " + (file / "out").string() + ": " + file.string() +
                      " is a file, not a folder; nothing was changed. Choose another --out "
                      "folder.\n");
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
