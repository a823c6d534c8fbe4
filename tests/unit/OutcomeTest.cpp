#include "tidepool/pipeline/Outcome.h"

#include <gtest/gtest.h>

namespace tidepool::pipeline {
namespace {

TEST(OutcomeTest, StatusesAreTheCliExitCodes) {
    EXPECT_EQ(ExitCode(Status::kOk), 0);
    EXPECT_EQ(ExitCode(Status::kInvalid), 1);
    EXPECT_EQ(ExitCode(Status::kUsage), 2);
    EXPECT_EQ(ExitCode(Status::kEnvironment), 3);
}

TEST(OutcomeTest, FailRecordsAMessageWithoutAPlaceAndStops) {
    Outcome outcome;
    outcome.Add({MakeError("a.yaml", 3, 1, "bad")});
    EXPECT_FALSE(outcome.Stopped());
    outcome.Fail(Status::kEnvironment, "disk full");
    EXPECT_TRUE(outcome.Stopped());
    ASSERT_EQ(outcome.diagnostics.size(), 2U);
    EXPECT_EQ(FormatDiagnostic(outcome.diagnostics[0]), "a.yaml:3:1: error: bad");
    EXPECT_EQ(FormatDiagnostic(outcome.diagnostics[1]), "error: disk full");
}

TEST(OutcomeTest, InvalidIsDoneNotStopped) {
    Outcome outcome;
    outcome.status = Status::kInvalid;
    EXPECT_FALSE(outcome.Stopped());
    EXPECT_EQ(FormatDiagnostic(Message(Severity::kWarning, "slow")), "warning: slow");
}

}  // namespace
}  // namespace tidepool::pipeline
