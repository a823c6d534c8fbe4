#include "tidepool/SourceAssembler.h"

#include <gtest/gtest.h>

namespace tidepool {
namespace {

TEST(SourceAssemblerTest, DriverSourceReplacesVersionLineAndKeepsTheUsersNumbering) {
    const std::string source = "#version 100\nprecision mediump float;\nvoid main() {}\n";
    EXPECT_EQ(AssembleDriverSource(source, {"ENABLE_FOG", "ENABLE_REFRACTION"}, Stage::kFragment,
                                   GlslTarget::kEs100),
              "#version 100\n#define ENABLE_FOG 1\n#define ENABLE_REFRACTION 1\n#line 2\n"
              "precision mediump float;\nvoid main() {}\n");
}

TEST(SourceAssemblerTest, FileWithoutVersionLineStartsAtLineOne) {
    EXPECT_EQ(AssembleDriverSource("void main() {}\n", {}, Stage::kVertex, GlslTarget::kEs100),
              "#version 100\n#line 1\nvoid main() {}\n");
}

TEST(SourceAssemblerTest, Es300TargetAddsTheCompatibilityBlockBeforeTheDefines) {
    const std::string out = AssembleDriverSource("#version 100\nvoid main() {}\n", {"A"},
                                                 Stage::kFragment, GlslTarget::kEs300);
    EXPECT_EQ(out.rfind("#version 300 es\n", 0), 0U);
    EXPECT_NE(out.find("#define gl_FragColor tp_FragColor\n"), std::string::npos);
    EXPECT_NE(out.find("#define A 1\n#line 2\nvoid main() {}\n"), std::string::npos);
}

TEST(SourceAssemblerTest, PreambleHasOneDefinePerLine) {
    EXPECT_EQ(DefinePreamble({"A", "B"}), "#define A 1\n#define B 1\n");
    EXPECT_EQ(DefinePreamble({}), "");
}

TEST(SourceAssemblerTest, FindVersionLineReadsOnlyTheFirstLine) {
    EXPECT_EQ(FindVersionLine("#version 100\nx"), "#version 100");
    EXPECT_EQ(FindVersionLine("  #version 300 es\r\n"), "#version 300 es");
    EXPECT_EQ(FindVersionLine("// c\n#version 100\n"), "");
}

}  // namespace
}  // namespace tidepool
