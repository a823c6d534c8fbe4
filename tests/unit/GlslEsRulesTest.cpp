// The GLSL ES checks on source text (compiler/src/GlslEsRules.h): the token lines they read,
// the NUL-byte and macro-size checks before glslang runs, and where a name is first mentioned.
// The checks on parsed and linked stages are tested through the validator (GlslValidatorTest).
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "GlslEsRules.h"
#include "PipelineFixture.h"

namespace tidepool {
namespace {

using testing::Formatted;

std::vector<std::string> Texts(const std::vector<SourceToken>& line) {
    std::vector<std::string> texts;
    for (const SourceToken& token : line) {
        texts.emplace_back(token.text);
    }
    return texts;
}

TEST(GlslEsRulesTest, TokenLinesSplitIdentifiersFromPunctuationAndDropComments) {
    const auto lines = SourceTokenLines("vec4 a_1=b; // c d\n  x/*y*/.z\n");
    ASSERT_EQ(lines.size(), 3U);  // the text ends with a newline: an empty last line
    EXPECT_EQ(Texts(lines[0]), (std::vector<std::string>{"vec4", "a_1", "=", "b", ";"}));
    EXPECT_EQ(Texts(lines[1]), (std::vector<std::string>{"x", ".", "z"}));
    EXPECT_TRUE(lines[2].empty());
    EXPECT_TRUE(lines[0][0].identifier);
    EXPECT_FALSE(lines[0][2].identifier);
    EXPECT_EQ(lines[1][0].line, 2);
    EXPECT_EQ(lines[1][0].column, 3);
    EXPECT_EQ(lines[1][2].column, 10);
}

TEST(GlslEsRulesTest, BackslashNewlineJoinsLinesAndBlockCommentsKeepLineNumbers) {
    const auto joined = SourceTokenLines("#define A \\\n  1\nB");
    ASSERT_EQ(joined.size(), 2U);
    EXPECT_EQ(Texts(joined[0]), (std::vector<std::string>{"#", "define", "A", "1"}));
    EXPECT_EQ(joined[0][3].line, 2);
    const auto commented = SourceTokenLines("a /* one\ntwo */ b");
    ASSERT_EQ(commented.size(), 1U);
    EXPECT_EQ(Texts(commented[0]), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(commented[0][1].line, 2);
    EXPECT_EQ(commented[0][1].column, 8);
}

TEST(GlslEsRulesTest, NumbersComeOutInPieces) {
    const auto lines = SourceTokenLines("1.5e3");
    ASSERT_EQ(lines.size(), 1U);
    EXPECT_EQ(Texts(lines[0]), (std::vector<std::string>{"1", ".", "5e3"}));
}

TEST(GlslEsRulesTest, ANulByteIsAnErrorAtItsLineAndColumn) {
    const std::string text = std::string("void main() {\n  x;") + '\0' + "y;\n}\n";
    EXPECT_EQ(Formatted(CheckSourceText(text, "", "a.fsh")),
              "a.fsh:2:5: error: NUL byte in the shader source; GLSL ES source is text "
              "(GLSL ES §3.1) and glslang would stop reading here\n");
}

// Each macro doubles the one before, from M0's two tokens: M16 alone is 2^17 tokens, exactly
// the bound, and M17 twice that.
std::string Doubling(int levels) {
    std::string text = "#define M0 x x\n";
    for (int i = 1; i <= levels; ++i) {
        text += "#define M" + std::to_string(i) + " M" + std::to_string(i - 1) + " M" +
                std::to_string(i - 1) + "\n";
    }
    return text;
}

TEST(GlslEsRulesTest, AMacroExpandingBeyondTheBoundIsNamedWhereItIsUsed) {
    EXPECT_EQ(Formatted(CheckSourceText(Doubling(16) + "M16\n", "", "a.fsh")), "");
    EXPECT_EQ(Formatted(CheckSourceText(Doubling(17) + "float f =\n  M17;\n", "", "a.fsh")),
              "a.fsh:20:3: error: macro 'M17' expands to more than 131072 tokens (a macro "
              "bomb); tidepool refuses shaders that large: write repeated code as functions and "
              "loops rather than macros, or split the shader\n");
}

TEST(GlslEsRulesTest, ManyUsesOfAnAllowedMacroAddUpToTheBoundToo) {
    const std::string text = Doubling(16) + "M16 M16\n";
    EXPECT_EQ(Formatted(CheckSourceText(text, "", "a.fsh")),
              "a.fsh:18:5: error: the shader has more than 131072 tokens once its macros are "
              "expanded; tidepool refuses shaders that large: write repeated code as functions and "
              "loops rather than macros, or split the shader\n");
}

TEST(GlslEsRulesTest, MacrosOfThePreambleExpandLikeTheFilesOwn) {
    // Defined on the command line, used in the file: the use is in the file, so it has a place.
    EXPECT_EQ(Formatted(CheckSourceText("M17\n", Doubling(17), "a.fsh")),
              "a.fsh:1:1: error: macro 'M17' expands to more than 131072 tokens (a macro bomb); "
              "tidepool refuses shaders that large: write repeated code as functions and loops "
              "rather than macros, or split the shader\n");
    // #undef forgets a macro: the name is one token again.
    EXPECT_EQ(Formatted(CheckSourceText("#undef M17\nM17\n", Doubling(17), "a.fsh")), "");
}

TEST(GlslEsRulesTest, FirstMentionIsTheFirstWholeWordAndZeroWhenAbsent) {
    const std::string_view source = "uniform vec4 colours;\nvarying vec4 colour;\n";
    EXPECT_EQ(FirstMention(source, "colour"), std::make_pair(2, 14));
    EXPECT_EQ(FirstMention(source, "colours"), std::make_pair(1, 14));
    EXPECT_EQ(FirstMention(source, "vec4"), std::make_pair(1, 9));
    EXPECT_EQ(FirstMention(source, "col"), std::make_pair(0, 0));
    EXPECT_EQ(FirstMention("", "x"), std::make_pair(0, 0));
}

}  // namespace
}  // namespace tidepool
