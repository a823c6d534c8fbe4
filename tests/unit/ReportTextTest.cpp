// The report's small formatting pieces (reports/src/ReportText.h): numbers with their sign and
// unit, infinities and NaN, intervals, HTML escaping, and the names the report's prose uses.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "ReportText.h"

namespace tidepool::report {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTextNan = std::numeric_limits<double>::quiet_NaN();

// A NUL or an escape in a name made the SVG charts fail to parse as XML.
TEST(ReportTextTest, HtmlEscapedReplacesWhatXmlDoesNotAllow) {
    EXPECT_EQ(HtmlEscaped(std::string("a\0b\x01"
                                      "c\x1b"
                                      "[31m\td\ne\rf",
                                      16)),
              "a\xEF\xBF\xBD"
              "b\xEF\xBF\xBD"
              "c\xEF\xBF\xBD[31m\td\ne\rf");
    EXPECT_EQ(HtmlEscaped("x\xEF\xBF\xBEy\xEF\xBF\xBFz\xEF\xBF\xBD"),
              "x\xEF\xBF\xBDy\xEF\xBF\xBDz\xEF\xBF\xBD");
    EXPECT_EQ(HtmlEscaped("\xEF\xBF"), "\xEF\xBF");  // cut short: left as it is
}

TEST(ReportTextTest, HtmlEscapedEscapesTheFourMarkupCharactersOnly) {
    EXPECT_EQ(HtmlEscaped("a & b < c > d \"e\" 'f'"), "a &amp; b &lt; c &gt; d &quot;e&quot; 'f'");
    EXPECT_EQ(HtmlEscaped(""), "");
}

TEST(ReportTextTest, FixedAndSignedRoundWithTheirUnitAndNameInfinityAndNan) {
    EXPECT_EQ(Fixed(3.14159, 2, " ms"), "3.14 ms");
    EXPECT_EQ(Fixed(-2.0 / 3.0, 3), "-0.667");
    EXPECT_EQ(Fixed(kInf, 1, " dB"), "inf");
    EXPECT_EQ(Fixed(-kInf, 1), "-inf");
    EXPECT_EQ(Fixed(kTextNan, 1), "–");
    EXPECT_EQ(Signed(4.25, 1, "%"), "+4.2%");
    EXPECT_EQ(Signed(-4.0, 1, "%"), "-4.0%");
    EXPECT_EQ(Signed(kInf, 1), "+inf");
    EXPECT_EQ(Signed(-kInf, 1), "-inf");
    EXPECT_EQ(Signed(kTextNan, 1), "–");
}

TEST(ReportTextTest, IntervalTextIsSignedEndsOrADashWhenEitherIsUnknown) {
    EXPECT_EQ(IntervalText(Interval{-3.25, 1.5}, 1, "%"), "[-3.2%, +1.5%]");
    EXPECT_EQ(IntervalText(Interval{kTextNan, 1.5}, 1, "%"), "–");
    EXPECT_EQ(IntervalText(Interval{1.0, kTextNan}, 1, "%"), "–");
}

TEST(ReportTextTest, NamesForClockDirectionAndAMissingPanel) {
    EXPECT_EQ(ClockName(TimingClock::kCpu), "CPU");
    EXPECT_EQ(ClockName(TimingClock::kWall), "wall");
    EXPECT_EQ(DirectionText(1), "faster");
    EXPECT_EQ(DirectionText(-1), "slower");
    ImagePanel panel;
    EXPECT_EQ(PanelId(panel), "(missing)");
    MeasuredConfiguration configuration;
    configuration.id = "water:FOG";
    panel.configuration = &configuration;
    EXPECT_EQ(PanelId(panel), "water:FOG");
}

TEST(ReportTextTest, HowToSentencesNameTheCommandThatProducesTheMissingFile) {
    EXPECT_NE(StabilityHowTo().find("`tidepool stability`"), std::string::npos);
    EXPECT_NE(StabilityHowTo().find("stability.json"), std::string::npos);
    EXPECT_NE(PlansHowTo().find("`tidepool plan --all --out DIR`"), std::string::npos);
    EXPECT_NE(PlansHowTo().find("plans.json"), std::string::npos);
}

}  // namespace
}  // namespace tidepool::report
