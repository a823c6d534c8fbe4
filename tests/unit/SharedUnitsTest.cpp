// Reading back a unit the second process rendered (runner/src/SharedUnits.h): its results file
// of one configuration or one comparison gives the render process the same entry it would have
// written itself.
#include "tidepool/runner/Results.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "SharedUnits.h"
#include "TempDir.h"

namespace tidepool::runner {
namespace {

// A configuration's results with every field the results file keeps set, including a warning
// and an identical image (infinite PSNR, which the file keeps as null).
ConfigurationResult EveryFieldSet() {
    ConfigurationResult r;
    r.configuration.id = "water+ENABLE_FOG";
    r.configuration.variant = MakeVariant("water", {"ENABLE_FOG"});
    r.verdict = {true, true, true, true, "vertex log", "fragment log", "link log", {}};
    r.verdict.diagnostics.push_back(
            {Severity::kWarning, "shaders/water.frag", 12, 3, "a warning", "water+ENABLE_FOG"});
    r.verdict.diagnostics.push_back(MakeError("shaders/water.vert", 4, 0, "an error"));
    ViewResult same;
    same.view = "overview";
    same.image_path = "images/water+ENABLE_FOG-overview.png";
    same.frame.passes = 3;
    same.frame.pass_names = {"reflection", "refraction", "main"};
    same.frame.draw_calls = 17;
    same.accuracy = base::ImageAccuracy{INFINITY, 1.0, 0.0};
    ViewResult different = same;
    different.view = "shore";
    different.frame.oblique_fallback = true;
    different.frame.gl_error = "GL_INVALID_OPERATION after pass main";
    different.accuracy = base::ImageAccuracy{31.25, 0.875, 0.125};
    r.views = {same, different};
    r.passes = 3;
    r.draw_calls = 17;
    r.samples_ms = {{4.5}, {4.25}};
    r.cpu_samples_ms = {{4.0}, {3.75}};
    r.plan_ms_median = 0.0625;
    r.pass_ms = {{"main", 2.5}, {"reflection", 1.5}};
    r.instrumented_frame_ms = 4.125;
    r.gl_error = "GL_INVALID_OPERATION after pass main (view shore)";
    return r;
}

// `written` as a unit file the second process left, read back as the render process reads it.
stagefiles::ReadResult<stagefiles::ResultsFile> ThroughAUnitFile(const std::string& written) {
    const testing::TempDir dir;
    return stagefiles::ReadResultsFile(dir.Write("unit.json", written));
}

TEST(SharedUnitsTest, AUnitReadBackFromItsFileWritesTheSameResultsEntry) {
    RunResults results;
    results.configurations = {EveryFieldSet()};
    const std::string written = stagefiles::ResultsFileText(ToResultsFile(results));
    const stagefiles::ReadResult<stagefiles::ResultsFile> read = ThroughAUnitFile(written);
    ASSERT_TRUE(read.value) << read.error;
    ASSERT_EQ(read.value->configurations.size(), 1U);

    RunResults again;
    again.configurations.resize(1);
    again.configurations[0].configuration = results.configurations[0].configuration;
    FromResultsEntry(read.value->configurations[0], again.configurations[0]);
    EXPECT_EQ(stagefiles::ResultsFileText(ToResultsFile(again)), written);
    const ConfigurationResult& r = again.configurations[0];
    EXPECT_TRUE(std::isinf(r.views.at(0).accuracy->psnr_db));
    ASSERT_EQ(r.verdict.diagnostics.size(), 2U);
    EXPECT_EQ(r.verdict.diagnostics[0].severity, Severity::kWarning);
    EXPECT_EQ(r.verdict.diagnostics[1].severity, Severity::kError);
}

// A comparison's unit read back keeps its pairs, its decision and each side's per-pass times.
TEST(SharedUnitsTest, AComparisonReadBackFromItsFileWritesTheSameResultsEntry) {
    RunResults results;
    results.configurations = {EveryFieldSet(), EveryFieldSet()};
    results.configurations[1].configuration.id = "water+ENABLE_FOG@lowres";
    ComparisonResult& c = results.comparisons.emplace_back();
    c.comparison.label = "row 7";
    c.comparison.baseline = 0;
    c.comparison.candidate = 1;
    c.timing.samples = {{10.0, 10.5}, {11.0, 11.25}, {10.25, 10.75}, {11.5, 11.5}};
    c.timing.estimate =
            base::EstimatePaired(c.timing.samples.baseline_ms, c.timing.samples.candidate_ms);
    c.timing.contended = {{10.0, 10.25}, {11.5, 11.75}, {}, {}};
    c.timing.contended_estimate =
            base::EstimatePaired(c.timing.contended.baseline_ms, c.timing.contended.candidate_ms);
    c.timing.stated = base::AcrossHostStates(c.timing.estimate, c.timing.contended_estimate);
    c.timing.decision = base::StopDecision::kResolved;
    c.timing.baseline_passes = {{{"main", 9.5}}, 10.25};
    c.timing.candidate_passes = {{{"main", 8.0}, {"low_res_water", 3.0}}, 11.25};
    const std::string written = stagefiles::ResultsFileText(ToResultsFile(results));
    const stagefiles::ReadResult<stagefiles::ResultsFile> read = ThroughAUnitFile(written);
    ASSERT_TRUE(read.value) << read.error;
    ASSERT_EQ(read.value->comparisons.size(), 1U);

    RunResults again = results;
    again.comparisons[0].timing = {};
    ASSERT_TRUE(FromResultsEntry(read.value->comparisons[0], again.comparisons[0]));
    EXPECT_EQ(stagefiles::ResultsFileText(ToResultsFile(again)), written);
    EXPECT_EQ(again.comparisons[0].timing.candidate_passes.pass_ms.at("low_res_water"), 3.0);
    EXPECT_EQ(again.comparisons[0].timing.baseline_passes.frame_ms, 10.25);
    EXPECT_EQ(again.comparisons[0].timing.contended.candidate_ms,
              (std::vector<double>{11.5, 11.75}));
    EXPECT_EQ(again.comparisons[0].timing.contended_estimate.pairs, 2);
}

}  // namespace
}  // namespace tidepool::runner
