// The one place that talks to glslang (compiler/src/GlslangSession.h): its info log turned into
// diagnostics, preprocessing, parsing and linking of small stages.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "GlslangSession.h"
#include "PipelineFixture.h"

namespace tidepool {
namespace {

using testing::Formatted;

const std::vector<std::string> kNoDefines;

GlslangStageInput Input(const std::string& file, const std::string& text, Stage stage,
                        const std::vector<std::string>& defines = kNoDefines) {
    return GlslangStageInput{file, text, stage, std::nullopt, defines, nullptr};
}

TEST(GlslangSessionTest, LogLinesBecomeDiagnosticsAtTheQuotedTokensColumn) {
    const std::string source = "void main() {\n  float x = yy;\n}\n";
    const std::string log =
            "ERROR: 0:2: 'yy' : undeclared identifier\n"
            "WARNING: 0:1: 'main' : something to note\n"
            "ERROR: 1 compilation errors.  No code generated.\n";
    EXPECT_EQ(Formatted(ParseGlslangLog(log, "a.fsh", source)),
              "a.fsh:2:13: error: 'yy' : undeclared identifier\n"
              "a.fsh:1:6: warning: 'main' : something to note\n");
}

// glslang reports any byte past ASCII in code as the token '\x80', which is on no line: the
// message had no column and wrote that byte, no UTF-8, out as the token.
TEST(GlslangSessionTest, ACharacterPastAsciiInCodeIsPlacedAndNamed) {
    const std::string source =
            "#version 300 es\nprecision mediump float;\n// caf\xC3\xA9 is fine here\n"
            "out vec4 c;\nvoid main() { /* \xC3\xA9 */ float caf\xC3\xA9 = 1.0; c = vec4(1.0); }"
            " // \xE2\x82\xAC\n";
    const StageParse parse = ParseStage(Input("a.frag", source, Stage::kFragment));
    EXPECT_FALSE(parse.ok);
    EXPECT_EQ(Formatted(parse.diagnostics),
              "a.frag:5:33: error: a character outside GLSL ES's character set (byte 0xC3, not "
              "ASCII): outside comments a shader may hold ASCII only (GLSL ES 1.00 and 3.00 "
              "section 3.1); remove it, or move it into a comment\n");
}

// It used to come out as "a.fsh: error: 0:-6: 'oops' ...", glslang's location as message text.
TEST(GlslangSessionTest, ALineWrappedNegativeByAHugeLineDirectiveIsSaidToBeUnknown) {
    const std::string source = "#version 100\n#line 4294967290\nvoid main() { oops; }\n";
    EXPECT_EQ(Formatted(ParseGlslangLog("ERROR: 0:-6: 'oops' : undeclared identifier\n", "a.fsh",
                                        source)),
              "a.fsh: error: at an unknown line (a '#line' directive set the count past "
              "2147483647 and glslang wrapped it to -6; use smaller line numbers): 'oops' : "
              "undeclared identifier\n");
}

// glslang's source string -1 is its preamble, where the defines are: it used to come out as
// "a.fsh: error: -1:1: '' : bad digit ...", blaming the file at a line it does not have.
TEST(GlslangSessionTest, AnErrorInADefinesValueIsSaidToBeThere) {
    EXPECT_EQ(Formatted(ParseGlslangLog("ERROR: -1:1: '' : bad digit in hexadecimal literal\n",
                                        "a.fsh", "#version 100\n")),
              "a.fsh: error: in a define's value (defines are given to glslang ahead of the file; "
              "check each -D NAME=VALUE): '' : bad digit in hexadecimal literal\n");
}

// A negative count a `#line` wrote itself was said to have wrapped past 2147483647.
TEST(GlslangSessionTest, ANegativeLineSetByALineDirectiveIsNotSaidToHaveWrapped) {
    const std::string source = "#version 100\n#line -5\nvoid main() { zz; }\n";
    EXPECT_EQ(Formatted(ParseGlslangLog("ERROR: 0:-5: 'zz' : undeclared identifier\n", "a.fsh",
                                        source)),
              "a.fsh: error: at an unknown line (a '#line' directive set the count to -5; use "
              "line numbers from 1 to 2147483647): 'zz' : undeclared identifier\n");
}

// `#line 2147483647` is a line number the user may write; a later line passes the limit.
TEST(GlslangSessionTest, ALineWrappedByLinesAfterAHighLineDirectiveIsSaidToBeUnknown) {
    const std::string source = "#version 100\n#line 2147483647\nvoid main() {}\noops;\n";
    const StageParse parse = ParseStage(Input("a.fsh", source, Stage::kFragment));
    EXPECT_FALSE(parse.ok);
    EXPECT_EQ(
            Formatted(parse.diagnostics)
                    .rfind("a.fsh: error: at an unknown line (a '#line' directive set the count so "
                           "near 2147483647 that a later line passed it, and glslang wrapped it to "
                           "-2147483648; use smaller line numbers): ",
                           0),
            0U)
            << Formatted(parse.diagnostics);
}

// glslang added "extra tokens" after each of these, on lines that have none, and put the bare
// directive's message on the line after it.
TEST(GlslangSessionTest, AnExtensionDirectiveErrorIsOneMessageOnItsOwnLine) {
    struct Case {
        const char* directive;
        const char* expected;
    };
    for (const Case& c :
         {Case{"#extension GL_FOO_bar : require",
               "a.fsh:2:1: error: '#extension' : extension not supported: GL_FOO_bar\n"},
          Case{"#extension GL_OES_standard_derivatives : bogus",
               "a.fsh:2:1: error: '#extension' : behavior not supported: bogus\n"},
          Case{"#extension", "a.fsh:2:1: error: '#extension' : extension name not specified\n"},
          // Tokens that are there are still reported.
          Case{"#extension GL_OES_standard_derivatives : enable foo",
               "a.fsh:2:1: error: '#extension' : extra tokens -- expected newline\n"}}) {
        const std::string source = std::string("#version 100\n") + c.directive +
                                   "\nprecision mediump float;\n"
                                   "void main() { gl_FragColor = vec4(1.0); }\n";
        const StageParse parse = ParseStage(Input("a.fsh", source, Stage::kFragment));
        EXPECT_FALSE(parse.ok) << c.directive;
        EXPECT_EQ(Formatted(parse.diagnostics), c.expected) << c.directive;
    }
}

TEST(GlslangSessionTest, ContinuationLinesJoinTheirMessageAndUnplacedMessagesKeepLineZero) {
    const std::string log =
            "ERROR: Linking fragment stage: Types must match:\n"
            "    colour: \"smooth in highp 4-component vector of float\" versus "
            "\"smooth out highp 3-component vector of float\"\n"
            "ERROR: 0:3: '' : compilation terminated\n";
    const std::vector<Diagnostic> diagnostics = ParseGlslangLog(log, "a.fsh", "");
    ASSERT_EQ(diagnostics.size(), 1U) << Formatted(diagnostics);
    EXPECT_EQ(diagnostics[0].line, 0);
    EXPECT_EQ(diagnostics[0].message,
              "Linking fragment stage: Types must match:; colour: \"smooth in highp 4-component "
              "vector of float\" versus \"smooth out highp 3-component vector of float\"");
    EXPECT_TRUE(ParseGlslangLog("\n  \n", "a.fsh", "").empty());
}

TEST(GlslangSessionTest, PreprocessingAppliesTheDefinesAndDropsInactiveBlocks) {
    const std::string text =
            "#version 100\n#ifdef ENABLE_FOG\nfloat fog;\n#else\nfloat clear;\n#endif\n"
            "// a comment\n";
    const std::vector<std::string> defines = {"ENABLE_FOG"};
    const PreprocessResult with = PreprocessStage(Input("a.fsh", text, Stage::kFragment, defines));
    ASSERT_TRUE(with.ok);
    EXPECT_NE(with.text.find("float fog;"), std::string::npos) << with.text;
    EXPECT_EQ(with.text.find("clear"), std::string::npos) << with.text;
    EXPECT_EQ(with.text.find("comment"), std::string::npos) << with.text;
    const PreprocessResult without = PreprocessStage(Input("a.fsh", text, Stage::kFragment));
    ASSERT_TRUE(without.ok);
    EXPECT_NE(without.text.find("float clear;"), std::string::npos) << without.text;
    EXPECT_FALSE(
            PreprocessStage(Input("a.fsh", "#version 100\n#error stop\n", Stage::kFragment)).ok);
}

TEST(GlslangSessionTest, ParseKeepsTheTreeOfAValidStageAndPlacesAnError) {
    const std::string good =
            "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); }\n";
    const StageParse parsed = ParseStage(Input("a.fsh", good, Stage::kFragment));
    EXPECT_TRUE(parsed.ok) << Formatted(parsed.diagnostics);
    EXPECT_NE(parsed.intermediate, nullptr);
    const std::string bad =
            "#version 100\nprecision mediump float;\nvoid main() {\n  gl_FragColor = yy;\n}\n";
    const StageParse failed = ParseStage(Input("b.fsh", bad, Stage::kFragment));
    EXPECT_FALSE(failed.ok);
    ASSERT_TRUE(HasErrors(failed.diagnostics));
    EXPECT_EQ(failed.diagnostics[0].file, "b.fsh");
    EXPECT_EQ(failed.diagnostics[0].line, 4);
    EXPECT_EQ(failed.diagnostics[0].column, 18);
}

TEST(GlslangSessionTest, DesktopGlslIsAnError) {
    const std::string desktop = "#version 330\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    const StageParse parsed = ParseStage(Input("a.fsh", desktop, Stage::kFragment));
    EXPECT_FALSE(parsed.ok);
    EXPECT_TRUE(HasErrors(parsed.diagnostics));
}

// A vertex stage writing `colour`, a fragment stage reading it as declared, and one reading it
// with another type.
constexpr const char* kColourVertex =
        "#version 100\nattribute vec4 p;\nvarying vec4 colour;\n"
        "void main() { colour = p; gl_Position = p; }\n";
constexpr const char* kMatchingFragment =
        "#version 100\nprecision mediump float;\nvarying vec4 colour;\n"
        "void main() { gl_FragColor = colour; }\n";
constexpr const char* kMismatchedFragment =
        "#version 100\nprecision mediump float;\nvarying vec3 colour;\n"
        "void main() { gl_FragColor = vec4(colour, 1.0); }\n";

TEST(GlslangSessionTest, LinkingChecksTheVaryingsBetweenTheStages) {
    const LinkResult good = LinkStages(Input("a.vsh", kColourVertex, Stage::kVertex),
                                       Input("a.fsh", kMatchingFragment, Stage::kFragment));
    EXPECT_TRUE(good.ok) << Formatted(good.diagnostics);
    const LinkResult bad = LinkStages(Input("a.vsh", kColourVertex, Stage::kVertex),
                                      Input("b.fsh", kMismatchedFragment, Stage::kFragment));
    EXPECT_FALSE(bad.ok);
    EXPECT_TRUE(HasErrors(bad.diagnostics));
}

TEST(GlslangSessionTest, AParseServesEveryLinkItIsGiven) {
    // (An input refers to its text, which must outlive it.)
    const std::string vertex = kColourVertex;
    const std::string matching = kMatchingFragment;
    const std::string mismatched = kMismatchedFragment;
    const GlslangStageInput vertex_input = Input("a.vsh", vertex, Stage::kVertex);
    const GlslangStageInput matching_input = Input("a.fsh", matching, Stage::kFragment);
    const GlslangStageInput mismatched_input = Input("b.fsh", mismatched, Stage::kFragment);
    StageParse vertex_parse = ParseStage(vertex_input);
    StageParse first = ParseStage(matching_input);
    EXPECT_TRUE(LinkParsed({&vertex_input, &matching_input}, {&vertex_parse, &first}).ok);
    ASSERT_TRUE(ReusableForLink(vertex_parse));
    ASSERT_TRUE(ReusableForLink(first));

    // The same vertex parse, twice more: the link's verdict and messages are a new parse's.
    StageParse second = ParseStage(matching_input);
    EXPECT_TRUE(LinkParsed({&vertex_input, &matching_input}, {&vertex_parse, &second}).ok);
    ASSERT_TRUE(ReusableForLink(vertex_parse));
    StageParse third = ParseStage(mismatched_input);
    const LinkResult bad = LinkParsed({&vertex_input, &mismatched_input}, {&vertex_parse, &third});
    const LinkResult fresh = LinkStages(vertex_input, mismatched_input);
    EXPECT_FALSE(bad.ok);
    EXPECT_EQ(Formatted(bad.diagnostics), Formatted(fresh.diagnostics));
    EXPECT_TRUE(HasErrors(bad.diagnostics));
    // tidepool's rules found the mismatch before glslang's link, which would have counted it in
    // the vertex tree and failed every later link of it: the parse still serves a good link.
    ASSERT_TRUE(ReusableForLink(vertex_parse));
    StageParse fourth = ParseStage(matching_input);
    EXPECT_TRUE(LinkParsed({&vertex_input, &matching_input}, {&vertex_parse, &fourth}).ok);
    // A tree glslang counted an error in serves no link.
    EXPECT_FALSE(ReusableForLink(ParseStage(Input("c.fsh", "void main() {", Stage::kFragment))));
}

TEST(GlslangSessionTest, ALinkKeepsUncalledFunctionsForTheNextLinkOfTheSameParse) {
    // The fragment stage reads `tint` only in a function nothing calls: still a static use, so it
    // links with a vertex stage that writes `tint` and not with one that lacks it, in this order
    // too (glslang's link would otherwise drop the function from the tree it links).
    const std::string with_tint =
            "#version 100\nattribute vec4 p;\nvarying vec3 tint;\n"
            "void main() { tint = p.xyz; gl_Position = p; }\n";
    const std::string without_tint =
            "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n";
    const std::string fragment =
            "#version 100\nprecision mediump float;\nvarying vec3 tint;\n"
            "vec3 Tinted() { return tint; }\n"
            "void main() { gl_FragColor = vec4(1.0); }\n";
    const GlslangStageInput tinted = Input("t.vsh", with_tint, Stage::kVertex);
    const GlslangStageInput plain = Input("p.vsh", without_tint, Stage::kVertex);
    const GlslangStageInput fragment_input = Input("a.fsh", fragment, Stage::kFragment);
    StageParse fragment_parse = ParseStage(fragment_input);
    StageParse tinted_parse = ParseStage(tinted);
    const LinkResult first =
            LinkParsed({&tinted, &fragment_input}, {&tinted_parse, &fragment_parse});
    EXPECT_TRUE(first.ok) << Formatted(first.diagnostics);
    ASSERT_TRUE(ReusableForLink(fragment_parse));
    StageParse plain_parse = ParseStage(plain);
    const LinkResult second =
            LinkParsed({&plain, &fragment_input}, {&plain_parse, &fragment_parse});
    EXPECT_FALSE(second.ok);
    EXPECT_EQ(Formatted(second.diagnostics),
              Formatted(LinkStages(plain, fragment_input).diagnostics));
    EXPECT_NE(Formatted(second.diagnostics).find("a.fsh:4:"), std::string::npos)
            << Formatted(second.diagnostics);
}

TEST(GlslangSessionTest, LineCommentsAreTakenOutWithoutMovingAnyCode) {
    // Code keeps its line and column; what follows `//` goes, up to the line's own ending.
    EXPECT_EQ(WithoutLineComments("float a; // note\r\nfloat b;//x\n// whole line\nc"),
              "float a; \r\nfloat b;\n\nc");
    EXPECT_EQ(WithoutLineComments("#define K 2 // two\n#if K == 2\n"),
              "#define K 2 \n#if K == 2\n");
    // Block comments stay as written, and a `//` inside one is not a line comment; a `/*` inside
    // a line comment starts nothing.
    EXPECT_EQ(WithoutLineComments("a /* x // y\n z */ b // c /* d\ne */"),
              "a /* x // y\n z */ b \ne */");
    EXPECT_EQ(WithoutLineComments("#define F(x) (x /* half\n */ * 0.5)\n"),
              "#define F(x) (x /* half\n */ * 0.5)\n");
    // A `//` after a `"` on its line may be inside a string; a division is no comment.
    EXPECT_EQ(WithoutLineComments("#line 3 \"a//b\" // c\nx = y / z; // d\n"),
              "#line 3 \"a//b\" // c\nx = y / z; \n");
    // A line continuation may carry a comment on to the next line: nothing is taken out.
    const std::string continued = "// a \\\nfloat hidden;\nfloat b; // c\n";
    EXPECT_EQ(WithoutLineComments(continued), continued);
    EXPECT_EQ(WithoutLineComments("x /"), "x /");
    EXPECT_EQ(WithoutLineComments(""), "");
}

TEST(GlslangSessionTest, DiagnosticsAfterLineCommentsKeepTheUsersLineAndColumn) {
    const std::string text =
            "#version 100 // the version\n"
            "precision mediump float; // default precision\n"
            "#define SCALE 2.0 // a macro with a comment\n"
            "// a whole line\n"
            "void main() {\n"
            "  gl_FragColor = vec4(SCALE) * yy; // undeclared\n"
            "}\n";
    const StageParse parsed = ParseStage(Input("a.fsh", text, Stage::kFragment));
    EXPECT_FALSE(parsed.ok);
    EXPECT_EQ(Formatted(parsed.diagnostics), "a.fsh:6:32: error: 'yy' : undeclared identifier\n");
}

TEST(GlslangSessionTest, OnlyLinesGlslangSkipsWithoutAMessageAreQuiet) {
    for (const std::string& line :
         std::vector<std::string>{"", "  \t", "float v = a.b * (c + 1.0) / 2.5e-3;",
                                  "x <<= 3; y ^^ z ? q : r;", "int n = 999999999;", ".5e+12", "0",
                                  "0.0", "a[1] = {}; !~%|&", "line end\r", std::string(255, 'n')}) {
        EXPECT_TRUE(IsQuietWhenSkipped(line)) << line;
    }
    // Each of these is either refused by glslang's scanner in skipped text (a hexadecimal `x`
    // without digits, an exponent without digits, a literal past 32 bits) or near enough to
    // something that is to be left to it.
    for (const std::string& line : std::vector<std::string>{"#ifdef A",
                                                            "int h = 0x1F;",
                                                            "int h = 0x;",
                                                            "int o = 09;",
                                                            "int big = 4294967296;",
                                                            "int nine = 1234567890;",
                                                            "float e = 1e;",
                                                            "float s = 1.0f;",
                                                            "uint u = 1u;",
                                                            "float d = 1e100;",
                                                            "x = 1.5.3;",
                                                            "s = \"text\";",
                                                            "c = 'a';",
                                                            "a \\",
                                                            "b /* c",
                                                            "c */ d",
                                                            "e // f",
                                                            "g @ h",
                                                            "i $ j",
                                                            "k\rl",
                                                            "\x80",
                                                            std::string(256, 'n')}) {
        EXPECT_FALSE(IsQuietWhenSkipped(line)) << line;
    }
}

TEST(GlslangSessionTest, BlankingEmptiesOnlyQuietSkippedLinesAndKeepsEveryLineBreak) {
    const std::string text = "a\nb 0x1\nc\nd\ne";
    const std::vector<bool> quiet = QuietWhenSkippedLines(text);
    EXPECT_EQ(quiet, (std::vector<bool>{true, false, true, true, true}));
    EXPECT_EQ(WithSkippedLinesBlanked(text, {{2, 3}, {5, 5}}, quiet), "a\nb 0x1\n\nd\n");
    EXPECT_EQ(WithSkippedLinesBlanked(text, {{1, 5}}, quiet), "\nb 0x1\n\n\n");
    EXPECT_EQ(WithSkippedLinesBlanked(text, {}, quiet), text);
    EXPECT_EQ(WithSkippedLinesBlanked(text + "\n", {{5, 6}}, QuietWhenSkippedLines(text + "\n")),
              "a\nb 0x1\nc\nd\n\n");
}

TEST(GlslangSessionTest, IdentityIsStableAndNamesTheLimits) {
    const std::string identity = GlslangIdentity();
    EXPECT_EQ(identity, GlslangIdentity());
    EXPECT_NE(identity.find("MaxDrawBuffers"), std::string::npos);
}

}  // namespace
}  // namespace tidepool
