// `run`'s refusals before any work (pipeline/include/tidepool/pipeline/RunStage.h): a matrix that
// does not load, a manifest.json that is not tidepool's and a render folder tidepool did not
// write; each is told to the progress sink and nothing is replaced. The whole run is CliTest's.
#include "tidepool/pipeline/RunStage.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "FileContents.h"
#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::ReadText;
using testing::SmallMatrix;

// Keeps what `run` tells; the refusals come before any long stage begins. (Run is called
// qualified: inside a test body GoogleTest's own Test::Run would hide it.)
class RecordedProgress : public ProgressSink {
public:
    void Begin(const std::string& line) override { begun.push_back(line); }
    void Progress(const StageProgress& /*progress*/) override {}
    void Finish() override {}
    void Line(const std::string& line) override { lines.push_back(line); }
    void Tell(const std::vector<Diagnostic>& told) override {
        diagnostics.insert(diagnostics.end(), told.begin(), told.end());
    }

    std::vector<std::string> begun;
    std::vector<std::string> lines;
    std::vector<Diagnostic> diagnostics;
};

// `run` of the small matrix into its folder's out/.
RunRequest RequestFor(const SmallMatrix& matrix) {
    RunRequest request;
    request.config = matrix.Config();
    request.out = matrix.Dir().Path() / "out";
    return request;
}

TEST(RunStageTest, AMatrixThatDoesNotLoadStopsAsUsageAndCreatesNothing) {
    const SmallMatrix matrix;
    RunRequest request = RequestFor(matrix);
    request.config = (matrix.Dir().Path() / "missing.yaml").string();
    RecordedProgress progress;
    const RunResult result = pipeline::Run(request, progress);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(progress.diagnostics));
    EXPECT_FALSE(result.rendered);
    EXPECT_FALSE(std::filesystem::exists(request.out));
}

TEST(RunStageTest, SomeoneElsesManifestIsRefusedBeforeValidationAndKept) {
    const SmallMatrix matrix;
    const std::filesystem::path theirs =
            matrix.Dir().Write("out/manifest/manifest.json", "{\"schema\": \"mine\"}");
    const RunRequest request = RequestFor(matrix);
    RecordedProgress progress;
    const RunResult result = pipeline::Run(request, progress);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_NE(Formatted(progress.diagnostics).find(theirs.string()), std::string::npos)
            << Formatted(progress.diagnostics);
    EXPECT_TRUE(progress.lines.empty());  // no "validate: ..." line: validation never ran
    EXPECT_EQ(ReadText(theirs), "{\"schema\": \"mine\"}");
    EXPECT_FALSE(std::filesystem::exists(request.out / "render"));
    EXPECT_FALSE(result.rendered);
}

TEST(RunStageTest, ARenderFolderTidepoolDidNotWriteIsRefusedAndKept) {
    const SmallMatrix matrix;
    const std::filesystem::path theirs = matrix.Dir().Write("out/render/notes.txt", "mine");
    const RunRequest request = RequestFor(matrix);
    RecordedProgress progress;
    const RunResult result = pipeline::Run(request, progress);
    EXPECT_EQ(result.outcome.status, Status::kUsage);
    EXPECT_TRUE(HasErrors(progress.diagnostics)) << Formatted(progress.diagnostics);
    EXPECT_TRUE(progress.lines.empty());
    EXPECT_EQ(ReadText(theirs), "mine");
    EXPECT_FALSE(std::filesystem::exists(result.manifest_path));
}

// The second process's forecast: its time so far over the share of its stages done, the stability
// catalogue kStabilityShareOfStages of them and the plans the rest.
TEST(RunStageTest, TheSecondProcessForecastsItsJoinFromTheShareOfItsStagesDone) {
    const std::unique_ptr<base::SharedClaims> claims = base::SharedClaims::Create(1);
    ASSERT_TRUE(claims);
    using std::chrono::seconds;
    const JoinForecast::Clock::time_point start{};
    const JoinForecast forecast(claims.get(), true, true, start);
    // The forecast to a microsecond (the share is not exact in binary).
    auto said = [&]() -> double {
        const auto at = claims->HelperExpectedAt();
        return at ? std::chrono::duration<double>(*at - start).count() : -1.0;
    };
    constexpr double kStability = kStabilityShareOfStages;
    forecast.Stability(0.0, start + seconds(1));  // nothing done: nothing said
    EXPECT_FALSE(claims->HelperExpectedAt());
    forecast.Stability(0.5, start + seconds(10));  // half the catalogue in 10 s
    EXPECT_NEAR(said(), 10.0 / (0.5 * kStability), 1e-6);
    forecast.Stability(1.0, start + seconds(13));  // the catalogue in 13 s
    EXPECT_NEAR(said(), 13.0 / kStability, 1e-6);
    forecast.Plans(0.5, start + seconds(60));  // and half the plans by 60 s
    EXPECT_NEAR(said(), 60.0 / (kStability + (1 - kStability) * 0.5), 1e-6);
    forecast.Plans(1.0, start + seconds(110));  // all of it
    EXPECT_NEAR(said(), 110.0, 1e-6);
    // Plans alone, or the catalogue alone, are all of the work.
    JoinForecast(claims.get(), false, true, start).Plans(0.25, start + seconds(5));
    EXPECT_NEAR(said(), 20.0, 1e-6);
    JoinForecast(claims.get(), true, false, start).Stability(0.5, start + seconds(5));
    EXPECT_NEAR(said(), 10.0, 1e-6);
    // Without a claim table there is no one to tell.
    JoinForecast(nullptr, true, true, start).Stability(1.0, start + seconds(5));
}

}  // namespace
}  // namespace tidepool::pipeline
