// The report's charts as standalone SVG (reports/include/tidepool/report/ReportCharts.h): which
// points a scatter chart draws, its frontier line, escaping, and the whitepaper chart's bars.
#include "tidepool/report/ReportCharts.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "FakeReportRun.h"
#include "TempDir.h"

namespace tidepool::report {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::size_t Count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
        ++n;
    }
    return n;
}

TEST(ReportChartsTest, ScatterDrawsTheFinitePointsOnlyWithTheirTooltipsAndLabels) {
    const std::vector<ChartPoint> points = {
            {1, 2, "a", "first", false},
            {kNan, 3, "b", "no x", false},
            {2, std::numeric_limits<double>::infinity(), "", "", false},
            {3, 1, "", "third", true}};
    const std::string svg = ScatterSvg(points, {}, "ms", "1 - SSIM", "Time & error");
    EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0U);
    EXPECT_EQ(svg.substr(svg.size() - 6), "</svg>");
    EXPECT_EQ(Count(svg, "<circle"), 2U) << svg;
    EXPECT_NE(svg.find("<title>first</title>"), std::string::npos);
    EXPECT_EQ(svg.find("no x"), std::string::npos);
    EXPECT_EQ(Count(svg, "r=\"5\" fill=\"#c0392b\""), 1U);  // the highlighted point
    EXPECT_NE(svg.find("<title>Time &amp; error</title>"), std::string::npos);
    EXPECT_EQ(svg.find("<path"), std::string::npos);  // no frontier asked for
}

TEST(ReportChartsTest, FrontierIsAStepLineThroughTheDrawablePointsItNames) {
    const std::vector<ChartPoint> points = {
            {0, 0, "", "", false}, {10, 10, "", "", false}, {kNan, 5, "", "", false}};
    const std::string svg = ScatterSvg(points, {0, 2, 7, 1}, "x", "y", "t");
    ASSERT_EQ(Count(svg, "<path d=\""), 1U) << svg;
    const std::size_t d = svg.find("<path d=\"") + 9;
    const std::string path = svg.substr(d, svg.find('"', d) - d);
    // One move and one step: the NaN point and the index past the end are skipped.
    EXPECT_EQ(path.rfind('M', 0), 0U) << path;
    EXPECT_EQ(Count(path, " H"), 1U) << path;
    EXPECT_EQ(Count(path, " V"), 1U) << path;
}

TEST(ReportChartsTest, AChartWithoutDrawablePointsStillHasItsAxes) {
    const std::string svg = ScatterSvg({{kNan, kNan, "", "", false}}, {0}, "x", "y", "empty");
    EXPECT_EQ(Count(svg, "<circle"), 0U);
    EXPECT_EQ(svg.find("<path"), std::string::npos);
    EXPECT_EQ(Count(svg, "stroke=\"#ddd\""), 12U);  // six grid lines per axis
    EXPECT_EQ(svg.substr(svg.size() - 6), "</svg>");
}

TEST(ReportChartsTest, WhitepaperChartHasABarPerMeasuredRowAndNoneForAFailedOne) {
    const testing::TempDir dir;
    std::vector<testing::FakeConfiguration> configurations = testing::WhitepaperConfigurations();
    configurations[2].ok = false;  // reflection_water_colour: row 2
    std::optional<ReportInputs> inputs;
    const ReportModel model =
            testing::BuildFrom(testing::WriteFakeRun(dir, configurations), &inputs);
    ASSERT_EQ(model.rows.size(), 11U);
    const std::string svg = WhitepaperChartSvg(model);
    for (const RowComparison& row : model.rows) {
        EXPECT_EQ(svg.find("<title>row " + std::to_string(row.row.number) + ": ") !=
                          std::string::npos,
                  row.row.number != 2)
                << row.row.number;
        EXPECT_NE(svg.find(std::to_string(row.row.number) + ". " + row.candidate.preset),
                  std::string::npos)
                << row.row.number;  // every row keeps its label
    }
}

}  // namespace
}  // namespace tidepool::report
