// Mesa's info-log format into diagnostics at the user's file and line.
#include "tidepool/runner/MesaInfoLog.h"

#include <gtest/gtest.h>

namespace tidepool::runner {
namespace {

TEST(MesaInfoLogTest, PositionedErrorsKeepLineAndMesasColumnWithoutSource) {
    const std::vector<Diagnostic> d = ParseMesaInfoLog(
            "0:5(22): error: `x' undeclared\n0:5(17): error: cannot construct `vec4' from a "
            "non-numeric data type\n\n",
            "shaders/water.fsh", "water:ENABLE_FOG");
    ASSERT_EQ(d.size(), 2U);
    EXPECT_EQ(FormatDiagnostic(d[0]),
              "shaders/water.fsh:5:22: error: `x' undeclared [water:ENABLE_FOG]");
    EXPECT_EQ(d[1].line, 5);
    EXPECT_EQ(d[1].column, 17);
}

// Mesa's preprocessor collapses blank runs to one space before it counts columns, so
// `    colour = undeclaredThing` reports column 11 for what is column 14 in the file.
TEST(MesaInfoLogTest, ColumnsMapBackThroughCollapsedBlanks) {
    const std::string source = "#version 100\nvoid main()\n{\n    colour =  undeclaredThing;\n}\n";
    const std::vector<Diagnostic> d =
            ParseMesaInfoLog("0:4(11): error: `undeclaredThing' undeclared\n", "u.fsh", "", source);
    ASSERT_EQ(d.size(), 1U);
    EXPECT_EQ(d[0].column, 15);  // two blanks after '=' also count once
    EXPECT_EQ(MapMesaColumn("x = y", 5), 5);
    EXPECT_EQ(MapMesaColumn("\t\tx", 2), 3);
    EXPECT_EQ(MapMesaColumn("ab", 9), 9);
}

TEST(MesaInfoLogTest, WarningsAndUnpositionedLinkErrors) {
    const std::vector<Diagnostic> d = ParseMesaInfoLog(
            "0:12(3): warning: `foo' used uninitialized\nerror: vertex shader output `Colour' is "
            "not read\n  by the fragment shader\n",
            "shaders/model.vsh", "model:");
    ASSERT_EQ(d.size(), 2U);
    EXPECT_EQ(d[0].severity, Severity::kWarning);
    EXPECT_EQ(d[0].line, 12);
    EXPECT_EQ(d[1].severity, Severity::kError);
    EXPECT_EQ(d[1].line, 0);
    EXPECT_EQ(d[1].message, "vertex shader output `Colour' is not read by the fragment shader");
}

TEST(MesaInfoLogTest, UnknownTextBecomesOneDiagnostic) {
    const std::vector<Diagnostic> d = ParseMesaInfoLog("something odd", "f.fsh", "");
    ASSERT_EQ(d.size(), 1U);
    EXPECT_EQ(d[0].message, "something odd");
    EXPECT_TRUE(ParseMesaInfoLog("", "f.fsh", "").empty());
}

}  // namespace
}  // namespace tidepool::runner
