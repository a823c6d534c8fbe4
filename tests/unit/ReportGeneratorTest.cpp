// The report generator on small hand-made inputs: whitepaper rows found by preset, verdicts with
// tolerance and noise floor, accuracy and its Pareto frontier, static cost versus time, failed
// configurations kept, corrupt inputs rejected with the file named, atomic publication, the
// comparison clock (CPU time when every configuration has it), the Scenes section, and the
// Reflection techniques section (cube-map and Fourier reflections against planar, depth optics).
#include "tidepool/base/RgbaImage.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"
#include "tidepool/report/WhitepaperTable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "TempDir.h"
#include <nlohmann/json.hpp>

namespace {

using namespace tidepool::report;
using tidepool::testing::TempDir;

std::string ReadText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// A flat image of one colour, with a bright square when `mark` > 0 (a visible difference).
tidepool::base::RgbaImage Flat(std::uint8_t grey, int mark = 0) {
    tidepool::base::RgbaImage image;
    image.width = 32;
    image.height = 24;
    image.pixels.assign(static_cast<std::size_t>(image.width * image.height * 4), grey);
    for (int y = 0; y < mark; ++y) {
        for (int x = 0; x < mark; ++x) {
            const auto i = static_cast<std::size_t>((y * image.width + x) * 4);
            image.pixels[i] = image.pixels[i + 1] = image.pixels[i + 2] = 255;
        }
    }
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
        image.pixels[i] = 255;
    }
    return image;
}

// One configuration of the hand-made results: id, presets, time per frame, image mark size.
struct FakeConfiguration {
    std::string id;
    std::vector<std::string> presets;
    double ms = 10;
    int mark = 0;  // 0: identical to the reference
    bool ok = true;
    std::string program = "water";
    int total_ops = 100;
    std::map<std::string, nlohmann::json> passes = {};
    double cpu_ms = 0;  // > 0: cpu_samples_ms and cpu_statistics are written at this time
    std::vector<std::string> pass_names = {};  // written per view when not empty
    int draw_calls = -1;                       // written per view when >= 0
    int grazing_mark = -1;                     // >= 0: a second view, "grazing", this mark
};

// Writes manifest.json, results.json and images for `configurations` into `dir`.
struct FakeRun {
    std::filesystem::path manifest;
    std::filesystem::path results;
};

FakeRun WriteFakeRun(const TempDir& dir, const std::vector<FakeConfiguration>& configurations,
                     int rounds = 24) {
    nlohmann::json variants = nlohmann::json::array();
    nlohmann::json entries = nlohmann::json::array();
    for (const FakeConfiguration& c : configurations) {
        const std::string variant = c.id.substr(0, c.id.find('@'));
        variants.push_back({{"id", variant},
                            {"program", c.program},
                            {"valid", true},
                            {"stages",
                             {{"vertex", {{"cost", {{"total_ops", 10}}}}},
                              {"fragment", {{"cost", {{"total_ops", c.total_ops - 10}}}}}}}});
        nlohmann::json samples = nlohmann::json::array();
        for (int r = 0; r < rounds; ++r) {
            // A little deterministic jitter so intervals have width.
            const double jitter = 1.0 + 0.002 * ((r % 3) - 1);
            samples.push_back({c.ms * jitter, c.ms * jitter * 1.001});
        }
        nlohmann::json cpu_samples = nlohmann::json::array();
        for (int r = 0; r < rounds; ++r) {
            // Jitter of another phase than the wall samples', as two clocks would give.
            const double jitter = 1.0 + 0.002 * (((r + 1) % 3) - 1);
            cpu_samples.push_back({c.cpu_ms * jitter, c.cpu_ms * jitter * 1.001});
        }
        nlohmann::json views = nlohmann::json::array();
        if (c.ok) {
            std::vector<std::pair<std::string, int>> marks = {{"three_quarter", c.mark}};
            if (c.grazing_mark >= 0) {
                marks.emplace_back("grazing", c.grazing_mark);
            }
            for (const auto& [view, mark] : marks) {
                const std::string image = "images/" + std::to_string(entries.size()) +
                                          (view == "three_quarter" ? "" : "-" + view) + ".png";
                EXPECT_EQ(tidepool::base::WritePngAtomically(dir.Path() / "render" / image,
                                                             Flat(100, mark)),
                          "");
                views.push_back({{"view", view}, {"image", image}});
                if (!c.pass_names.empty()) {
                    views.back()["pass_names"] = c.pass_names;
                    views.back()["passes"] = c.pass_names.size();
                }
                if (c.draw_calls >= 0) {
                    views.back()["draw_calls"] = c.draw_calls;
                }
            }
        }
        nlohmann::json passes = {{"reflection_size", 256},
                                 {"low_res_water", false},
                                 {"clip", "oblique"},
                                 {"culling", true}};
        for (const auto& [k, v] : c.passes) {
            passes[k] = v;
        }
        entries.push_back({{"id", c.id},
                           {"variant", variant},
                           {"program", c.program},
                           {"presets", c.presets},
                           {"passes", passes},
                           {"driver", {{"valid", c.ok}, {"diagnostics", nlohmann::json::array()}}},
                           {"views", views},
                           {"samples_ms", c.ok ? samples : nlohmann::json::array()},
                           {"statistics",
                            {{"count", c.ok ? rounds * 2 : 0},
                             {"median_ms", c.ms},
                             {"ci_low_ms", c.ms * 0.99},
                             {"ci_high_ms", c.ms * 1.01}}},
                           {"gl_error", ""},
                           {"ok", c.ok}});
        if (c.cpu_ms > 0) {
            entries.back()["cpu_samples_ms"] = c.ok ? cpu_samples : nlohmann::json::array();
            entries.back()["cpu_statistics"] = {{"count", c.ok ? rounds * 2 : 0},
                                                {"median_ms", c.cpu_ms},
                                                {"ci_low_ms", c.cpu_ms * 0.99},
                                                {"ci_high_ms", c.cpu_ms * 1.01}};
        }
    }
    const nlohmann::json manifest = {{"schema", "tidepool.manifest"},
                                     {"version", 1},
                                     {"variants", variants},
                                     {"pruned_by_rule", nlohmann::json::array()},
                                     {"counts", {{"variants", variants.size()}, {"pruned", 0}}}};
    const nlohmann::json results = {
            {"schema", "tidepool.render-results"},
            {"version", 1},
            {"environment", {{"gl_renderer", "llvmpipe (test)"}, {"lp_num_threads", "2"}}},
            {"settings",
             {{"timing_view", "three_quarter"},
              {"rounds", rounds},
              {"views", {{{"name", "three_quarter"}}}}}},
            {"configurations", entries},
            {"disagreements", nlohmann::json::array()},
            {"diagnostics", nlohmann::json::array()},
            {"ok", true}};
    FakeRun run;
    run.manifest = dir.Write("manifest/manifest.json", manifest.dump(2));
    run.results = dir.Write("render/results.json", results.dump(2));
    return run;
}

// Every preset of the whitepaper table plus the reference, with times chosen per row.
std::vector<FakeConfiguration> WhitepaperConfigurations() {
    return {
            {"water:", {"reflection_only"}, 10.0, 6, true, "water", 50},
            {"water:ENABLE_REFRACTION", {"reflection_refraction"}, 24.0, 4, true, "water", 80},
            {"water:ENABLE_WATER_COLOUR", {"reflection_water_colour"}, 10.9, 5, true, "water", 60},
            {"water:ENABLE_ALPHA_BLEND", {"reflection_alpha_blend"}, 11.0, 5, true, "water", 55},
            {"water:FULL", {"full"}, 30.0, 2, true, "water", 200},
            {"water:FULL_NO_FOG", {"full_no_fog"}, 29.0, 3, true, "water", 190},
            {"water:CONST", {"full_constant_mix"}, 25.0, 3, true, "water", 150},
            {"water:UNSCALED", {"full_unscaled_distortion"}, 29.9, 3, true, "water", 195},
            {"water:FULL@lowres",
             {"full_low_res_water"},
             26.0,
             3,
             true,
             "water",
             200,
             {{"low_res_water", true}}},
            {"water:CUBE", {"full_cubemap_normalise"}, 36.0, 2, true, "water", 190},
            {"water_uniform:FULL", {"full_uniform_bools"}, 30.3, 2, true, "water_uniform", 400},
            {"water:FULL@discard",
             {"full_clip_discard"},
             40.0,
             2,
             true,
             "water",
             200,
             {{"clip", "discard"}}},
            {"water:FULL@refl128",
             {"full_reflection_128"},
             27.0,
             3,
             true,
             "water",
             200,
             {{"reflection_size", 128}}},
            {"water:EXACT@refl512",
             {"reference"},
             45.0,
             0,
             true,
             "water",
             220,
             {{"reflection_size", 512}}},
    };
}

PairedRatio Ratio(double ratio, double low, double high) {
    PairedRatio r;
    r.ratio = ratio;
    r.ci = {low, high};
    r.pairs = 40;
    return r;
}

const WhitepaperRow& Row(int number) {
    return WhitepaperRows()[static_cast<std::size_t>(number - 1)];
}

TEST(ReportWhitepaperTable, HasElevenRowsWithPresetsAndDirectionOnlyRowsEightToEleven) {
    ASSERT_EQ(WhitepaperRows().size(), 11u);
    for (const WhitepaperRow& row : WhitepaperRows()) {
        EXPECT_FALSE(row.baseline_preset.empty()) << row.number;
        EXPECT_FALSE(row.candidate_preset.empty()) << row.number;
        EXPECT_FALSE(row.llvmpipe_note.empty()) << row.number;
        EXPECT_EQ(row.kind == FigureKind::kDirection, row.number >= 8) << row.number;
    }
    EXPECT_EQ(Row(1).whitepaper_percent, -60.0);
    EXPECT_EQ(Row(4).baseline_preset, "full");
    EXPECT_EQ(Row(4).candidate_preset, "full_no_fog");
    EXPECT_EQ(Row(9).baseline_preset, "full_uniform_bools");
    EXPECT_EQ(Row(10).baseline_preset, "full_clip_discard");
}

TEST(ReportInputsTest, RowPresetsResolveToTheConfigurationsCarryingThem) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    for (const WhitepaperRow& row : WhitepaperRows()) {
        ASSERT_NE(loaded.inputs->FindByPreset(row.baseline_preset), nullptr) << row.number;
        ASSERT_NE(loaded.inputs->FindByPreset(row.candidate_preset), nullptr) << row.number;
    }
    EXPECT_EQ(loaded.inputs->FindByPreset("full_clip_discard")->id, "water:FULL@discard");
    EXPECT_EQ(loaded.inputs->FindByPreset("full_clip_discard")->clip, "discard");
    EXPECT_EQ(loaded.inputs->FindByPreset("full_reflection_128")->reflection_size, 128);
    EXPECT_EQ(loaded.inputs->FindByPreset("no_such_preset"), nullptr);
}

struct GradeCase {
    const char* name;
    int row;
    PairedRatio ratio;
    Verdict expected;
};

TEST(ReportGradeRow, VerdictsAreDecidedByTheIntervalAgainstHalfToTwiceTheFigure) {
    // Frame-time ratio r is a performance change of (1/r - 1) * 100 %.
    const std::vector<GradeCase> cases = {
            {"row 1: [-58.3, -54.5] lies within 30..120% of -60%", 1, Ratio(2.3, 2.2, 2.4),
             Verdict::kSameDirectionAndMagnitude},
            {"row 1: [-25.9, -20] is slower but wholly under half of 60%", 1,
             Ratio(1.3, 1.25, 1.35), Verdict::kSameDirectionDifferentMagnitude},
            {"row 1: [-33.3, -25.9] overlaps half of 60%", 1, Ratio(1.4, 1.35, 1.5),
             Verdict::kSameDirectionAndMagnitude},
            {"row 1: +25% faster is the opposite", 1, Ratio(0.8, 0.78, 0.82), Verdict::kOpposite},
            {"row 1: an interval through no change claims no direction", 1, Ratio(1.2, 0.9, 1.5),
             Verdict::kBelowResolution},
            {"row 2: [-1, 0] reaches no change", 2, Ratio(1.005, 1.0, 1.01),
             Verdict::kBelowResolution},
            {"row 2: [-9.1, -6.5] lies within 4.5..18% of -9%", 2, Ratio(1.087, 1.07, 1.1),
             Verdict::kSameDirectionAndMagnitude},
            {"row 2: [-3.8, -2] is under half of -9%", 2, Ratio(1.03, 1.02, 1.04),
             Verdict::kSameDirectionDifferentMagnitude},
            {"row 2: [-2, -1] excludes no change, but not by the margin", 2,
             Ratio(1.015, 1.01, 1.02), Verdict::kBelowResolution},
            {"row 6: [-1.5, +0.5] is negligible as the whitepaper's <1%", 6,
             Ratio(1.005, 0.995, 1.015), Verdict::kNegligibleAsClaimed},
            {"row 6: a definite 30% loss is not <1%", 6, Ratio(1.43, 1.4, 1.46),
             Verdict::kSameDirectionDifferentMagnitude},
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

TEST(ReportGradeRow, BelowResolutionSaysHowSmallTheChangeIs) {
    std::string reason;
    ASSERT_EQ(GradeRow(Row(3), Ratio(1.005, 0.99, 1.02), nullptr, &reason),
              Verdict::kBelowResolution);
    // The interval [-1.96%, +1.01%]: |change| < 2.0%.
    EXPECT_NE(reason.find("below resolution: |change| < 2.0%; the interval reaches within 1.5 "
                          "points of no change"),
              std::string::npos)
            << reason;
}

TEST(ReportGradeRow, HalvesThatDisagreeInSignAreSaidNotFoldedIntoTheCategory) {
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

TEST(ReportGradeRow, FirmVerdictsAreTheOnesASecondRunCouldContradict) {
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionAndMagnitude, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionDifferentMagnitude, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kOpposite, FigureKind::kPercent));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kNegligibleAsClaimed, FigureKind::kNegligible));
    EXPECT_TRUE(IsFirmVerdict(Verdict::kSameDirectionOnly, FigureKind::kDirection));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kSameDirectionOnly, FigureKind::kPercent));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kBelowResolution, FigureKind::kDirection));
    EXPECT_FALSE(IsFirmVerdict(Verdict::kFailed, FigureKind::kPercent));
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

TEST(ReportStaticCost, RankCorrelationAndLargestDisagreementsOnKnownInputs) {
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

// The HTML tags of a heading removed and its entities decoded: the text a reader sees.
std::string HeadingText(std::string html) {
    std::string text;
    bool in_tag = false;
    for (char c : html) {
        if (c == '<' || c == '>') {
            in_tag = c == '<';
        } else if (!in_tag) {
            text += c;
        }
    }
    for (const auto& [entity, plain] : {std::pair<std::string, std::string>{"&lt;", "<"},
                                        {"&gt;", ">"},
                                        {"&quot;", "\""},
                                        {"&amp;", "&"}}) {
        for (std::size_t at = text.find(entity); at != std::string::npos;
             at = text.find(entity, at + plain.size())) {
            text.replace(at, entity.size(), plain);
        }
    }
    return text;
}

// Both pages are rendered from one document, so every heading of index.html (section, sub-
// heading, image panel, folded table) is a heading of report.md too. Before the document model
// the Markdown lacked the failed-configuration and pruned-rule headings.
TEST(ReportWriterTest, MarkdownHasEveryHeadingTheHtmlHas) {
    TempDir dir;
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    configurations[2].ok = false;  // a failed configuration adds its table and heading
    const FakeRun run = WriteFakeRun(dir, configurations);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string html = ReadText(written.folder / "index.html");
    const std::string md = ReadText(written.folder / "report.md");
    int headings = 0;
    for (const auto& [open, close, prefix] :
         {std::tuple<std::string, std::string, std::string>{"<h2", "</h2>", "## "},
          {"<h3", "</h3>", "### "},
          {"<summary>", "</summary>", "### "}}) {
        for (std::size_t at = html.find(open); at != std::string::npos;
             at = html.find(open, at + 1)) {
            const std::size_t start = html.find('>', at) + 1;
            const std::size_t end = html.find(close, start);
            ASSERT_NE(end, std::string::npos);
            const std::string text = HeadingText(html.substr(start, end - start));
            EXPECT_NE(md.find("\n" + prefix + text + "\n\n"), std::string::npos) << text;
            ++headings;
        }
    }
    EXPECT_GT(headings, 20);
    EXPECT_NE(md.find("### Failed configurations\n\n| configuration | status | why |"),
              std::string::npos)
            << md;
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

TEST(ReportInputsTest, CorruptManifestIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("manifest/manifest.json", "{\"schema\": \"tidepool.manifest\", \"vers");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error.rfind(run.manifest.string() + ": not valid JSON", 0), 0u)
            << loaded.error;
}

TEST(ReportInputsTest, MissingResultsFileIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    std::filesystem::remove(run.results);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": no such file");
}

TEST(ReportInputsTest, ForeignSchemaIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/results.json", R"({"schema": "something.else", "schema_version": 1})");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": schema is not 'tidepool.render-results'");
}

// Every stage file carries its version under "version"; results.json once said
// "schema_version", and old runs still report.
TEST(ReportInputsTest, ResultsWithTheOldVersionKeyStillLoadAndAWrongVersionIsNamed) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    results.erase("version");
    results["schema_version"] = 1;
    dir.Write("render/results.json", results.dump());
    ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_TRUE(loaded.inputs) << loaded.error;
    results["schema_version"] = 2;
    dir.Write("render/results.json", results.dump());
    loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": schema_version must be 1");
    results.erase("schema_version");
    dir.Write("render/results.json", results.dump());
    loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": version must be 1");
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

TEST(ReportWriterTest, WritesAllFormatsAndReplacesOnlyItsOwnFolder) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ReportOptions options;
    options.name = "t";
    const ReportModelResult built = BuildReportModel(*loaded.inputs, options);
    ASSERT_TRUE(built.model) << built.error;
    WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    for (const char* file :
         {"index.html", "report.md", "data.json", "charts/accuracy.svg", "charts/whitepaper.svg",
          "charts/static_cost.svg", "images/reference-three_quarter.png"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(written.folder / file)) << file;
    }
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["schema"], "tidepool.report");
    EXPECT_EQ(data["version"], 1);
    EXPECT_EQ(data["whitepaper_rows"].size(), 11u);
    EXPECT_EQ(data["stability"]["present"], false);
    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
    EXPECT_NE(html.find("tidepool stability"), std::string::npos);
    // Rewriting replaces the earlier report; no staging folder is left behind.
    written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    for (const auto& entry : std::filesystem::directory_iterator(dir.Path() / "out")) {
        EXPECT_EQ(entry.path().filename(), "t");
    }
    // A folder the writer did not make is never replaced.
    dir.Write("out2/t/precious.txt", "keep me");
    written = WriteReport(*built.model, dir.Path() / "out2");
    EXPECT_NE(written.error.find("not written by tidepool"), std::string::npos) << written.error;
    EXPECT_TRUE(written.refused);
    EXPECT_TRUE(std::filesystem::exists(dir.Path() / "out2/t/precious.txt"));
    // Nor is one that merely holds a data.json: only the marker file says a report is ours.
    dir.Write("out3/t/data.json", "{}");
    written = WriteReport(*built.model, dir.Path() / "out3");
    EXPECT_TRUE(written.refused) << written.error;
    EXPECT_EQ(ReadText(dir.Path() / "out3/t/data.json"), "{}");
}

TEST(ReportWriterTest, StabilityTablesAreRenderedGenerically) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/stability.json", R"js({"schema": "tidepool.stability", "version": 1,
        "cases": [{"name": "grazing_fresnel", "description": "cos near 0", "kind": "fresnel",
                   "variants_checked": 4, "nan_count": 0, "inf_count": 0, "max_error": 0.001,
                   "bound": 0.01, "passed": true, "fix": "clamp"}],
        "precision": [{"expression": "pow(1-c,5)", "max_abs_error_float": 1e-7,
                       "max_abs_error_fp16": 0.002, "max_rel_error_fp16": 0.01,
                       "loses_precision": false, "note": "ok"}],
        "guards": [{"guard": "max(dot,0)", "max_channel_diff_normal_views": 0,
                    "tolerance": 1}]})js");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ASSERT_TRUE(loaded.inputs->stability);
    const ReportModelResult built = BuildReportModel(*loaded.inputs, ReportOptions{});
    ASSERT_TRUE(built.model) << built.error;
    const WrittenReport written = WriteReport(*built.model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("| grazing_fresnel | cos near 0 | fresnel | 4 | 0 | 0 | 0.001 | 0.01 | true "
                      "| clamp |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("pow(1-c,5)"), std::string::npos);
    EXPECT_NE(md.find("max(dot,0)"), std::string::npos);
}

// The whitepaper configurations with CPU times: 1.5x the wall time (llvmpipe's two threads)
// except the cube-map normalisation, whose CPU time is below full's (wall: above).
std::vector<FakeConfiguration> WithCpuTimes(std::vector<FakeConfiguration> configurations) {
    for (FakeConfiguration& c : configurations) {
        c.cpu_ms = c.presets.front() == "full_cubemap_normalise" ? 40.0 : c.ms * 1.5;
    }
    return configurations;
}

ReportModel BuildOrFail(const ReportInputs& inputs) {
    ReportModelResult built = BuildReportModel(inputs, ReportOptions{});
    EXPECT_TRUE(built.model) << built.error;
    return built.model ? std::move(*built.model) : ReportModel{};
}

TEST(ReportClockTest, ResultsWithoutCpuSamplesAreComparedOnWallTime) {
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

TEST(ReportClockTest, CpuSamplesOnEveryConfigurationMakeEveryComparisonUseCpuTime) {
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

TEST(ReportClockTest, OneConfigurationWithoutCpuSamplesKeepsEveryComparisonOnWallTime) {
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

// A plans.json of two scenes as `tidepool plan --all` writes it (docs/SCENES.md).
constexpr const char* kPlansJson = R"js({"schema": "tidepool.plans", "version": 1,
    "size": [160, 120], "timing": {"resolution_points": 3.0, "min_pairs": 20, "max_pairs": 200},
    "plans": [
    {"scene": "murky_pond", "description": "murky", "target": {"min_psnr_db": 30},
     "chosen": {"id": "water:ENABLE_FOG,ENABLE_WATER_COLOUR@refl128", "variant": "water:x",
                "passes": ["reflection", "main"]},
     "full": {"id": "water:FULL", "variant": "water:FULL",
              "passes": ["reflection", "refraction", "main"]},
     "time_ms_chosen": 8.06, "time_ms_full": 15.0, "time_change_percent": -46.3,
     "error": {"psnr_db": 41.1, "ssim": 0.998, "share_visible": 0.018}, "met": true,
     "dropped": [{"effect": "refraction", "reason": "fog hides the floor at 0.8",
                  "psnr_change_db": 41.1, "time_change_percent": -37}],
     "kept": [{"effect": "fog", "reason": "fog breaks the target without it",
               "psnr_change_db": 12.5, "time_change_percent": -2}],
     "passes_saved": 1, "draws_saved": 5, "pixels_saved": 19200},
    {"scene": "open_sea", "target": {"min_psnr_db": 30}, "chosen": {"id": "water:FULL"},
     "full": {"id": "water:FULL"}, "time_ms_chosen": 7.4, "time_ms_full": 7.4,
     "time_change_percent": 0, "error": {"psnr_db": 99, "ssim": 1, "share_visible": 0},
     "met": false, "dropped": [], "kept": [], "passes_saved": 0, "draws_saved": 0,
     "pixels_saved": 0}]})js";

TEST(ReportScenesTest, PlansBesideTheResultsAreShownPerSceneWithEveryDecisionAndReason) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/plans.json", kPlansJson);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    ASSERT_TRUE(loaded.inputs->plans) << loaded.inputs->plans_error;
    const ReportModel model = BuildOrFail(*loaded.inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 8. Scenes"), std::string::npos);
    // The method as plans.json records it, not placeholders.
    EXPECT_NE(md.find("at 160x120, each candidate timed against the full effect pair by pair "
                      "until its 95% interval is within +/-3.0 points (20 to 200 pairs)"),
              std::string::npos)
            << md;
    EXPECT_EQ(md.find("paired rounds of"), std::string::npos);
    EXPECT_NE(md.find("| murky_pond | water:ENABLE_FOG,ENABLE_WATER_COLOUR@refl128 | water:FULL | "
                      "8.06 / 15.00 | -46% | 41.1 dB, SSIM 0.998, 1.8% | min_psnr_db 30 | met | "
                      "1 / 5 / 19200 |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("| refraction | dropped | 41.1 dB | -37% | fog hides the floor at 0.8 |"),
              std::string::npos);
    EXPECT_NE(md.find("| fog | kept | 12.5 dB | -2% | fog breaks the target without it |"),
              std::string::npos);
    EXPECT_NE(md.find("identical, SSIM 1.000"), std::string::npos);  // 99 dB = identical
    EXPECT_NE(md.find("1 scene(s) NOT met"), std::string::npos);
    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("<h2 id=\"scenes\">8. Scenes</h2>"), std::string::npos);
    EXPECT_NE(html.find("fog hides the floor at 0.8"), std::string::npos);
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["scenes"]["present"], true);
    EXPECT_EQ(data["scenes"]["plans"].size(), 2u);
    EXPECT_EQ(data["scenes"]["plans"][0]["dropped"][0]["effect"], "refraction");
    EXPECT_EQ(data["inputs"]["plans"], loaded.inputs->plans_path.string());
}

TEST(ReportScenesTest, MissingPlansSayHowToProduceThem) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    EXPECT_FALSE(loaded.inputs->plans);
    EXPECT_EQ(loaded.inputs->plans_error, "");
    const ReportModel model = BuildOrFail(*loaded.inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");
    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 8. Scenes\n\nNo scene plans were found"), std::string::npos) << md;
    EXPECT_NE(md.find("tidepool plan --all --out DIR"), std::string::npos);
    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    EXPECT_EQ(data["scenes"]["present"], false);
    EXPECT_EQ(data["inputs"]["plans"], nullptr);
}

TEST(ReportScenesTest, CorruptOrForeignPlansAreAnErrorNamingTheFileInTheReport) {
    for (const std::string& content :
         {std::string("{\"schema\": \"tidepool.pla"), std::string(R"({"schema": "other"})"),
          std::string(R"({"schema": "tidepool.plans", "version": 1, "plans": [{"x": 1}]})")}) {
        TempDir dir;
        const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
        const std::filesystem::path plans = dir.Write("render/plans.json", content);
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        ASSERT_TRUE(loaded.inputs) << loaded.error;  // the rest of the report is still built
        EXPECT_FALSE(loaded.inputs->plans);
        EXPECT_EQ(loaded.inputs->plans_error.rfind(plans.string() + ": ", 0), 0u)
                << loaded.inputs->plans_error;
        const ReportModel model = BuildOrFail(*loaded.inputs);
        const WrittenReport written = WriteReport(model, dir.Path() / "out");
        ASSERT_EQ(written.error, "");
        const std::string md = ReadText(written.folder / "report.md");
        EXPECT_NE(md.find(loaded.inputs->plans_error), std::string::npos) << md;
        const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
        EXPECT_EQ(data["scenes"]["error"], loaded.inputs->plans_error);
    }
}

// The whitepaper configurations plus the reflection techniques and the depth optics, with the
// passes each runs: cube map and Fourier have no reflection pass. Images: reflection_only has
// mark 6 at both views; cubemap_reflection draws the same image (identical), fourier_reflection
// a different one (mark 0 at both); full has mark 2 at both views; full_cubemap_reflection
// matches it at three_quarter but not at grazing (the view where it breaks);
// full_fourier_reflection differs at both; full_depth_optics changes three_quarter only.
std::vector<FakeConfiguration> ReflectionConfigurations() {
    std::vector<FakeConfiguration> configurations = WhitepaperConfigurations();
    for (FakeConfiguration& c : configurations) {
        c.pass_names = {"reflection", "main"};
        c.draw_calls = 20;
        if (c.presets.front() == "reflection_only") {
            c.grazing_mark = 6;
        }
        if (c.presets.front() == "full") {
            c.pass_names = {"reflection", "refraction", "main"};
            c.draw_calls = 30;
            c.grazing_mark = 2;
        }
    }
    const std::vector<std::string> main_only = {"main"};
    const std::vector<std::string> refraction_main = {"refraction", "main"};
    configurations.push_back({"water:REFLECTION_CUBEMAP",
                              {"cubemap_reflection"},
                              8.0,
                              6,
                              true,
                              "water",
                              45,
                              {},
                              0,
                              main_only,
                              12,
                              6});
    configurations.push_back({"water:REFLECTION_FOURIER",
                              {"fourier_reflection"},
                              12.5,
                              0,
                              true,
                              "water",
                              70,
                              {},
                              0,
                              main_only,
                              12,
                              0});
    configurations.push_back({"water:CUBE_FULL",
                              {"full_cubemap_reflection"},
                              24.0,
                              2,
                              true,
                              "water",
                              190,
                              {},
                              0,
                              refraction_main,
                              22,
                              9});
    configurations.push_back({"water:FOURIER_FULL",
                              {"full_fourier_reflection"},
                              26.0,
                              5,
                              true,
                              "water",
                              230,
                              {},
                              0,
                              refraction_main,
                              22,
                              7});
    configurations.push_back({"water:OPTICS",
                              {"full_depth_optics"},
                              33.0,
                              4,
                              true,
                              "water",
                              260,
                              {},
                              0,
                              {"reflection", "refraction", "main"},
                              30,
                              2});
    return configurations;
}

ReportModel BuildFrom(const FakeRun& run, std::optional<ReportInputs>* keep) {
    ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_TRUE(loaded.inputs) << loaded.error;
    if (!loaded.inputs) {
        return {};
    }
    *keep = std::move(loaded.inputs);
    return BuildOrFail(**keep);
}

TEST(ReportReflectionTest, SectionListsTheFourComparisonsWithPassesFromThePassNames) {
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

TEST(ReportReflectionTest, ErrorAgainstPlanarIsIdenticalWhenImagesMatchAndFiniteWhenTheyDiffer) {
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

TEST(ReportReflectionTest, MissingOrFailedCandidateIsShownAsSuchNotDropped) {
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

TEST(ReportReflectionTest, SectionAppearsInHtmlMarkdownAndDataJson) {
    TempDir dir;
    std::optional<ReportInputs> inputs;
    const ReportModel model = BuildFrom(WriteFakeRun(dir, ReflectionConfigurations()), &inputs);
    const WrittenReport written = WriteReport(model, dir.Path() / "out");
    ASSERT_EQ(written.error, "");

    const std::string md = ReadText(written.folder / "report.md");
    EXPECT_NE(md.find("## 9. Reflection techniques"), std::string::npos);
    EXPECT_NE(md.find("| cube-map reflection (reflection only) | reflection_only [water:] → "
                      "cubemap_reflection [water:REFLECTION_CUBEMAP] | measured | reflection, "
                      "main → main (no reflection pass) | 20 → 12 | 10.00 / 8.00 | +25.0%, "
                      "faster |"),
              std::string::npos)
            << md;
    EXPECT_NE(md.find("| identical | 1.0000 | 0.00% | three_quarter: identical; grazing: "
                      "identical |"),
              std::string::npos);
    EXPECT_NE(md.find("grazing: "), std::string::npos);
    EXPECT_NE(md.find("(worst)"), std::string::npos);
    EXPECT_NE(md.find("### Depth optics"), std::string::npos);
    EXPECT_NE(md.find("| depth optics (full effect) | full [water:FULL] → full_depth_optics "
                      "[water:OPTICS] | measured |"),
              std::string::npos);
    EXPECT_NE(md.find("| this configuration | planar reflection (full) | difference |"),
              std::string::npos);
    EXPECT_NE(md.find("images/reflection-full_fourier_reflection-three_quarter.png"),
              std::string::npos);
    EXPECT_TRUE(std::filesystem::is_regular_file(written.folder /
                                                 "images/planar-full-three_quarter.png"));
    EXPECT_TRUE(std::filesystem::is_regular_file(
            written.folder / "images/reflection-full_cubemap_reflection-three_quarter-diff.png"));

    const std::string html = ReadText(written.folder / "index.html");
    EXPECT_NE(html.find("<h2 id=\"reflections\">9. Reflection techniques</h2>"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#reflections\">Reflection techniques</a>"), std::string::npos);
    EXPECT_NE(html.find("<h3 id=\"depth-optics\">Depth optics</h3>"), std::string::npos);
    EXPECT_NE(html.find("<tr class=\"technique-cubemap-full\">"), std::string::npos);
    EXPECT_NE(html.find("<figcaption>planar reflection (full)</figcaption>"), std::string::npos);
    // Every tag the section opens is closed (the page stays valid), and its panels' images
    // are embedded like the others.
    const std::string section = html.substr(html.find("<h2 id=\"reflections\">"));
    for (const auto& [open, close] :
         std::vector<std::pair<std::string, std::string>>{{"<table", "</table>"},
                                                          {"<tr", "</tr>"},
                                                          {"<div", "</div>"},
                                                          {"<figure>", "</figure>"},
                                                          {"<p", "</p>"},
                                                          {"<h3", "</h3>"}}) {
        std::size_t opened = 0;
        std::size_t closed = 0;
        for (std::size_t at = section.find(open); at != std::string::npos;
             at = section.find(open, at + 1)) {
            // "<p" also starts "<path"; the section has no SVG, but count only <p> and <p ...>.
            const char next = section[at + open.size()];
            if (open != "<p" || next == '>' || next == ' ') {
                ++opened;
            }
        }
        for (std::size_t at = section.find(close); at != std::string::npos;
             at = section.find(close, at + 1)) {
            ++closed;
        }
        EXPECT_EQ(opened, closed) << open;
    }
    std::size_t embedded = 0;
    for (std::size_t at = section.find("src=\"data:image/png;base64,"); at != std::string::npos;
         at = section.find("src=\"data:image/png;base64,", at + 1)) {
        ++embedded;
    }
    EXPECT_EQ(embedded, 6u);  // two panels of three images

    const nlohmann::json data = nlohmann::json::parse(ReadText(written.folder / "data.json"));
    const nlohmann::json& section_json = data["reflection_techniques"];
    ASSERT_EQ(section_json["comparisons"].size(), 4u);
    const nlohmann::json& cubemap = section_json["comparisons"][0];
    EXPECT_EQ(cubemap["kind"], "cubemap");
    EXPECT_EQ(cubemap["baseline"]["pass_names"], nlohmann::json({"reflection", "main"}));
    EXPECT_EQ(cubemap["candidate"]["pass_names"], nlohmann::json({"main"}));
    EXPECT_EQ(cubemap["candidate"]["draw_calls"], 12);
    EXPECT_EQ(cubemap["passes_dropped"], nlohmann::json({"reflection"}));
    EXPECT_NEAR(cubemap["measured_percent"].get<double>(), 25.0, 0.05);
    EXPECT_EQ(cubemap["direction"], "faster");
    EXPECT_EQ(cubemap["error"]["identical"], true);
    EXPECT_EQ(cubemap["error"]["psnr_db"], nullptr);
    const nlohmann::json& fourier = section_json["comparisons"][1];
    EXPECT_EQ(fourier["error"]["identical"], false);
    EXPECT_TRUE(fourier["error"]["psnr_db"].is_number());
    EXPECT_EQ(section_json["comparisons"][2]["error"]["worst_view"], "grazing");
    EXPECT_EQ(section_json["comparisons"][2]["error"]["per_view"].size(), 2u);
    EXPECT_EQ(section_json["images"].size(), 2u);
    EXPECT_EQ(section_json["images"][0]["compared_with"], "full");
    ASSERT_EQ(data["depth_optics"]["comparisons"].size(), 1u);
    EXPECT_EQ(data["depth_optics"]["comparisons"][0]["candidate"]["configuration"], "water:OPTICS");
}

TEST(ReportReflectionTest, ResultsWithoutPassNamesStillLoadAndShowPassesAsUnknown) {
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

namespace {

// Rewrites one stage file of a fake run through `edit` and returns what loading then says.
template <typename Edit>
ReportInputsResult LoadEdited(const TempDir& dir, const std::filesystem::path& file, Edit edit) {
    nlohmann::json json = nlohmann::json::parse(ReadText(file));
    edit(json);
    dir.Write(std::filesystem::relative(file, dir.Path()).string(), json.dump());
    return LoadReportInputs(dir.Path() / "manifest/manifest.json",
                            dir.Path() / "render/results.json");
}

}  // namespace

// Corrupt in meaning, though well typed: each replaced a good report with an empty or wrong
// one and exit 0 before.
TEST(ReportInputsTest, InputsCorruptInMeaningAreErrorsNamingTheFileAndField) {
    struct Case {
        const char* what;
        bool manifest;  // edit the manifest, else results.json
        void (*edit)(nlohmann::json&);
        const char* message;
    };
    const std::vector<Case> cases = {
            {"empty configurations", false,
             [](nlohmann::json& j) { j["configurations"] = nlohmann::json::array(); },
             "'configurations' is empty"},
            {"duplicate configuration id", false,
             [](nlohmann::json& j) { j["configurations"][1]["id"] = j["configurations"][0]["id"]; },
             "appears more than once"},
            {"variant not an object", true, [](nlohmann::json& j) { j["variants"][0] = 7; },
             "'variants[0]' has the wrong type (expected object, found number)"},
            {"variant without id", true, [](nlohmann::json& j) { j["variants"][1].erase("id"); },
             "'variants[1].id' is not a non-empty string"},
            {"variant valid not boolean", true,
             [](nlohmann::json& j) { j["variants"][0]["valid"] = "yes"; },
             "'variants[0].valid' has the wrong type"},
            {"absolute image path", false,
             [](nlohmann::json& j) { j["configurations"][0]["views"][0]["image"] = "/etc/passwd"; },
             "'image' must be a path inside the results folder, not '/etc/passwd'"},
            {"image path with ..", false,
             [](nlohmann::json& j) {
                 j["configurations"][0]["views"][0]["image"] = "images/../../secret.png";
             },
             "'image' must be a path inside the results folder, not 'images/../../secret.png'"},
            // Wrongly typed fields (issue 15 class 3): an error naming the field, not an abort.
            {"uniform_bools a string", false,
             [](nlohmann::json& j) { j["configurations"][0]["uniform_bools"] = "yes"; },
             "'configurations[0].uniform_bools' has the wrong type (expected bool, found string)"},
            {"driver.valid a number", false,
             [](nlohmann::json& j) { j["configurations"][0]["driver"]["valid"] = 1; },
             "'configurations[0].driver.valid' has the wrong type (expected bool, found number)"},
            {"passes.culling a string", false,
             [](nlohmann::json& j) { j["configurations"][0]["passes"]["culling"] = "no"; },
             "'configurations[0].passes.culling' has the wrong type (expected bool, found "
             "string)"},
    };
    for (const Case& c : cases) {
        TempDir dir;
        const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
        const ReportInputsResult loaded =
                LoadEdited(dir, c.manifest ? run.manifest : run.results, c.edit);
        EXPECT_FALSE(loaded.inputs) << c.what;
        const std::filesystem::path file = c.manifest ? run.manifest : run.results;
        EXPECT_EQ(loaded.error.rfind(file.string() + ": ", 0), 0u)
                << c.what << ": " << loaded.error;
        EXPECT_NE(loaded.error.find(c.message), std::string::npos)
                << c.what << ": " << loaded.error;
    }
}
