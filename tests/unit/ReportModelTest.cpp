// The report model on small hand-made runs: whitepaper rows graded by interval, tolerance and
// noise floor; accuracy and its Pareto frontier; static cost against time; failed configurations
// kept; the comparison clock (CPU time when every configuration has it); the reflection
// techniques against planar (reports/include/tidepool/report/ReportModel.h).
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"
#include "tidepool/report/WhitepaperTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "FakeReportRun.h"
#include "FileContents.h"
#include "TempDir.h"
#include <nlohmann/json.hpp>

namespace {

using namespace tidepool::report;
using namespace tidepool::testing;

PairedRatio Ratio(double ratio, double low, double high) {
    PairedRatio r;
    r.ratio = ratio;
    r.ci = {low, high};
    r.pairs = 40;
    return r;
}

// A measured interval of performance change [low, high] percent.
PairedRatio Change(double low, double high) {
    return Ratio(1.0 / (1.0 + (low + high) / 200.0), 1.0 / (1.0 + high / 100.0),
                 1.0 / (1.0 + low / 100.0));
}

const WhitepaperRow& Row(int number) {
    return WhitepaperRows()[static_cast<std::size_t>(number - 1)];
}

struct GradeCase {
    const char* name;
    int row;
    PairedRatio ratio;
    Verdict expected;
};

TEST(ReportModelTest, VerdictsAreDecidedByTheWholeIntervalAgainstHalfToTwiceTheFigure) {
    // Frame-time ratio r is a performance change of (1/r - 1) * 100 %.
    const std::vector<GradeCase> cases = {
            {"row 1: [-58.3, -54.5] lies within 30..120% of -60%", 1, Ratio(2.3, 2.2, 2.4),
             Verdict::kSameDirectionAndMagnitude},
            {"row 1: [-25.9, -20] is slower but wholly under half of 60%", 1,
             Ratio(1.3, 1.25, 1.35), Verdict::kSameDirectionDifferentMagnitude},
            {"row 1: [-33.3, -25.9] holds 30%, the lower end of 30..120%", 1, Ratio(1.4, 1.35, 1.5),
             Verdict::kSameDirectionMagnitudeAtBandEdge},
            {"row 1: +25% faster is the opposite", 1, Ratio(0.8, 0.78, 0.82), Verdict::kOpposite},
            {"row 1: an interval through no change claims no direction", 1, Ratio(1.2, 0.9, 1.5),
             Verdict::kBelowResolution},
            {"row 2: [-1, 0] reaches no change", 2, Ratio(1.005, 1.0, 1.01),
             Verdict::kBelowResolution},
            {"row 2: [-9.1, -6.5] lies within 4.5..18% of -9%", 2, Ratio(1.087, 1.07, 1.1),
             Verdict::kSameDirectionAndMagnitude},
            {"row 2: [-3.8, -2] is under half of -9%", 2, Ratio(1.03, 1.02, 1.04),
             Verdict::kSameDirectionDifferentMagnitude},
            {"row 4: [+6.6, +7.2] holds 7%, the upper end of 1.75..7% of +3.5%", 4,
             Change(6.6, 7.2), Verdict::kSameDirectionMagnitudeAtBandEdge},
            {"row 4: [+7.05, +7.7] lies wholly above twice +3.5%", 4, Change(7.05, 7.7),
             Verdict::kSameDirectionDifferentMagnitude},
            {"row 4: [+2, +6.9] lies within 1.75..7%", 4, Change(2.0, 6.9),
             Verdict::kSameDirectionAndMagnitude},
            {"row 2: [-2, -1] excludes no change, but not by the margin", 2,
             Ratio(1.015, 1.01, 1.02), Verdict::kBelowResolution},
            {"row 6: [-1.5, +0.5] is negligible as the whitepaper's <1%", 6,
             Ratio(1.005, 0.995, 1.015), Verdict::kNegligibleAsClaimed},
            {"row 6: a definite 30% loss is not <1%", 6, Ratio(1.43, 1.4, 1.46),
             Verdict::kSameDirectionDifferentMagnitude},
            {"row 6: [-2.5, -1.6] holds the 2% end of <1% x 2", 6, Change(-2.5, -1.6),
             Verdict::kSameDirectionMagnitudeAtBandEdge},
            {"row 6: [-4.8, +1] is neither negligible nor a direction", 6, Ratio(1.02, 0.99, 1.05),
             Verdict::kBelowResolution},
            {"row 8: qualitative faster, measured faster", 8, Ratio(0.8, 0.78, 0.82),
             Verdict::kSameDirectionOnly},
            {"row 8: qualitative faster, measured slower", 8, Ratio(1.2, 1.15, 1.25),
             Verdict::kOpposite},
            {"row 11: qualitative, [-0.5, +1.5] includes no change", 11, Ratio(0.995, 0.985, 1.005),
             Verdict::kBelowResolution},
            {"failed measurement", 3, PairedRatio{}, Verdict::kFailed},
    };
    for (const GradeCase& c : cases) {
        std::string reason;
        const Verdict verdict = GradeRow(Row(c.row), c.ratio, nullptr, &reason);
        EXPECT_EQ(verdict, c.expected)
                << c.name << ": " << VerdictName(verdict) << " (" << reason << ")";
        EXPECT_FALSE(reason.empty()) << c.name;
    }
}

TEST(ReportModelTest, EachVerdictBoundaryIsWhereTheRowsVerdictChanges) {
    EXPECT_EQ(VerdictBoundaries(Row(2)), (std::vector<double>{-4.5, -18.0}));  // "reduced by 9%"
    EXPECT_EQ(VerdictBoundaries(Row(6)), (std::vector<double>{-2.0, 2.0}));    // "<1%"
    EXPECT_TRUE(VerdictBoundaries(Row(8)).empty());                            // qualitative
    for (const WhitepaperRow& row : WhitepaperRows()) {
        for (double b : VerdictBoundaries(row)) {
            // A narrow interval just on either side of the boundary gets two verdicts.
            std::string reason;
            const Verdict below = GradeRow(row, Change(b - 0.4, b - 0.2), nullptr, &reason);
            const Verdict above = GradeRow(row, Change(b + 0.2, b + 0.4), nullptr, &reason);
            EXPECT_NE(below, above)
                    << "row " << row.number << " at " << b << ": " << VerdictName(below);
        }
    }
}

TEST(ReportModelTest, AnIntervalHoldingABandEndClaimsTheDirectionButNoMagnitude) {
    // Run g of 2026-11-27: row 4 (+3.5%, band 1.75..7%) read +7.0% [+6.6, +7.2] quiet and
    // +7.4% [+7.0x, +7.7] loaded. "Overlaps the band" called the first the same magnitude and
    // the second a different one; holding the 7% end, the first decides neither.
    std::string reason;
    const Verdict quiet = GradeRow(Row(4), Change(6.6, 7.2), nullptr, &reason);
    EXPECT_EQ(quiet, Verdict::kSameDirectionMagnitudeAtBandEdge);
    EXPECT_NE(reason.find("holds its 7.0% end (half to twice the whitepaper's figure: 1.8% to "
                          "7%), so the magnitude is not decided either way"),
              std::string::npos)
            << reason;
    // The direction is still a claim another run could contradict.
    EXPECT_TRUE(IsFirmVerdict(quiet, FigureKind::kPercent));
    EXPECT_EQ(GradeRow(Row(4), Change(-7.2, -6.6), nullptr, &reason), Verdict::kOpposite);
    // Either side of the end is decided once the interval clears it.
    EXPECT_EQ(GradeRow(Row(4), Change(7.02, 7.7), nullptr, &reason),
              Verdict::kSameDirectionDifferentMagnitude);
    EXPECT_EQ(GradeRow(Row(4), Change(6.3, 6.98), nullptr, &reason),
              Verdict::kSameDirectionAndMagnitude);
    // An interval wider than the band holds both ends; the reason says so.
    EXPECT_EQ(GradeRow(Row(4), Change(1.6, 7.5), nullptr, &reason),
              Verdict::kSameDirectionMagnitudeAtBandEdge);
    EXPECT_NE(reason.find("holds the whole band"), std::string::npos) << reason;
    // Row 6's band is the whitepaper's "<1%" times 2, not half to twice a figure.
    EXPECT_EQ(GradeRow(Row(6), Change(-2.5, -1.6), nullptr, &reason),
              Verdict::kSameDirectionMagnitudeAtBandEdge);
    EXPECT_NE(reason.find("holds its 2.0% end (the whitepaper's <1% times 2: |change| <= 2%)"),
              std::string::npos)
            << reason;
}

TEST(ReportModelTest, BelowResolutionSaysHowSmallTheChangeIs) {
    std::string reason;
    ASSERT_EQ(GradeRow(Row(3), Ratio(1.005, 0.99, 1.02), nullptr, &reason),
              Verdict::kBelowResolution);
    // The interval [-1.96%, +1.01%]: |change| < 2.0%.
    EXPECT_NE(reason.find("below resolution: |change| < 2.0%; the interval reaches within 1.5 "
                          "points of no change"),
              std::string::npos)
            << reason;
}

TEST(ReportModelTest, HalvesThatDisagreeInSignAreSaidNotFoldedIntoTheCategory) {
    SplitHalf split;
    split.odd = Ratio(0.7, 0.6, 0.8);   // candidate first: faster
    split.even = Ratio(1.1, 1.0, 1.2);  // baseline first: slower
    std::string reason;
    EXPECT_EQ(GradeRow(Row(10), Ratio(0.8, 0.7, 0.9), &split, &reason),
              Verdict::kSameDirectionOnly);
    EXPECT_NE(reason.find("the two halves of the pairs disagree in sign"), std::string::npos)
            << reason;
    split.even = Ratio(0.85, 0.8, 0.9);
    EXPECT_EQ(GradeRow(Row(10), Ratio(0.8, 0.7, 0.9), &split, &reason),
              Verdict::kSameDirectionOnly);
    EXPECT_EQ(reason.find("disagree"), std::string::npos) << reason;
}

TEST(ReportModelTest, FirmVerdictsAreTheOnesASecondRunCouldContradict) {
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionAndMagnitude, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionDifferentMagnitude, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionMagnitudeAtBandEdge, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kOpposite, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kNegligibleAsClaimed, FigureKind::kNegligible));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionOnly, FigureKind::kDirection));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kSameDirectionOnly, FigureKind::kPercent));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kBelowResolution, FigureKind::kDirection));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kFailed, FigureKind::kPercent));
}

TEST(ReportModelTest, VerdictsStandAsAgreeingInDirectionOnlyWhenOnlyTheDirectionIsClaimed) {
    EXPECT_EQ(StandingOf(Verdict::kSameDirectionAndMagnitude), VerdictStanding::kAgrees);
    EXPECT_EQ(StandingOf(Verdict::kNegligibleAsClaimed), VerdictStanding::kAgrees);
    EXPECT_EQ(StandingOf(Verdict::kSameDirectionMagnitudeAtBandEdge),
              VerdictStanding::kAgreesInDirection);
    EXPECT_EQ(StandingOf(Verdict::kSameDirectionDifferentMagnitude),
              VerdictStanding::kAgreesInDirection);
    EXPECT_EQ(StandingOf(Verdict::kSameDirectionOnly), VerdictStanding::kAgreesInDirection);
    EXPECT_EQ(StandingOf(Verdict::kOpposite), VerdictStanding::kDisagrees);
    EXPECT_EQ(StandingOf(Verdict::kFailed), VerdictStanding::kDisagrees);
    EXPECT_EQ(StandingOf(Verdict::kBelowResolution), VerdictStanding::kUndecided);
}

TEST(ReportModelTest, WhitepaperRowsAreMeasuredFromPairedRounds) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const ReportModel& model = *built.model;
    ASSERT_EQ(model.rows.size(), 11u);
    // Row 1: 10 ms -> 24 ms is a frame-time ratio of 2.4, "performance reduced by 58.3%".
    EXPECT_NEAR(model.rows[0].ratio.ratio, 2.4, 1e-3);
    EXPECT_NEAR(model.rows[0].change_percent, -58.33, 0.05);
    EXPECT_EQ(model.rows[0].verdict, Verdict::kSameDirectionAndMagnitude);
    // Row 10: discard 40 ms -> oblique 30 ms: faster, direction only.
    EXPECT_EQ(model.rows[9].verdict, Verdict::kSameDirectionOnly);
    // Row 8: cube map 36 ms vs 30 ms is slower: opposite to the whitepaper.
    EXPECT_EQ(model.rows[7].verdict, Verdict::kOpposite);
    // Row 9: 30.3 -> 30 ms is 1% faster, inside the 1.5-point margin: no direction.
    EXPECT_EQ(model.rows[8].verdict, Verdict::kBelowResolution);
    EXPECT_TRUE(std::isfinite(model.largest_split_half_disagreement));
}

// Row 7's "why" cites the per-pass times its comparison took in pairs; each configuration's own
// per-pass times (timed in whichever comparison came first, under another moment's load) are
// only the fallback for results that have no per-comparison ones.
// Row 7's comparison as results.json records it, with two pairs of frames.
nlohmann::json Row7ComparisonEntry() {
    return {{"label", "row 7"},
            {"baseline", "water:FULL"},
            {"candidate", "water:FULL@lowres"},
            {"decision", "resolved"},
            {"baseline_ms", {30.0, 30.5}},
            {"candidate_ms", {26.0, 26.5}}};
}

// Row 7 of the model built from `results` written over the fake run's results.json.
RowComparison Row7Built(TempDir& dir, const FakeRun& run, const nlohmann::json& results) {
    dir.Write("render/results.json", results.dump());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    if (!loaded.inputs) {
        ADD_FAILURE() << loaded.error;
        return {};
    }
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    if (!built.model) {
        ADD_FAILURE() << built.error;
        return {};
    }
    return built.model->rows.at(6);
}

TEST(ReportModelTest, MeasuredWhyCitesTheComparisonsOwnPassTimes) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    for (nlohmann::json& c : results["configurations"]) {
        if (c["id"] == "water:FULL") {
            c["pass_ms"] = {{"reflection", 3.3}, {"main", 26.5}};
        } else if (c["id"] == "water:FULL@lowres") {
            c["pass_ms"] = {{"reflection", 4.4}, {"main", 35.6}, {"low_res_water", 11.2}};
        }
    }
    const std::string fallback = Row7Built(dir, run, results).measured_why;
    EXPECT_NE(fallback.find("main 26.5 -> 35.6 ms"), std::string::npos) << fallback;

    nlohmann::json entry = Row7ComparisonEntry();
    entry["baseline_pass_ms"] = {{"reflection", 3.2}, {"main", 26.0}};
    entry["candidate_pass_ms"] = {{"reflection", 3.3}, {"main", 12.0}, {"low_res_water", 10.5}};
    results["comparisons"] = nlohmann::json::array({entry});
    const std::string why = Row7Built(dir, run, results).measured_why;
    EXPECT_NE(why.find("reflection 3.2 -> 3.3 ms"), std::string::npos) << why;
    EXPECT_NE(why.find("main 26.0 -> 12.0 ms"), std::string::npos) << why;
    EXPECT_NE(why.find("low_res_water none -> 10.5 ms"), std::string::npos) << why;
    EXPECT_NE(why.find("The main pass changes most (-14.0 ms); it is 89% of the baseline's frame"),
              std::string::npos)
            << why;
    EXPECT_EQ(why.find("35.6"), std::string::npos) << why;
}

// Before, an image of another size than the reference's gave an empty heat map, and the report
// failed writing it ("a 0x0 image needs 0 bytes", exit code 3) without naming the input.
TEST(ReportModelTest, AnImageOfAnotherSizeThanTheReferencesIsAnErrorNamingIt) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, {{"water:REF", {"reference"}, 50, 0},
                                           {"water:FULL", {"full"}, 10, 0},
                                           {"water:NOFOG", {"full_no_fog"}, 9, 0}});
    tidepool::base::RgbaImage odd;
    odd.width = 17;
    odd.height = 33;
    odd.pixels.assign(static_cast<std::size_t>(17 * 33 * 4), 255);
    const std::filesystem::path image = dir.Path() / "render/images/1.png";
    ASSERT_EQ(tidepool::base::WritePngAtomically(image, odd), "");
    // The render recorded the image's accuracy while it was in memory, so the accuracy table
    // takes that and never reads the file: only the whitepaper panels do.
    nlohmann::json results = nlohmann::json::parse(std::ifstream(run.results));
    for (nlohmann::json& c : results["configurations"]) {
        for (nlohmann::json& v : c["views"]) {
            v["accuracy"] = {{"psnr_db", 40.0}, {"ssim", 0.99}, {"share_visible", 0.0}};
        }
    }
    std::ofstream(run.results) << results.dump();
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    EXPECT_FALSE(built.model);
    EXPECT_NE(built.error.find(image.string() + ": 17x33 image, but "), std::string::npos)
            << built.error;
    EXPECT_NE(built.error.find("the reference configuration's at view 'three_quarter' is 32x24"),
              std::string::npos)
            << built.error;
}

TEST(ReportModelTest, AccuracyAndParetoFrontierOnKnownImages) {
    TempDir dir;
    // Reference slow and exact; "cheap" fast with a small error; "bad" slower and worse than
    // "cheap", so it is dominated; "mid" between the two on both axes.
    const FakeRun run = WriteFakeRun(dir, {{"water:REF", {"reference"}, 50, 0},
                                           {"water:CHEAP", {}, 10, 4},
                                           {"water:BAD", {}, 20, 8},
                                           {"water:MID", {}, 15, 2}});
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const ReportModel& model = *built.model;
    ASSERT_EQ(model.accuracy.size(), 4u);
    const AccuracyEntry& ref = model.accuracy[0];
    EXPECT_TRUE(ref.is_reference);
    EXPECT_TRUE(std::isinf(ref.psnr_db));
    EXPECT_DOUBLE_EQ(ref.ssim, 1.0);
    EXPECT_DOUBLE_EQ(ref.share_visible, 0.0);
    // 16 of 768 pixels differ in "cheap", 64 in "bad", 4 in "mid".
    EXPECT_NEAR(model.accuracy[1].share_visible, 16.0 / 768.0, 1e-12);
    EXPECT_NEAR(model.accuracy[2].share_visible, 64.0 / 768.0, 1e-12);
    EXPECT_LT(model.accuracy[2].ssim, model.accuracy[1].ssim);
    EXPECT_TRUE(model.accuracy[0].on_frontier);
    EXPECT_TRUE(model.accuracy[1].on_frontier);
    EXPECT_FALSE(model.accuracy[2].on_frontier);
    EXPECT_TRUE(model.accuracy[3].on_frontier);
    ASSERT_EQ(model.frontier.size(), 3u);
    EXPECT_EQ(model.frontier.front(), 1u);  // sorted by time: cheap, mid, reference
    EXPECT_EQ(model.frontier.back(), 0u);
}

// The render compares each image with the reference's while it is in memory and records it
// (`accuracy` per view); the report takes those figures instead of reading the image back, and
// null PSNR means identical. The file must still exist.
TEST(ReportModelTest, AccuracyRecordedByTheRenderIsUsedWithoutReadingTheImage) {
    TempDir dir;
    const FakeRun run =
            WriteFakeRun(dir, {{"water:REF", {"reference"}, 50, 0}, {"water:CHEAP", {}, 10, 4}});
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    results["configurations"][0]["views"][0]["accuracy"] = {
            {"psnr_db", nullptr}, {"ssim", 1.0}, {"share_visible", 0.0}};
    results["configurations"][1]["views"][0]["accuracy"] = {
            {"psnr_db", 33.0}, {"ssim", 0.5}, {"share_visible", 0.25}};
    dir.Write("render/results.json", results.dump(2));
    // Not a PNG any more: reading it would fail the report.
    const std::string cheap = results["configurations"][1]["views"][0]["image"];
    dir.Write("render/" + cheap, "not a png");
    {
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        ASSERT_TRUE(loaded.inputs) << loaded.error;
        const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
        ASSERT_TRUE(built.model) << built.error;
        ASSERT_EQ(built.model->accuracy.size(), 2u);
        EXPECT_TRUE(std::isinf(built.model->accuracy[0].psnr_db));
        EXPECT_DOUBLE_EQ(built.model->accuracy[1].psnr_db, 33.0);
        EXPECT_DOUBLE_EQ(built.model->accuracy[1].ssim, 0.5);
        EXPECT_DOUBLE_EQ(built.model->accuracy[1].share_visible, 0.25);
    }
    std::filesystem::remove(dir.Path() / "render" / cheap);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    EXPECT_FALSE(built.model);
    EXPECT_NE(built.error.find((dir.Path() / "render" / cheap).string() + ": cannot read image"),
              std::string::npos)
            << built.error;
}

TEST(ReportModelTest, RankCorrelationAndLargestDisagreementsOnKnownInputs) {
    MeasuredConfiguration a, b, c, d;
    a.id = "a";
    b.id = "b";
    c.id = "c";
    d.id = "d";
    std::vector<StaticCostEntry> entries = {
            {&a, 0, 0, 10, 1.0}, {&b, 0, 0, 20, 2.0}, {&c, 0, 0, 30, 3.0}, {&d, 0, 0, 40, 4.0}};
    StaticCostAnalysis monotone = AnalyseStaticCost(entries);
    EXPECT_DOUBLE_EQ(monotone.spearman_rho, 1.0);
    // "d" has the most operations but is the fastest: the count misleads most there.
    entries[3].median_ms = 0.5;
    StaticCostAnalysis misled = AnalyseStaticCost(entries);
    EXPECT_NEAR(misled.spearman_rho, -0.2, 1e-12);
    ASSERT_FALSE(misled.misleading.empty());
    EXPECT_EQ(misled.entries[misled.misleading.front()].configuration, &d);
    EXPECT_DOUBLE_EQ(misled.entries[3].ops_rank, 4.0);
    EXPECT_DOUBLE_EQ(misled.entries[3].time_rank, 1.0);
    EXPECT_TRUE(std::isnan(AnalyseStaticCost({entries[0], entries[1]}).spearman_rho));
}

TEST(ReportModelTest, FailedConfigurationIsShownAsFailedNotDropped) {
    TempDir dir;
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    configurations[2].ok = false;  // reflection_water_colour: row 2
    const FakeRun run = WriteFakeRun(dir, configurations);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const ReportModel& model = *built.model;
    EXPECT_EQ(model.failed_configurations, 1);
    EXPECT_EQ(model.accuracy.size(), configurations.size());
    EXPECT_FALSE(model.accuracy[2].measured);
    EXPECT_NE(model.accuracy[2].note.find("FAILED"), std::string::npos);
    EXPECT_EQ(model.rows[1].verdict, Verdict::kFailed);
    EXPECT_NE(model.rows[1].verdict_reason.find("water:ENABLE_WATER_COLOUR"), std::string::npos);
    ASSERT_EQ(model.validation.failed.size(), 1u);

    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string html = ReadText(written.folder / "index.html");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(html.find("1 configuration(s) FAILED"), std::string::npos);
    EXPECT_NE(md.find("water:ENABLE_WATER_COLOUR | FAILED"), std::string::npos) << md;
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["whitepaper_rows"][1]["verdict"], "failed");
    EXPECT_EQ(data["validation"]["failed_configurations"][0]["configuration"],
              "water:ENABLE_WATER_COLOUR");
}

// The manifest holds pruned counts per rule; the report summarises them, one row per rule, and
// summarises a manifest written before that (a list of combinations) by grouping it.
TEST(ReportModelTest, PrunedCombinationsAreSummarisedPerRuleNotListed) {
    const nlohmann::json by_rule = nlohmann::json::parse(R"([
        {"program": "water", "rule": "ENABLE_FRESNEL requires ENABLE_REFRACTION",
         "file": "variants.yaml", "line": 36, "count": 4608},
        {"program": "model", "rule": "excluded combination ENABLE_FOG_DEPTH, CLIP_DISCARD",
         "file": "variants.yaml", "line": 98, "count": 0}])");
    const nlohmann::json old_list = nlohmann::json::parse(R"([
        {"id": "water:ENABLE_FRESNEL", "program": "water",
         "rule": "ENABLE_FRESNEL requires ENABLE_REFRACTION", "file": "variants.yaml", "line": 36},
        {"id": "water:ENABLE_FOG,ENABLE_FRESNEL", "program": "water",
         "rule": "ENABLE_FRESNEL requires ENABLE_REFRACTION", "file": "variants.yaml", "line": 36}
        ])");
    for (const auto& [key, value, first_count] :
         {std::tuple{"pruned_by_rule", by_rule, 4608U}, std::tuple{"pruned", old_list, 2U}}) {
        TempDir dir;
        const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
        nlohmann::json manifest = nlohmann::json::parse(ReadText(run.manifest));
        manifest.erase("pruned_by_rule");
        manifest[key] = value;
        dir.Write("manifest/manifest.json", manifest.dump());
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        ASSERT_TRUE(loaded.inputs) << loaded.error;
        const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
        ASSERT_TRUE(built.model) << built.error;
        const std::vector<PrunedRuleRow>& rows = built.model->validation.pruned_by_rule;
        ASSERT_FALSE(rows.empty()) << key;
        EXPECT_EQ(rows[0].program, "water");
        EXPECT_EQ(rows[0].rule, "ENABLE_FRESNEL requires ENABLE_REFRACTION");
        EXPECT_EQ(rows[0].line, 36);
        EXPECT_EQ(rows[0].count, first_count) << key;

        const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
        ASSERT_EQ(written.error, "");
        const std::string md = ReadText(written.folder / "report.md");
        EXPECT_NE(md.find("| water | ENABLE_FRESNEL requires ENABLE_REFRACTION | variants.yaml:36 "
                          "| " +
                          std::to_string(first_count) + " |"),
                  std::string::npos)
                << md;
        EXPECT_EQ(md.find("water:ENABLE_FOG,ENABLE_FRESNEL"), std::string::npos);
        const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
        EXPECT_EQ(data["validation"]["pruned_by_rule"][0]["count"], first_count);
    }
}

TEST(ReportModelTest, MissingImageIsAnErrorNamingTheFileAndNothingIsBuilt) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const std::filesystem::path image = dir.Path() / "render" / "images" / "3.png";
    ASSERT_TRUE(std::filesystem::remove(image));
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    EXPECT_FALSE(built.model);
    EXPECT_EQ(built.error.rfind(image.string(), 0), 0u) << built.error;
}

// The whitepaper configurations with CPU times: 1.5x the wall time (llvmpipe's two threads)
// except the cube-map normalisation, whose CPU time is below full's (wall: above).
std::vector<FakeConfiguration> WithCpuTimes(std::vector<FakeConfiguration> configurations) {
    for (FakeConfiguration& c : configurations) {
        c.cpu_ms = c.presets.front() == "full_cubemap_normalise" ? 40.0 : c.ms * 1.5;
    }
    return configurations;
}

TEST(ReportModelTest, ResultsWithoutCpuSamplesAreComparedOnWallTime) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    EXPECT_EQ(loaded.inputs->clock, TimingClock::kWall);
    EXPECT_NE(loaded.inputs->clock_reason.find("wall-clock"), std::string::npos);
    const ReportModel model = BuildOrFail(*loaded.inputs);
    EXPECT_EQ(model.clock, TimingClock::kWall);
    EXPECT_NEAR(model.rows[0].ratio.ratio, 2.4, 1e-3);  // 24 / 10 ms on the wall clock
    const nlohmann::json data = ReportToJson(model);
    EXPECT_EQ(data["method"]["clock"], "wall");
    EXPECT_EQ(data["accuracy"][0]["median_cpu_ms"], nullptr);
}

TEST(ReportModelTest, CpuSamplesOnEveryConfigurationMakeEveryComparisonUseCpuTime) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WithCpuTimes(WhitepaperConfigurations()));
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    EXPECT_EQ(loaded.inputs->clock, TimingClock::kCpu);
    EXPECT_NE(loaded.inputs->clock_reason.find("CPU time"), std::string::npos);
    ReportOptions options;
    options.name = "cpu";
    const ReportModelResult built = BuildReportModel(*loaded.inputs, options);
    ASSERT_TRUE(built.model) << built.error;
    const ReportModel& model = *built.model;
    EXPECT_EQ(model.clock, TimingClock::kCpu);
    // Row 1 keeps its ratio (both clocks scale alike); row 8 follows the CPU clock: 40 ms on
    // CPU against full's 45 is faster, where the wall clock (36 against 30) said slower.
    EXPECT_NEAR(model.rows[0].ratio.ratio, 2.4, 1e-3);
    EXPECT_EQ(model.rows[7].verdict, Verdict::kSameDirectionOnly) << model.rows[7].verdict_reason;
    // Accuracy, Pareto and static cost are on CPU time too.
    for (const AccuracyEntry& e : model.accuracy) {
        EXPECT_DOUBLE_EQ(e.median_ms, e.configuration->cpu_median_ms);
    }
    for (const StaticCostEntry& e : model.static_cost.entries) {
        EXPECT_DOUBLE_EQ(e.median_ms, e.configuration->cpu_median_ms);
    }
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["method"]["clock"], "cpu");
    EXPECT_EQ(data["whitepaper_rows"][0]["clock"], "cpu");
    EXPECT_DOUBLE_EQ(data["accuracy"][0]["median_cpu_ms"].get<double>(), 15.0);
    EXPECT_DOUBLE_EQ(data["accuracy"][0]["median_wall_ms"].get<double>(), 10.0);
    // Both medians are shown, the compared one named; the Method section says why.
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("median ms (CPU, compared)"), std::string::npos);
    EXPECT_NE(md.find("median ms (wall)"), std::string::npos);
    EXPECT_NE(md.find("| Compared on | CPU time: process CPU time"), std::string::npos);
}

// Pairs timed with the core shared widen the row's stated interval to reach them, keep the
// as-run change, and the verdict follows the stated interval: here the contended pairs see no
// gain, so no direction is claimed.
TEST(ReportModelTest, ContendedPairsWidenTheStatedIntervalAndTheVerdictFollowsIt) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WithCpuTimes(WhitepaperConfigurations()));
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    nlohmann::json entry = Row7ComparisonEntry();
    std::vector<double> base, cand, busy_base, busy_cand;
    for (int i = 0; i < 12; ++i) {
        const double jitter = 1.0 + 0.001 * (i % 4);
        base.push_back(30.0 * jitter);
        cand.push_back(27.0 * jitter);  // 11% faster as run
        busy_base.push_back(30.0 * jitter);
        busy_cand.push_back(29.9 * jitter);  // 0.3% faster with the core shared
    }
    entry["baseline_ms"] = base;
    entry["candidate_ms"] = cand;
    results["comparisons"] = nlohmann::json::array({entry});
    const RowComparison as_run = Row7Built(dir, run, results);
    EXPECT_EQ(as_run.ratio.contended_pairs, 0);
    EXPECT_GT(as_run.change_ci.low, 10.0);
    EXPECT_NE(as_run.verdict, Verdict::kBelowResolution);

    entry["contended_baseline_ms"] = busy_base;
    entry["contended_candidate_ms"] = busy_cand;
    results["comparisons"] = nlohmann::json::array({entry});
    const RowComparison both = Row7Built(dir, run, results);
    EXPECT_EQ(both.ratio.contended_pairs, 12);
    EXPECT_NEAR(both.change_percent, as_run.change_percent, 1e-9);
    EXPECT_NEAR(PerformanceChangePercent(both.ratio.contended_ratio), 0.33, 0.05);
    EXPECT_LT(both.change_ci.low, 0.4);
    EXPECT_NEAR(both.change_ci.high, as_run.change_ci.high, 1e-9);
    EXPECT_EQ(both.verdict, Verdict::kBelowResolution) << both.verdict_reason;
    EXPECT_NEAR(both.resolution_points, (both.change_ci.high - both.change_ci.low) / 2, 1e-9);

    // The report shows both states: data.json's row and the Method section's table and text.
    results["timing"]["contended_share"] = 0.5;
    dir.Write("render/results.json", results.dump());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    const nlohmann::json& row = data["whitepaper_rows"][6];
    EXPECT_EQ(row["contended_pairs"], 12);
    EXPECT_NEAR(row["contended_percent"].get<double>(), 0.33, 0.05);
    EXPECT_NEAR(row["as_run_percent_ci"][0].get<double>(), as_run.change_ci.low, 1e-9);
    EXPECT_NEAR(row["measured_percent_ci"][0].get<double>(), both.change_ci.low, 1e-9);
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("Host states. Contention is not only noise"), std::string::npos);
    EXPECT_NE(md.find("| core shared [95%] |"), std::string::npos);
    EXPECT_NE(md.find("| Pairs with the core shared, per as-run pair (at least) | 0.5 |"),
              std::string::npos);
}

// The Method section says a run probed its comparisons only when it did: a minimum above the
// probe's 10 pairs, on one rendering thread (runner::ProbesComparisons).
TEST(ReportModelTest, TheMethodSaysWhenComparisonsWereProbed) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WithCpuTimes(WhitepaperConfigurations()));
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    auto method_says_probed = [&](int min_pairs, int workers) {
        results["timing"]["min_pairs"] = min_pairs;
        results["settings"]["workers"] = workers;
        dir.Write("render/results.json", results.dump());
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        EXPECT_TRUE(loaded.inputs) << loaded.error;
        if (!loaded.inputs) {
            return false;
        }
        const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
        EXPECT_TRUE(built.model) << built.error;
        if (!built.model) {
            return false;
        }
        const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
        EXPECT_EQ(written.error, "");
        return ReadText(written.folder / "report.md").find("first 10 pairs (its probe)") !=
               std::string::npos;
    };
    EXPECT_TRUE(method_says_probed(20, 1));
    EXPECT_FALSE(method_says_probed(10, 1));
    EXPECT_FALSE(method_says_probed(20, 2));
}

// A row whose pairs `run`'s second process timed says so in its pairs' source (data.json), since
// that process timed them at another moment of the machine's load.
TEST(ReportModelTest, PairsTheSecondProcessTimedSaySo) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WithCpuTimes(WhitepaperConfigurations()));
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    auto source_of_row_7 = [&](const std::string& timed_by) {
        nlohmann::json entry = Row7ComparisonEntry();
        entry["timed_by"] = timed_by;
        results["comparisons"] = nlohmann::json::array({entry});
        return Row7Built(dir, run, results).pairs_source;
    };
    EXPECT_EQ(source_of_row_7("render"), "pairs of frames rendered back to back");
    EXPECT_EQ(source_of_row_7(""), "pairs of frames rendered back to back");
    EXPECT_EQ(source_of_row_7("second_process"),
              "pairs of frames rendered back to back, by the process beside the render");
}

TEST(ReportModelTest, OneConfigurationWithoutCpuSamplesKeepsEveryComparisonOnWallTime) {
    TempDir dir;
    std::vector<FakeConfiguration> configurations = WithCpuTimes(WhitepaperConfigurations());
    configurations[3].cpu_ms = 0;  // reflection_alpha_blend: an older writer's entry
    const FakeRun run = WriteFakeRun(dir, configurations);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    EXPECT_EQ(loaded.inputs->clock, TimingClock::kWall);
    EXPECT_NE(loaded.inputs->clock_reason.find("water:ENABLE_ALPHA_BLEND"), std::string::npos)
            << loaded.inputs->clock_reason;
    const ReportModel model = BuildOrFail(*loaded.inputs);
    EXPECT_EQ(model.rows[7].verdict, Verdict::kOpposite);  // the wall clock's cube-map row
}

TEST(ReportModelTest, SectionListsTheFourComparisonsWithPassesFromThePassNames) {
    TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, ReflectionConfigurations()), &inputs);
    ASSERT_EQ(model.reflections.size(), 4u);
    const std::vector<std::pair<std::string, std::string>> pairs = {
            {"reflection_only", "cubemap_reflection"},
            {"reflection_only", "fourier_reflection"},
            {"full", "full_cubemap_reflection"},
            {"full", "full_fourier_reflection"}};
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        const TechniqueComparison& t = model.reflections[i];
        EXPECT_EQ(t.baseline.preset, pairs[i].first) << i;
        EXPECT_EQ(t.candidate.preset, pairs[i].second) << i;
        ASSERT_NE(t.candidate.configuration, nullptr) << i;
        EXPECT_EQ(t.note, "") << i;
        EXPECT_EQ(t.passes_dropped, std::vector<std::string>{"reflection"}) << i;
        EXPECT_FALSE(t.reading.empty()) << i;
    }
    EXPECT_EQ(model.reflections[0].kind, TechniqueKind::kCubemapReflection);
    EXPECT_EQ(model.reflections[1].kind, TechniqueKind::kFourierReflection);
    EXPECT_EQ(model.reflections[0].baseline_passes,
              (std::vector<std::string>{"reflection", "main"}));
    EXPECT_EQ(model.reflections[0].candidate_passes, std::vector<std::string>{"main"});
    EXPECT_EQ(model.reflections[2].baseline_passes,
              (std::vector<std::string>{"reflection", "refraction", "main"}));
    EXPECT_EQ(model.reflections[2].candidate_passes,
              (std::vector<std::string>{"refraction", "main"}));
    EXPECT_EQ(model.reflections[2].baseline_draw_calls, 30);
    EXPECT_EQ(model.reflections[2].candidate_draw_calls, 22);
    // 10 ms -> 8 ms is a frame-time ratio of 0.8, "performance increased by 25%"; 10 -> 12.5
    // is 1.25, "reduced by 20%": the same sign convention as the whitepaper rows.
    EXPECT_NEAR(model.reflections[0].change_percent, 25.0, 0.05);
    EXPECT_EQ(model.reflections[0].direction, +1);
    EXPECT_DOUBLE_EQ(model.reflections[0].baseline_median_ms, 10.0);
    EXPECT_DOUBLE_EQ(model.reflections[0].candidate_median_ms, 8.0);
    EXPECT_NEAR(model.reflections[1].change_percent, -20.0, 0.05);
    EXPECT_EQ(model.reflections[1].direction, -1);
    // Both sides share their rounds' jitter, so the paired interval is narrow but finite.
    EXPECT_LE(model.reflections[1].change_ci.low, model.reflections[1].change_percent);
    EXPECT_GE(model.reflections[1].change_ci.high, model.reflections[1].change_percent);
    EXPECT_TRUE(std::isfinite(model.reflections[1].change_ci.low));
    EXPECT_EQ(model.reflections[1].ratio.pairs, 24);
    // What each technique misses, in the words of the issue.
    EXPECT_NE(model.reflections[0].reading.find("Local objects and terrain are missing"),
              std::string::npos);
    EXPECT_NE(model.reflections[1].reading.find("objects (anything that moves) are missing"),
              std::string::npos);
    // The depth optics: an addition to full, no pass dropped.
    ASSERT_EQ(model.optics.size(), 1u);
    EXPECT_EQ(model.optics[0].kind, TechniqueKind::kDepthOptics);
    EXPECT_EQ(model.optics[0].baseline.preset, "full");
    EXPECT_EQ(model.optics[0].candidate.preset, "full_depth_optics");
    EXPECT_TRUE(model.optics[0].passes_dropped.empty());
    EXPECT_NEAR(model.optics[0].change_percent, (30.0 / 33.0 - 1) * 100, 0.05);
    EXPECT_TRUE(std::isfinite(model.optics[0].psnr_db));
    EXPECT_NE(model.optics[0].reading.find("Most changed view: three_quarter"), std::string::npos)
            << model.optics[0].reading;
    // One panel per technique: its full-effect candidate beside planar full.
    ASSERT_EQ(model.reflection_panels.size(), 2u);
    EXPECT_EQ(model.reflection_panels[0].configuration->id, "water:CUBE_FULL");
    EXPECT_EQ(model.reflection_panels[0].reference_preset, "full");
    EXPECT_NE(model.reflection_panels[0].title.find("planar"), std::string::npos);
    EXPECT_EQ(model.reflection_panels[1].configuration->id, "water:FOURIER_FULL");
    EXPECT_TRUE(std::isfinite(model.reflection_panels[1].psnr_db));
}

TEST(ReportModelTest, ErrorAgainstPlanarIsIdenticalWhenImagesMatchAndFiniteWhenTheyDiffer) {
    TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, ReflectionConfigurations()), &inputs);
    ASSERT_EQ(model.reflections.size(), 4u);
    const TechniqueComparison& same = model.reflections[0];  // cube map: identical images
    EXPECT_EQ(same.views_compared, 2);
    EXPECT_TRUE(std::isinf(same.psnr_db) && same.psnr_db > 0) << same.psnr_db;
    EXPECT_DOUBLE_EQ(same.ssim, 1.0);
    EXPECT_DOUBLE_EQ(same.share_visible, 0.0);
    EXPECT_EQ(same.worst_view, "");  // nothing differs, so no view breaks
    const TechniqueComparison& differs = model.reflections[1];  // Fourier: mark 0 against 6
    EXPECT_EQ(differs.views_compared, 2);
    EXPECT_TRUE(std::isfinite(differs.psnr_db));
    EXPECT_LT(differs.ssim, 1.0);
    EXPECT_NEAR(differs.share_visible, 36.0 / 768.0, 1e-12);
    // Full cube map: identical at three_quarter, broken at grazing, which the reading names.
    const TechniqueComparison& full = model.reflections[2];
    ASSERT_EQ(full.per_view.size(), 2u);
    EXPECT_EQ(full.per_view[0].view, "three_quarter");
    EXPECT_TRUE(std::isinf(full.per_view[0].psnr_db));
    EXPECT_EQ(full.per_view[1].view, "grazing");
    EXPECT_TRUE(std::isfinite(full.per_view[1].psnr_db));
    EXPECT_TRUE(std::isfinite(full.psnr_db));
    EXPECT_GT(full.psnr_db, full.per_view[1].psnr_db);  // the mean MSE halves the error
    EXPECT_EQ(full.worst_view, "grazing");
    EXPECT_DOUBLE_EQ(full.worst_psnr_db, full.per_view[1].psnr_db);
    EXPECT_NE(full.reading.find("Worst view: grazing"), std::string::npos) << full.reading;
    // The panel is at the timing view, where the full cube map matches planar exactly.
    EXPECT_TRUE(std::isinf(model.reflection_panels[0].psnr_db));
}

TEST(ReportModelTest, MissingOrFailedCandidateIsShownAsSuchNotDropped) {
    TempDir dir;
    std::vector<FakeConfiguration> configurations = ReflectionConfigurations();
    configurations.erase(std::remove_if(configurations.begin(), configurations.end(),
                                        [](const FakeConfiguration& c) {
                                            return c.presets.front() == "fourier_reflection";
                                        }),
                         configurations.end());
    for (FakeConfiguration& c : configurations) {
        if (c.presets.front() == "full_cubemap_reflection") {
            c.ok = false;
        }
    }
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, configurations), &inputs);
    ASSERT_EQ(model.reflections.size(), 4u);
    const TechniqueComparison& missing = model.reflections[1];
    EXPECT_EQ(missing.candidate.preset, "fourier_reflection");
    EXPECT_EQ(missing.candidate.configuration, nullptr);
    EXPECT_EQ(missing.note, "no configuration in the results carries preset 'fourier_reflection'");
    EXPECT_TRUE(std::isnan(missing.change_percent));
    EXPECT_FALSE(missing.HasError());
    // The baseline's side is still shown.
    EXPECT_EQ(missing.baseline_passes, (std::vector<std::string>{"reflection", "main"}));
    EXPECT_DOUBLE_EQ(missing.baseline_median_ms, 10.0);
    const TechniqueComparison& failed = model.reflections[2];
    ASSERT_NE(failed.candidate.configuration, nullptr);
    EXPECT_NE(failed.note.find("water:CUBE_FULL (preset 'full_cubemap_reflection') FAILED"),
              std::string::npos)
            << failed.note;
    EXPECT_TRUE(std::isnan(failed.psnr_db));
    ASSERT_EQ(model.reflection_panels.size(), 2u);
    EXPECT_NE(model.reflection_panels[0].note.find("FAILED"), std::string::npos);

    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("| Fourier reflection (reflection only) | reflection_only [water:] → "
                      "fourier_reflection [fourier_reflection (missing)] | no configuration in "
                      "the results carries preset 'fourier_reflection' | reflection, main → – |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("full_cubemap_reflection [water:CUBE_FULL FAILED]"), std::string::npos);
    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("<tr class=\"bad technique-fourier-reflection_only\">"), std::string::npos);
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    const nlohmann::json& entry = data["reflection_techniques"]["comparisons"][1];
    EXPECT_EQ(entry["candidate"]["configuration"], nullptr);
    EXPECT_EQ(entry["candidate"]["ok"], false);
    EXPECT_EQ(entry["measured_percent"], nullptr);
    EXPECT_EQ(entry["note"], missing.note);
}

TEST(ReportModelTest, ResultsWithoutPassNamesStillLoadAndShowPassesAsUnknown) {
    TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, WhitepaperConfigurations()), &inputs);
    ASSERT_TRUE(inputs);
    const ViewImage* view = inputs->FindByPreset("full")->ViewAt("three_quarter");
    ASSERT_NE(view, nullptr);
    EXPECT_TRUE(view->pass_names.empty());
    EXPECT_FALSE(view->draw_calls.has_value());
    ASSERT_EQ(model.reflections.size(), 4u);  // every candidate missing, none dropped
    for (const TechniqueComparison& t : model.reflections) {
        EXPECT_EQ(t.candidate.configuration, nullptr);
        EXPECT_TRUE(t.baseline_passes.empty());
        EXPECT_NE(t.note.find("carries preset"), std::string::npos);
    }
    ASSERT_EQ(model.reflection_panels.size(), 2u);
    EXPECT_NE(model.reflection_panels[0].note.find("MISSING"), std::string::npos);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("`(missing)`: **MISSING: no configuration carries preset "
                      "'full_cubemap_reflection'**"),
              std::string::npos)
            << md;
}

}  // namespace
