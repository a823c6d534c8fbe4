// The WebGL rules (compiler/src/WebGlRules.h and the WebGL targets of GlslangSession), each shown
// from both sides: a shader written for the rule that breaks it, with the exact first error, and
// one that keeps it. Run through ValidateShaderFiles with a target, as
// `tidepool validate --target webgl1|webgl2 VERT FRAG` does.
#include "tidepool/GlslValidator.h"

#include <gtest/gtest.h>

#include <string>

#include "NestedStructs.h"
#include "ShaderPairValidation.h"
#include "WebGlRules.h"

namespace tidepool {
namespace {

using testing::PairVerdict;
using testing::ValidatePair;

struct WebGlCase {
    const char* why;
    GlslTarget target;
    std::string vertex;    // "": no vertex file
    std::string fragment;  // "": no fragment file
    const char* expected;  // the first error, folder left out; "" when the pair is valid
};

void PrintTo(const WebGlCase& c, std::ostream* out) {
    *out << c.why;
}

class WebGlRulesTest : public ::testing::TestWithParam<WebGlCase> {};

TEST_P(WebGlRulesTest, GivesTheExpectedVerdictAndFirstError) {
    const WebGlCase& c = GetParam();
    auto text = [](const std::string& t) {
        return t.empty() ? std::nullopt : std::optional<std::string>(t);
    };
    ShaderFileOptions options;
    options.target = c.target;
    const PairVerdict verdict = ValidatePair(text(c.vertex), text(c.fragment), options);
    ASSERT_EQ(verdict.verdicts, 1U) << c.why;
    EXPECT_EQ(verdict.valid, std::string(c.expected).empty()) << c.why;
    EXPECT_EQ(verdict.first_error, c.expected) << c.why;
}

const std::string kVertex100 =
        "#version 100\n"
        "attribute vec4 position;\n"
        "varying vec2 uv;\n"
        "void main() { uv = position.xy; gl_Position = position; }\n";

// A 1.00 fragment shader with `body` as the body of main, after `globals`.
std::string Fragment100(const std::string& globals, const std::string& body) {
    return "#version 100\n"
           "precision mediump float;\n"
           "varying vec2 uv;\n" +
           globals + "void main() {\n" + body + "}\n";
}

const std::string kVertex300 =
        "#version 300 es\n"
        "in vec4 position;\n"
        "out vec2 uv;\n"
        "void main() { uv = position.xy; gl_Position = position; }\n";

std::string Fragment300(const std::string& globals, const std::string& body) {
    return "#version 300 es\n"
           "precision mediump float;\n"
           "in vec2 uv;\n"
           "out vec4 colour;\n" +
           globals + "void main() {\n" + body + "}\n";
}

// WebGL 1.0 §6.20 and WebGL 2.0 (GLSL ES 3.00 §3.8): the longest token.
INSTANTIATE_TEST_SUITE_P(
        TokenLength, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"an identifier of 256 characters in WebGL 1", GlslTarget::kWebGl1,
                          kVertex100,
                          Fragment100("float " + std::string(256, 'w') + " = 1.0;\n",
                                      "    gl_FragColor = vec4(" + std::string(256, 'w') + ");\n"),
                          ""},
                WebGlCase{"an identifier of 257 characters in WebGL 1", GlslTarget::kWebGl1,
                          kVertex100,
                          Fragment100("float " + std::string(257, 'w') + " = 1.0;\n",
                                      "    gl_FragColor = vec4(1.0);\n"),
                          "a.fsh:4:7: error: a token of 257 characters ('wwwwwwwwwwwwwwww...'); "
                          "webgl1 accepts at most 256 (WebGL 1.0 §6.20 \"Maximum GLSL Token "
                          "Size\")"},
                WebGlCase{"an identifier of 1024 characters in WebGL 2", GlslTarget::kWebGl2,
                          kVertex300,
                          Fragment300("float " + std::string(1024, 'w') + " = 1.0;\n",
                                      "    colour = vec4(" + std::string(1024, 'w') + ");\n"),
                          ""},
                WebGlCase{"an identifier of 1024 characters in a 1.00 shader for WebGL 2",
                          GlslTarget::kWebGl2, kVertex100,
                          Fragment100("float " + std::string(1024, 'w') + " = 1.0;\n",
                                      "    gl_FragColor = vec4(" + std::string(1024, 'w') + ");\n"),
                          ""},
                WebGlCase{"an identifier of 1025 characters in WebGL 2", GlslTarget::kWebGl2,
                          kVertex300,
                          Fragment300("float " + std::string(1025, 'w') + " = 1.0;\n",
                                      "    colour = vec4(1.0);\n"),
                          "a.fsh:5:7: error: a token of 1025 characters ('wwwwwwwwwwwwwwww...'); "
                          "webgl2 accepts at most 1024 (WebGL 1.0 §6.20 \"Maximum GLSL Token "
                          "Size\"; GLSL ES 3.00 §3.8)"}));

// WebGL 1.0 §6.17: `webgl_` and `_webgl_` names are WebGL's.
INSTANTIATE_TEST_SUITE_P(
        ReservedPrefixes, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"webgl inside a name is fine", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("float my_webgl_tint = 0.5;\n",
                                      "    gl_FragColor = vec4(my_webgl_tint);\n"),
                          ""},
                WebGlCase{"a uniform named webgl_...", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform float webgl_tint;\n",
                                      "    gl_FragColor = vec4(webgl_tint);\n"),
                          "a.fsh:4:15: error: 'webgl_tint': identifiers starting with 'webgl_' "
                          "or '_webgl_' are reserved for use by WebGL (WebGL 1.0 §6.17 \"GLSL "
                          "Constructs\"); rename it"},
                WebGlCase{"a function named _webgl_... in WebGL 2", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("float _webgl_half(float x) { return x * 0.5; }\n",
                                      "    colour = vec4(_webgl_half(uv.x));\n"),
                          "a.fsh:5:7: error: '_webgl_half': identifiers starting with 'webgl_' "
                          "or '_webgl_' are reserved for use by WebGL (WebGL 1.0 §6.17 \"GLSL "
                          "Constructs\"); rename it"}));

// WebGL 1.0 §6.21: outside comments and inactive blocks, only the GLSL ES character set.
INSTANTIATE_TEST_SUITE_P(
        CharacterSet, WebGlRulesTest,
        ::testing::Values(WebGlCase{"non-ASCII text in comments and a quote in an inactive block",
                                    GlslTarget::kWebGl1, kVertex100,
                                    Fragment100("// Wasserfarbe, “gemischt” — ok\n"
                                                "#ifdef __cplusplus\n"
                                                "#line 42 \"water.glsl\"\n"
                                                "#endif\n",
                                                "    gl_FragColor = vec4(uv, 0.0, 1.0); /* ü */\n"),
                                    ""},
                          WebGlCase{"a dollar sign in code", GlslTarget::kWebGl1, kVertex100,
                                    Fragment100("float $tint = 0.5;\n",
                                                "    gl_FragColor = vec4(uv, 0.0, 1.0);\n"),
                                    // glslang's preprocessor refuses it first and drops it from its
                                    // output; the verdict is the same.
                                    "a.fsh:4:7: error: '$' : unexpected token"}));

// GLSL ES 1.00 Appendix A §4 and §5, which WebGL requires of 1.00 shaders (WebGL 1.0 and 2.0
// §4.3); plain GLSL ES and WebGL 2's 3.00 shaders accept these loops.
INSTANTIATE_TEST_SUITE_P(
        AppendixA, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"a for loop with a constant bound, indexing by its index",
                          GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform vec4 taps[4];\n",
                                      "    vec4 sum = vec4(0.0);\n"
                                      "    for (int i = 0; i < 4; i++) { sum += taps[i]; }\n"
                                      "    gl_FragColor = sum;\n"),
                          ""},
                WebGlCase{"a while loop", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("",
                                      "    float depth = uv.x;\n"
                                      "    while (depth > 1.0) { depth *= 0.5; }\n"
                                      "    gl_FragColor = vec4(depth);\n"),
                          "a.fsh:6: error: 'limitation' : while loops not available"},
                WebGlCase{"a loop bound by a uniform", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform int count;\n",
                                      "    float sum = 0.0;\n"
                                      "    for (int i = 0; i < count; i++) { sum += 0.1; }\n"
                                      "    gl_FragColor = vec4(sum);\n"),
                          "a.fsh:7: error: 'limitations' : inductive-loop condition requires "
                          "the form \"loop-index <comparison-op> constant-expression\""},
                WebGlCase{"a fragment uniform array indexed by a uniform", GlslTarget::kWebGl1,
                          kVertex100,
                          Fragment100("uniform vec4 taps[4];\nuniform int pick;\n",
                                      "    gl_FragColor = taps[pick];\n"),
                          "a.fsh:7: error: 'limitations' : Non-constant-index-expression"},
                WebGlCase{"a vertex uniform array indexed by an attribute is allowed",
                          GlslTarget::kWebGl1,
                          "#version 100\n"
                          "attribute vec4 position;\n"
                          "attribute float bone;\n"
                          "uniform vec4 offsets[8];\n"
                          "void main() { gl_Position = position + offsets[int(bone)]; }\n",
                          Fragment100("", "    gl_FragColor = vec4(1.0);\n"), ""},
                WebGlCase{"the same while loop in WebGL 2", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("",
                                      "    float depth = uv.x;\n"
                                      "    while (depth > 1.0) { depth *= 0.5; }\n"
                                      "    colour = vec4(depth);\n"),
                          ""},
                WebGlCase{"the while loop in a 1.00 shader for WebGL 2", GlslTarget::kWebGl2,
                          kVertex100,
                          Fragment100("",
                                      "    float depth = uv.x;\n"
                                      "    while (depth > 1.0) { depth *= 0.5; }\n"
                                      "    gl_FragColor = vec4(depth);\n"),
                          "a.fsh:6: error: 'limitation' : while loops not available"}));

TEST(JoinContinuedLinesTest, JoinsEachContinuedLineAndKeepsTheLineCount) {
    EXPECT_EQ(JoinContinuedLines("a \\\nb\nc\n"), "a b\n\nc\n");
    EXPECT_EQ(JoinContinuedLines("a\\\r\nb\\\nc\nd"), "abc\n\n\nd");
    EXPECT_EQ(JoinContinuedLines("a\\\n"), "a\n");  // a continuation on the last line
}

TEST(JoinContinuedLinesTest, LeavesOtherBackslashesAlone) {
    EXPECT_EQ(JoinContinuedLines("a \\ b\nc\\ \n"), "a \\ b\nc\\ \n");
    EXPECT_EQ(JoinContinuedLines(""), "");
}

// WebGL supports the line continuation character in 1.00 shaders too (KhronosGroup/WebGL#3212);
// GLSL ES 1.00 has none, so without a WebGL target the next line is code.
INSTANTIATE_TEST_SUITE_P(
        LineContinuation, WebGlRulesTest,
        ::testing::Values(WebGlCase{"a line comment continued onto the next line in WebGL 1",
                                    GlslTarget::kWebGl1, kVertex100,
                                    Fragment100("// the sea \\\nfoam and spray\n",
                                                "    gl_FragColor = vec4(1.0);\n"),
                                    ""},
                          WebGlCase{"an expression continued in a 1.00 shader for WebGL 2",
                                    GlslTarget::kWebGl2, kVertex100,
                                    Fragment100("", "    gl_FragColor = \\\n        vec4(1.0);\n"),
                                    ""},
                          WebGlCase{"the continued comment without a WebGL target",
                                    GlslTarget::kEs100, kVertex100,
                                    Fragment100("// the sea \\\nfoam and spray\n",
                                                "    gl_FragColor = vec4(1.0);\n"),
                                    "a.fsh:5: error: '' :  syntax error, unexpected IDENTIFIER"}));

// The version each WebGL runs, and the preprocessor rules WebGL settles (§6.34, §6.35).
INSTANTIATE_TEST_SUITE_P(
        VersionsAndDirectives, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"a 3.00 shader for WebGL 1", GlslTarget::kWebGl1, kVertex300,
                          Fragment300("", "    colour = vec4(1.0);\n"),
                          "a.vsh:1:1: error: '#version 300 es': WebGL 1 runs GLSL ES 1.00 "
                          "shaders only (WebGL 1.0 §4.3 \"Supported GLSL Constructs\"); use "
                          "'#version 100', or the webgl2 target for a GLSL ES 3.00 shader"},
                WebGlCase{"a 1.00 shader for WebGL 2", GlslTarget::kWebGl2, kVertex100,
                          Fragment100("", "    gl_FragColor = vec4(1.0);\n"), ""},
                WebGlCase{"#extension after a declaration is allowed in WebGL 1",
                          GlslTarget::kWebGl1, kVertex100,
                          Fragment100("#extension GL_OES_standard_derivatives : enable\n",
                                      "    gl_FragColor = vec4(dFdx(uv.x));\n"),
                          ""},
                WebGlCase{"#extension after a declaration of a 1.00 shader in WebGL 2",
                          GlslTarget::kWebGl2, kVertex100,
                          Fragment100("#extension GL_OES_standard_derivatives : enable\n",
                                      "    gl_FragColor = vec4(dFdx(uv.x));\n"),
                          ""},
                WebGlCase{"#extension after a declaration without a WebGL target",
                          GlslTarget::kEs100, kVertex100,
                          Fragment100("#extension GL_OES_standard_derivatives : enable\n",
                                      "    gl_FragColor = vec4(dFdx(uv.x));\n"),
                          "a.fsh:4:1: error: '#extension' after the first non-preprocessor token "
                          "(line 2); extension directives must come before any of them (GLSL ES "
                          "1.00 §3.4, GLSL ES 3.00 §3.4)"},
                WebGlCase{"defined produced by a macro in #if", GlslTarget::kWebGl1, kVertex100,
                          "#version 100\n"
                          "precision mediump float;\n"
                          "#define HAS(x) defined(x)\n"
                          "#if HAS(GL_ES)\n"
                          "#endif\n"
                          "void main() { gl_FragColor = vec4(1.0); }\n",
                          "a.fsh:4: error: 'defined' : cannot use in preprocessor expression "
                          "when expanded from macros"}));

// WebGL 1.0 §6.22: structures nest at most 4 levels deep; plain GLSL ES sets no such limit.
const std::string kNestedStructs =
        "struct Foam { float density; };\n"
        "struct Crest { Foam foam; };\n"
        "struct Wave { Crest crests[2]; };\n"
        "struct Swell { Wave wave; };\n";

INSTANTIATE_TEST_SUITE_P(
        StructNesting, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"structures nested 4 levels deep", GlslTarget::kWebGl1, kVertex100,
                          Fragment100(kNestedStructs + "uniform Swell swell;\n",
                                      "    gl_FragColor = "
                                      "vec4(swell.wave.crests[1].foam.density);\n"),
                          ""},
                WebGlCase{"structures nested 5 levels deep", GlslTarget::kWebGl1, kVertex100,
                          Fragment100(kNestedStructs + "struct Sea { Swell swell; };\n"
                                                       "uniform Sea sea;\n",
                                      "    gl_FragColor = "
                                      "vec4(sea.swell.wave.crests[1].foam.density);\n"),
                          "a.fsh:8:8: error: struct 'Sea' nests structures 5 levels deep; WebGL "
                          "allows at most "
                          "4 (WebGL 1.0 §6.22 \"Maximum Nesting of Structures\")"},
                WebGlCase{
                        "5 levels in a local variable in WebGL 2", GlslTarget::kWebGl2, kVertex300,
                        Fragment300(kNestedStructs + "struct Sea { Swell swell; };\n",
                                    "    Sea sea;\n"
                                    "    sea.swell.wave.crests[0].foam.density = uv.x;\n"
                                    "    colour = vec4(sea.swell.wave.crests[0].foam.density);\n"),
                        "a.fsh:9:8: error: struct 'Sea' nests structures 5 levels deep; WebGL "
                        "allows at most "
                        "4 (WebGL 1.0 §6.22 \"Maximum Nesting of Structures\")"}));

// A uniform of 40 structures, each holding the one before twice: 2^40 floats. Its uniform
// vectors, its nesting and its packing are each worked out once per structure; before, each
// walk went over every member anew and the stage ran past the 20 s limit. (Declared through a
// macro, out of the source guard's sight; unused, since glslang's own walks of a member access
// are as slow.)
INSTANTIATE_TEST_SUITE_P(StructNestingAtScale, WebGlRulesTest,
                         ::testing::Values(WebGlCase{
                                 "40 levels, each structure holding the one before twice",
                                 GlslTarget::kWebGl1, kVertex100,
                                 Fragment100(tidepool::testing::DoublingStructsByMacro(40) +
                                                     "uniform S40 deep;\n",
                                             "    gl_FragColor = vec4(uv, 0.0, 1.0);\n"),
                                 "a.fsh:45:13: error: uniform 'deep' needs over "
                                 "1099511627775 uniform vectors, more than the 16 a fragment "
                                 "shader has (gl_MaxFragmentUniformVectors; GLSL ES 1.00 "
                                 "Appendix A §7, GLSL ES 3.00 §4.3.5)"}));

// WebGL 1.0 §6.33: a WebGL 1 global initializer may use uniforms and non-const globals, not
// varyings, built-in variables, texture lookups or assignments; plain GLSL ES 1.00 wants constants.
INSTANTIATE_TEST_SUITE_P(
        GlobalInitializers, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"uniforms, globals and built-in functions", GlslTarget::kWebGl1,
                          kVertex100,
                          Fragment100("uniform float level;\n"
                                      "float height = level * 2.0;\n"
                                      "float crest = height + sin(level), trough = -height;\n",
                                      "    gl_FragColor = vec4(crest, trough, uv);\n"),
                          ""},
                WebGlCase{"the same without a WebGL target", GlslTarget::kEs100, kVertex100,
                          Fragment100("uniform float level;\n"
                                      "float height = level * 2.0;\n",
                                      "    gl_FragColor = vec4(height);\n"),
                          "a.fsh:5: error: 'non-constant global initializer (needs "
                          "GL_EXT_shader_non_constant_global_initializers)' : not supported for "
                          "this version or the enabled extensions"},
                WebGlCase{"a varying", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform float level;\n"
                                      "float height = level + uv.x;\n",
                                      "    gl_FragColor = vec4(height);\n"),
                          "a.fsh:5:24: error: the initializer of the global variable 'height' "
                          "uses the varying 'uv'; WebGL 1 allows only constant expressions, "
                          "uniforms and other global variables there (WebGL 1.0 §6.33 \"GLSL ES "
                          "Global Variable Initialization\")"},
                WebGlCase{"a texture lookup", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform sampler2D foam;\n"
                                      "float height = texture2D(foam, uv).r;\n",
                                      "    gl_FragColor = vec4(height);\n"),
                          "a.fsh:5:34: error: the initializer of the global variable 'height' "
                          "uses a texture lookup; WebGL 1 allows only constant expressions, "
                          "uniforms and other global variables there (WebGL 1.0 §6.33 \"GLSL ES "
                          "Global Variable Initialization\")"},
                WebGlCase{"an increment", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("float height = 1.0;\n"
                                      "float crest = height++;\n",
                                      "    gl_FragColor = vec4(crest);\n"),
                          "a.fsh:5:21: error: the initializer of the global variable 'crest' "
                          "uses an increment or decrement; WebGL 1 allows only constant "
                          "expressions, uniforms and other global variables there (WebGL 1.0 "
                          "§6.33 \"GLSL ES Global Variable Initialization\")"},
                WebGlCase{"gl_FragCoord", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("float depth = gl_FragCoord.z;\n",
                                      "    gl_FragColor = vec4(depth);\n"),
                          "a.fsh:4:15: error: the initializer of the global variable 'depth' "
                          "uses the built-in variable 'gl_FragCoord'; WebGL 1 allows only "
                          "constant expressions, uniforms and other global variables there "
                          "(WebGL 1.0 §6.33 \"GLSL ES Global Variable Initialization\")"}));

// WebGL 1.0 §6.26: uniforms and varyings must pack by GLSL ES 1.00 Appendix A §7 into the limits
// (ES 2.0's minimums here: 16 fragment uniform vectors, 8 varying vectors).
const std::string kManyVaryingsVertex =
        "#version 100\n"
        "attribute vec4 position;\n"
        "varying vec3 normals[4];\n"
        "varying vec3 tangents[4];\n"
        "varying vec3 view;\n"
        "varying float fades[8];\n"
        "void main() {\n"
        "    for (int i = 0; i < 4; i++) { normals[i] = position.xyz; tangents[i] = position.xyz; "
        "}\n"
        "    for (int i = 0; i < 8; i++) { fades[i] = position.w; }\n"
        "    view = position.xyz;\n"
        "    gl_Position = position;\n"
        "}\n";

// A ninth vec3 varying beside 4 + 4: one row more than gl_MaxVaryingVectors, 8 in ES 2.0.
const std::string kNineVaryingRowsFragment =
        "#version 100\n"
        "precision mediump float;\n"
        "varying vec3 normals[4];\n"
        "varying vec3 tangents[4];\n"
        "varying vec3 view;\n"
        "void main() { gl_FragColor = vec4(normals[3] + tangents[3] + view, 1.0); }\n";
const char* const kNineVaryingRowsError =
        "a.fsh:5:14: error: the varyings the fragment shader reads do not fit in 8 vectors "
        "(gl_MaxVaryingVectors): 'view' finds no room by the packing of GLSL ES 1.00 Appendix A "
        "§7, which WebGL requires (WebGL 1.0 §6.26 \"Packing Restrictions for Uniforms and "
        "Varyings\")";

INSTANTIATE_TEST_SUITE_P(
        Packing, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"16 vec3 and 16 floats fill 16 rows", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform vec3 normals[16];\n"
                                      "uniform float heights[16];\n",
                                      "    gl_FragColor = vec4(normals[15], heights[15]);\n"),
                          ""},
                WebGlCase{"a vec2 finds no room beside 16 vec3", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform vec3 normals[16];\n"
                                      "uniform vec2 offset;\n",
                                      "    gl_FragColor = vec4(normals[15], 0.0) + "
                                      "offset.xyxy;\n"),
                          "a.fsh:5:14: error: the uniforms of the fragment shader do not fit in "
                          "16 vectors (gl_MaxFragmentUniformVectors): 'offset' finds no room by "
                          "the packing of GLSL ES 1.00 Appendix A §7, which WebGL requires "
                          "(WebGL 1.0 §6.26 \"Packing Restrictions for Uniforms and Varyings\")"},
                WebGlCase{"vec2s in both column pairs and floats beside the vec3s fill all 64 "
                          "components",
                          GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform vec3 normals[8];\n"
                                      "uniform vec2 offsets[8];\n"
                                      "uniform vec2 scales[8];\n"
                                      "uniform float heights[8];\n",
                                      "    gl_FragColor = vec4(normals[7], heights[7]) + "
                                      "vec4(offsets[7], scales[7]);\n"),
                          ""},
                WebGlCase{"an unused uniform does not count", GlslTarget::kWebGl1, kVertex100,
                          Fragment100("uniform vec3 normals[16];\n"
                                      "uniform vec2 offset;\n",
                                      "    gl_FragColor = vec4(normals[15], 0.0);\n"),
                          ""},
                WebGlCase{"8 vec3 and 8 floats fill 8 varying rows", GlslTarget::kWebGl1,
                          kManyVaryingsVertex,
                          "#version 100\n"
                          "precision mediump float;\n"
                          "varying vec3 normals[4];\n"
                          "varying vec3 tangents[4];\n"
                          "varying float fades[8];\n"
                          "void main() { gl_FragColor = vec4(normals[3] + tangents[3], fades[7]); "
                          "}\n",
                          ""},
                WebGlCase{"a ninth vec3 varying in WebGL 2", GlslTarget::kWebGl2,
                          kManyVaryingsVertex, kNineVaryingRowsFragment, kNineVaryingRowsError},
                WebGlCase{"a ninth vec3 varying", GlslTarget::kWebGl1, kManyVaryingsVertex,
                          kNineVaryingRowsFragment, kNineVaryingRowsError}));

// The WebGL 2 conformance suite's copy of dEQP keeps image1DShadow, image2DShadow,
// image1DArrayShadow and image2DArrayShadow in reserved_keywords (GLSL ES 3.00 §3.7); plain GLSL ES
// 3.00 accepts them with a warning, as dEQP-GLES3 now expects (ConformanceRulesTest).
INSTANTIATE_TEST_SUITE_P(
        Webgl2ReservedImageShadowWords, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"a WebGL 2 local named image2DArrayShadow", GlslTarget::kWebGl2,
                          kVertex300,
                          Fragment300("",
                                      "    float image2DArrayShadow = uv.x;\n"
                                      "    colour = vec4(image2DArrayShadow);\n"),
                          "a.fsh:6:11: error: 'image2DArrayShadow' : reserved word; GLSL ES 3.00 "
                          "reserves it for future use, and using it is an error (GLSL ES 3.00 "
                          "§3.7; WebGL 2 keeps it reserved); rename it"},
                WebGlCase{"the same local without a WebGL target", GlslTarget::kEs300, kVertex300,
                          Fragment300("",
                                      "    float image2DArrayShadow = uv.x;\n"
                                      "    colour = vec4(image2DArrayShadow);\n"),
                          ""}));

// WebGL 2.0 §5.26: no `,` or `?:` over arrays, structures holding arrays or void.
INSTANTIATE_TEST_SUITE_P(
        Webgl2Operators, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"sequences and ternaries of scalars", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("uniform bool wet;\n",
                                      "    float a = uv.x;\n"
                                      "    float x = (a += 1.0, wet ? a : 2.0);\n"
                                      "    colour = vec4(x);\n"),
                          ""},
                WebGlCase{"a ternary choosing between arrays", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("uniform bool wet;\n",
                                      "    float a[2] = float[2](uv.x, uv.y);\n"
                                      "    float b[2] = float[2](uv.y, uv.x);\n"
                                      "    float c[2] = wet ? a : b;\n"
                                      "    colour = vec4(c[0]);\n"),
                          "a.fsh:9:22: error: the ternary operator '?:' applied to an array: "
                          "WebGL 2 forbids it (WebGL 2.0 §5.26 \"Disallowed variants of GLSL ES "
                          "3.00 operators\")"},
                WebGlCase{"a ternary choosing between void calls", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("uniform bool wet;\nvoid splash() {}\n",
                                      "    wet ? splash() : splash();\n"
                                      "    colour = vec4(1.0);\n"),
                          "a.fsh:8:9: error: the ternary operator '?:' applied to void: WebGL 2 "
                          "forbids it (WebGL 2.0 §5.26 \"Disallowed variants of GLSL ES 3.00 "
                          "operators\")"},
                WebGlCase{"the same choice as an if-statement", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("uniform bool wet;\nvoid splash() {}\n",
                                      "    if (wet) splash(); else splash();\n"
                                      "    colour = vec4(1.0);\n"),
                          ""},
                WebGlCase{"the ternary of void calls without a WebGL target", GlslTarget::kEs300,
                          kVertex300,
                          Fragment300("uniform bool wet;\nvoid splash() {}\n",
                                      "    wet ? splash() : splash();\n"
                                      "    colour = vec4(1.0);\n"),
                          ""},
                WebGlCase{"a sequence ending in a structure holding an array", GlslTarget::kWebGl2,
                          kVertex300,
                          Fragment300("struct Foam { float d[2]; };\n"
                                      "uniform Foam foam;\n",
                                      "    float h = uv.x;\n"
                                      "    Foam f = (h = 2.0, foam);\n"
                                      "    colour = vec4(f.d[0] + h);\n"),
                          "a.fsh:9:22: error: the sequence operator ',' applied to a structure "
                          "containing an array: WebGL 2 forbids it (WebGL 2.0 §5.26 \"Disallowed "
                          "variants of GLSL ES 3.00 operators\")"},
                WebGlCase{"the same sequence without a WebGL target", GlslTarget::kEs300,
                          kVertex300,
                          Fragment300("struct Foam { float d[2]; };\n"
                                      "uniform Foam foam;\n",
                                      "    float h = uv.x;\n"
                                      "    Foam f = (h = 2.0, foam);\n"
                                      "    colour = vec4(f.d[0] + h);\n"),
                          ""}));

const std::string kVertex300WithStd140Block =
        "#version 300 es\n"
        "in vec4 position;\n"
        "out vec2 uv;\n"
        "layout(std140) uniform Tide { highp vec4 level; };\n"
        "void main() { uv = position.xy; gl_Position = position + level; }\n";

// WebGL 2.0 "Only std140 layout supported in uniform blocks", which also makes std140 the layout
// of an unqualified block; plain GLSL ES 3.00 takes all three, and shared is its default.
INSTANTIATE_TEST_SUITE_P(
        BlockLayouts, WebGlRulesTest,
        ::testing::Values(
                WebGlCase{"std140 and an unqualified block", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("layout(std140) uniform Tide { vec4 level; };\n"
                                      "uniform Spray { vec4 amount; };\n",
                                      "    colour = level + amount;\n"),
                          ""},
                WebGlCase{"a shared block", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("layout(shared, row_major) uniform Tide { vec4 level; };\n",
                                      "    colour = level;\n"),
                          "a.fsh:5:8: error: layout qualifier 'shared': WebGL 2 supports only the "
                          "std140 layout "
                          "for uniform blocks (WebGL 2.0 \"Only std140 layout supported in "
                          "uniform blocks\"); use layout(std140) or leave the layout out"},
                WebGlCase{"packed as the default of every block", GlslTarget::kWebGl2, kVertex300,
                          Fragment300("layout(packed) uniform;\n"
                                      "uniform Tide { vec4 level; };\n",
                                      "    colour = level;\n"),
                          "a.fsh:5:8: error: layout qualifier 'packed': WebGL 2 supports only the "
                          "std140 layout "
                          "for uniform blocks (WebGL 2.0 \"Only std140 layout supported in "
                          "uniform blocks\"); use layout(std140) or leave the layout out"},
                WebGlCase{"a block std140 in one stage and unqualified in the other",
                          GlslTarget::kWebGl2, kVertex300WithStd140Block,
                          Fragment300("uniform Tide { highp vec4 level; };\n",
                                      "    colour = level;\n"),
                          ""},
                WebGlCase{"std140 by a default declaration, without a WebGL target",
                          GlslTarget::kEs300, kVertex300WithStd140Block,
                          Fragment300("layout(std140) uniform;\n"
                                      "uniform Tide { highp vec4 level; };\n",
                                      "    colour = level;\n"),
                          ""},
                WebGlCase{"the same blocks without a WebGL target, where unqualified is shared",
                          GlslTarget::kEs300, kVertex300WithStd140Block,
                          Fragment300("uniform Tide { highp vec4 level; };\n",
                                      "    colour = level;\n"),
                          "a.fsh:5:9: error: Linking vertex and fragment stages: Layout packing "
                          "qualifier must match:; vertex stage: Block: Tide Instance: anon@0: "
                          "\"layout( column_major std140) uniform\"; fragment stage: Block: Tide "
                          "Instance: anon@0: \"layout( column_major shared) uniform\""}));

}  // namespace
}  // namespace tidepool
