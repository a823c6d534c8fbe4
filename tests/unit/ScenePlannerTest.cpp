// The scene planner's parts that need no GL: the rule each candidate is timed by
// (CandidateRule), and its choice between measured candidates, on a tie and at the margins
// (lab/include/tidepool/lab/ScenePlanner.h, ChooseCandidate).
#include "tidepool/lab/ScenePlanner.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace tidepool::lab {
namespace {

// The planner's resolution (PlanOptions::rule): qualifying candidates closer than this tie.
constexpr double kTiePoints = 3.0;

CandidateMeasure Candidate(double change, double low, double high, double psnr) {
    return {true, true, 10.0 * (1 + change / 100), low, high, change, psnr};
}

TEST(ScenePlannerTest, ACandidateMissingTheTargetTakesTheFewestPairsAsTheMachineRunsOnly) {
    const PlanOptions options;
    const base::StoppingRule& rule = options.rule;
    ASSERT_GT(rule.contended_share, 0);  // plans are timed in both states by default
    const base::StoppingRule missing = CandidateRule(rule, true);
    EXPECT_EQ(missing.max_pairs, rule.min_pairs);
    EXPECT_EQ(missing.contended_share, 0);
    // One that meets the target is timed as the rule says, in both states.
    const base::StoppingRule meeting = CandidateRule(rule, false);
    EXPECT_EQ(meeting.max_pairs, rule.max_pairs);
    EXPECT_EQ(meeting.contended_share, rule.contended_share);
}

TEST(ScenePlannerTest, ATieInsideTheIntervalsKeepsTheMoreAccurateCandidate) {
    // Candidate 1 is 20% faster, candidate 2 21% faster but less accurate; their intervals
    // overlap, so the difference is inside the measurement's own uncertainty.
    const std::vector<CandidateMeasure> candidates = {
            Candidate(0, 0, 0, 99), Candidate(-20, -22, -18, 40), Candidate(-21, -23, -19, 30)};
    const CandidateChoice choice = ChooseCandidate(candidates, true, std::nullopt, kTiePoints);
    EXPECT_EQ(choice.index, 1);
    EXPECT_NE(choice.reason.find("differ by less than their 95% intervals"), std::string::npos)
            << choice.reason;
}

TEST(ScenePlannerTest, ADifferenceUnderTheResolutionTiesEvenWhenTheIntervalsMiss) {
    // -35.6% [-36.4, -34.8] against -33.7% [-34.6, -32.8]: the intervals just miss each other,
    // but 1.9 points is under the planner's 3-point resolution, so the more accurate is kept.
    const std::vector<CandidateMeasure> candidates = {Candidate(0, 0, 0, 99),
                                                      Candidate(-33.7, -34.6, -32.8, 41.88),
                                                      Candidate(-35.6, -36.4, -34.8, 41.86)};
    const CandidateChoice choice = ChooseCandidate(candidates, true, std::nullopt, kTiePoints);
    EXPECT_EQ(choice.index, 1);
    EXPECT_NE(choice.reason.find("3.0-point resolution"), std::string::npos) << choice.reason;
    // Apart by more than the resolution and beyond both intervals: the faster one wins.
    const std::vector<CandidateMeasure> apart = {Candidate(0, 0, 0, 99),
                                                 Candidate(-33.7, -34.6, -32.8, 41.88),
                                                 Candidate(-37.2, -38.0, -36.4, 41.86)};
    EXPECT_EQ(ChooseCandidate(apart, true, std::nullopt, kTiePoints).index, 2);
}

TEST(ScenePlannerTest, AClearlyFasterCandidateWins) {
    const std::vector<CandidateMeasure> candidates = {
            Candidate(0, 0, 0, 99), Candidate(-10, -11, -9, 40), Candidate(-30, -32, -28, 30)};
    EXPECT_EQ(ChooseCandidate(candidates, true, std::nullopt, kTiePoints).index, 2);
}

TEST(ScenePlannerTest, NoCandidateFasterBeyondItsIntervalKeepsTheFullEffect) {
    // "+34% slower" and "-2% within noise" are never preferred to the full effect.
    const std::vector<CandidateMeasure> candidates = {
            Candidate(0, 0, 0, 99), Candidate(34, 30, 38, 40), Candidate(-2, -5, 1, 35)};
    const CandidateChoice choice = ChooseCandidate(candidates, true, std::nullopt, kTiePoints);
    EXPECT_EQ(choice.index, 0);
    EXPECT_NE(choice.reason.find("full effect is kept"), std::string::npos) << choice.reason;
}

TEST(ScenePlannerTest, AGainWithinTheDirectionMarginKeepsTheFullEffect) {
    // -2.5% [-3.5, -1.0]: faster beyond the interval, but not beyond the 1.5-point margin a
    // shift under load can reach, so it is not a reason to drop an effect.
    const std::vector<CandidateMeasure> candidates = {Candidate(0, 0, 0, 99),
                                                      Candidate(-2.5, -3.5, -1.0, 40)};
    EXPECT_EQ(ChooseCandidate(candidates, true, std::nullopt, kTiePoints).index, 0);
    const std::vector<CandidateMeasure> clear = {Candidate(0, 0, 0, 99),
                                                 Candidate(-3.5, -4.5, -2.0, 40)};
    EXPECT_EQ(ChooseCandidate(clear, true, std::nullopt, kTiePoints).index, 1);
}

TEST(ScenePlannerTest, CandidatesMissingTheQualityTargetAreNeverChosen) {
    std::vector<CandidateMeasure> candidates = {Candidate(0, 0, 0, 99),
                                                Candidate(-40, -42, -38, 20)};
    candidates[1].meets_quality = false;
    EXPECT_EQ(ChooseCandidate(candidates, true, std::nullopt, kTiePoints).index, 0);
}

}  // namespace
}  // namespace tidepool::lab
