// Static cost analysis on small hand-written shaders whose counts were worked out by hand (the
// comments next to each line give the count that line contributes).
#include "tidepool/StaticCost.h"

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace tidepool {
namespace {

using Calls = std::map<std::string, int>;

StageCost Analyze(std::string_view source, bool is_fragment) {
    std::string log;
    const std::optional<StageCost> cost = AnalyzeSourceCost(source, is_fragment, &log);
    EXPECT_TRUE(cost.has_value()) << log;
    return cost.value_or(StageCost{});
}

StageCost AnalyzeFragment(std::string_view source) {
    return Analyze(source, true);
}
StageCost AnalyzeVertex(std::string_view source) {
    return Analyze(source, false);
}

TEST(StaticCostAnalyzerTest, BuiltinCallsAreCountedByGlslName) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform vec3 u_light_dir;
varying vec3 v_normal;
void main() {
    vec3 n = normalize(v_normal);                 // normalize
    float s = pow(dot(n, u_light_dir), 8.0);      // pow, dot
    gl_FragColor = vec4(s);
})");
    EXPECT_EQ(cost.builtin_calls, (Calls{{"dot", 1}, {"normalize", 1}, {"pow", 1}}));
    EXPECT_EQ(cost.arithmetic_ops, 0);
    EXPECT_EQ(cost.texture_samples, 0);
    EXPECT_EQ(cost.TotalOps(), 3);
    EXPECT_EQ(cost.shortest_path_ops, 3);
    EXPECT_EQ(cost.longest_path_ops, 3);
}

TEST(StaticCostAnalyzerTest, StraightLineCodeHasOnePathThatCostsEveryCountedOp) {
    // No branch: the path counts exactly the operators the totals count, whatever their kind
    // (constructors, swizzles and moves are free in both).
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform sampler2D u_tex;
varying vec2 v_uv;
void main() {
    vec4 c = texture2D(u_tex, v_uv * 2.0);          // texture2D, *
    vec3 n = normalize(c.xyz);                      // normalize
    float d = -dot(n, vec3(0.0, 1.0, 0.0));         // dot, unary -
    bool lit = !(d > 0.5);                          // >, !
    float k = float(lit) + d;                       // +
    k += 1.0;                                       // +=
    gl_FragColor = vec4(n * k, c.a);                // *
})");
    EXPECT_EQ(cost.builtin_calls, (Calls{{"dot", 1}, {"normalize", 1}, {"texture2D", 1}}));
    EXPECT_EQ(cost.arithmetic_ops, 7);
    EXPECT_EQ(cost.TotalOps(), 10);
    EXPECT_EQ(cost.shortest_path_ops, cost.TotalOps());
    EXPECT_EQ(cost.longest_path_ops, cost.TotalOps());
}

TEST(StaticCostAnalyzerTest, TextureLookupsAreSamplesAndNamedCalls) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform sampler2D u_normal_map;
uniform samplerCube u_sky;
varying vec2 v_uv;
void main() {
    vec3 n = texture2D(u_normal_map, v_uv).xyz * 2.0 - 1.0;  // texture2D, *, -
    vec4 sky = textureCube(u_sky, n);                        // textureCube
    vec4 far = texture2D(u_normal_map, v_uv * 0.5);          // texture2D, *
    gl_FragColor = sky + far;                                // +
})");
    EXPECT_EQ(cost.texture_samples, 3);
    EXPECT_EQ(cost.builtin_calls, (Calls{{"texture2D", 2}, {"textureCube", 1}}));
    EXPECT_EQ(cost.arithmetic_ops, 4);
    EXPECT_EQ(cost.TotalOps(), 7);  // each lookup once, not once as a sample and once as a call
    EXPECT_EQ(cost.samplers, 2);
    EXPECT_EQ(cost.uniforms, 0);
}

TEST(StaticCostAnalyzerTest, UncalledHelperContributesNothing) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform float u_unused_scale;
uniform float u_gain;
varying float v_height;
float Unused(float x) { return pow(x, u_unused_scale) * 3.0; }
float Used(float x) { return x * u_gain; }
void main() {
    gl_FragColor = vec4(Used(v_height));  // Used: *
})");
    EXPECT_EQ(cost.builtin_calls, Calls{});
    EXPECT_EQ(cost.arithmetic_ops, 1);
    EXPECT_EQ(cost.uniforms, 1);  // u_gain; u_unused_scale is only read by Unused
}

TEST(StaticCostAnalyzerTest, HelperIsCountedOncePerCallSite) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform float u_gain;
varying float v_height;
float Shade(float x) { return sqrt(x) * u_gain; }   // sqrt, * per call
float Twice(float x) { return Shade(x) + Shade(-x); } // +, unary minus, and two Shade calls
void main() {
    gl_FragColor = vec4(Twice(v_height), Shade(v_height), 0.0, 1.0);
})");
    // Three calls of Shade (two through Twice), plus Twice's own + and unary minus.
    EXPECT_EQ(cost.builtin_calls, (Calls{{"sqrt", 3}}));
    EXPECT_EQ(cost.arithmetic_ops, 5);
    EXPECT_EQ(cost.TotalOps(), 8);
    EXPECT_EQ(cost.longest_path_ops, 8);
    EXPECT_EQ(cost.uniforms, 1);
}

TEST(StaticCostAnalyzerTest, IfElsePathsTakeTheCheaperAndTheDearerArm) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform float u_threshold;
varying vec3 v_normal;
varying vec3 v_view;
void main() {
    vec3 color = vec3(0.0);
    if (v_normal.y > u_threshold) {                         // >
        color = vec3(0.5);                                  // nothing
    } else {
        vec3 r = reflect(-v_view, normalize(v_normal));     // unary minus, reflect, normalize
        color = r * pow(max(dot(r, v_view), 0.0), 16.0);    // *, pow, max, dot
    }
    gl_FragColor = vec4(color, 1.0);
})");
    EXPECT_EQ(cost.branches, 1);
    EXPECT_EQ(cost.shortest_path_ops, 1);  // condition + empty arm
    EXPECT_EQ(cost.longest_path_ops, 8);   // condition + 7 in the else arm
    EXPECT_EQ(cost.TotalOps(), 8);
    EXPECT_EQ(cost.arithmetic_ops, 3);
    EXPECT_EQ(cost.builtin_calls,
              (Calls{{"dot", 1}, {"max", 1}, {"normalize", 1}, {"pow", 1}, {"reflect", 1}}));
}

TEST(StaticCostAnalyzerTest, ConditionalExpressionAndElseIfAreBranches) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
varying vec4 v_a;
void main() {
    float edge = v_a.z > 0.0 ? v_a.z : sqrt(abs(v_a.z));  // >, then 0 or 2
    if (v_a.x > 0.5) {                                     // >
        edge += 1.0;                                       // +=
    } else if (v_a.y > 0.5) {                              // >
        edge = exp2(edge) * 3.0;                           // exp2, *
    }
    gl_FragColor = vec4(edge);
})");
    EXPECT_EQ(cost.branches, 3);
    // Shortest: 1 + 0 (?:) + 1 + min(1, 1 + 0) = 3. Longest: 1 + 2 + 1 + max(1, 1 + 2) = 7.
    EXPECT_EQ(cost.shortest_path_ops, 3);
    EXPECT_EQ(cost.longest_path_ops, 7);
    EXPECT_EQ(cost.TotalOps(), 8);
}

TEST(StaticCostAnalyzerTest, LoopIsCountedOnceWhateverItsTripCount) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
uniform sampler2D u_waves;
varying vec2 v_uv;
void main() {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; i++) {                          // <, ++
        sum += texture2D(u_waves, v_uv * float(i + 1));    // +=, texture2D, *, +
    }
    gl_FragColor = sum * 0.25;                             // *
})");
    EXPECT_EQ(cost.loops, 1);
    EXPECT_EQ(cost.branches, 0);
    EXPECT_EQ(cost.texture_samples, 1);
    EXPECT_EQ(cost.arithmetic_ops, 6);
    EXPECT_EQ(cost.TotalOps(), 7);
    EXPECT_EQ(cost.shortest_path_ops, 7);
    EXPECT_EQ(cost.longest_path_ops, 7);
}

TEST(StaticCostAnalyzerTest, VertexInterfaceCountsReferencedDeclarations) {
    const StageCost cost = AnalyzeVertex(R"(
attribute vec4 a_position;
attribute vec2 a_uv;
uniform mat4 u_mvp;
uniform float u_time;
uniform vec4 u_waves[4];
uniform float u_unused;
uniform sampler2D u_height;
varying vec2 v_uv;
varying float v_height;
varying vec3 v_never_written;
void main() {
    float h = texture2DLod(u_height, a_uv, 0.0).r + u_waves[0].x * u_waves[1].y * u_time;
    v_uv = a_uv;
    v_height = h;
    gl_Position = u_mvp * (a_position + vec4(0.0, h, 0.0, 0.0));
})");
    EXPECT_EQ(cost.uniforms, 3);  // u_mvp, u_time, u_waves (one array, one declaration)
    EXPECT_EQ(cost.samplers, 1);  // u_height
    EXPECT_EQ(cost.varyings, 2);  // v_uv, v_height; attributes and gl_Position are not varyings
    EXPECT_EQ(cost.builtin_calls, (Calls{{"texture2DLod", 1}}));
    EXPECT_EQ(cost.texture_samples, 1);
    EXPECT_EQ(cost.arithmetic_ops, 5);
}

TEST(StaticCostAnalyzerTest, FragmentInterfaceCountsReferencedDeclarations) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
struct Light { vec3 dir; vec3 color; };
uniform Light u_light;
uniform sampler2D u_foam;
uniform sampler2D u_unused_map;
varying vec2 v_uv;
varying float v_height;
varying vec3 v_not_read;
void main() {
    vec4 foam = texture2D(u_foam, v_uv);
    gl_FragColor = vec4(u_light.color * v_height, 1.0) + foam;
})");
    EXPECT_EQ(cost.uniforms, 1);  // u_light: a struct is one declaration
    EXPECT_EQ(cost.samplers, 1);  // u_foam
    EXPECT_EQ(cost.varyings, 2);  // v_uv, v_height
    EXPECT_EQ(cost.arithmetic_ops, 2);
}

// One statement per row, spliced into a fragment shader: which constructs are arithmetic, which
// are named builtin calls (several share a glslang operator with a syntactic operator), which
// are free.
struct OperatorCase {
    const char* statement;
    int arithmetic_ops;
    int branches;
    Calls builtin_calls;
};

TEST(StaticCostAnalyzerTest, OperatorsAndBuiltinsAreClassifiedByGlslConstruct) {
    // clang-format off
    const OperatorCase cases[] = {
        {"gl_FragColor = mod(v_a, v_b);",
         0, 0, {{"mod", 1}}},
        {"gl_FragColor = vec4(matrixCompMult(u_m, u_m)[0], 0.0, 0.0);",
         0, 0, {{"matrixCompMult", 1}}},
        {"gl_FragColor = vec4(u_m * u_m[0], 0.0, 0.0);",
         1, 0, {}},
        {"gl_FragColor = vec4(lessThan(v_a, v_b));",
         0, 0, {{"lessThan", 1}}},
        {"gl_FragColor = vec4(v_a.x < v_b.x);",
         1, 0, {}},
        {"gl_FragColor = vec4(not(lessThan(v_a, v_b)));",
         0, 0, {{"lessThan", 1}, {"not", 1}}},
        {"gl_FragColor = vec4(!(v_a.x < v_b.x));",
         2, 0, {}},
        {"gl_FragColor = vec4(v_a == v_b);",
         1, 0, {}},
        {"gl_FragColor = vec4(atan(v_a.x, v_b.x) + atan(v_a.y));",
         1, 0, {{"atan", 2}}},
        {"gl_FragColor = vec4(dFdx(v_a.x) + fwidth(v_a.y));",
         1, 0, {{"dFdx", 1}, {"fwidth", 1}}},
        {"gl_FragColor = vec4(inversesqrt(v_a.x), smoothstep(0.0, 1.0, v_b.x), 0.0, 1.0);",
         0, 0, {{"inversesqrt", 1}, {"smoothstep", 1}}},
        {"gl_FragColor = v_a; gl_FragColor.x = 2.0 * 3.0;",
         0, 0, {}},  // constant-folded
        {"gl_FragColor = vec4(v_a.xy, float(int(v_b.x)), 1.0);",
         0, 0, {}},  // all free
        {"vec4 c = v_a; c += v_b; c *= 2.0; c.x++; gl_FragColor = -c;",
         4, 0, {}},
        {"gl_FragColor = vec4(v_a.x > 0.0 && v_b.x > 0.0);",
         3, 0, {}},
        {"gl_FragColor = any(equal(v_a, v_b)) ? v_a : v_b;",
         0, 1, {{"any", 1}, {"equal", 1}}},
        {"gl_FragColor = texture2DProj(u_s, v_a);",
         0, 0, {{"texture2DProj", 1}}},
        {"gl_FragColor = textureCube(u_c, v_a.xyz, 1.0);",
         0, 0, {{"textureCube", 1}}},  // with bias
        {"gl_FragColor = texture2DLodEXT(u_s, v_a.xy, 0.0);",
         0, 0, {{"texture2DLodEXT", 1}}},
        {"gl_FragColor = texture2DGradEXT(u_s, v_a.xy, v_b.xy, v_b.zw);",
         0, 0, {{"texture2DGradEXT", 1}}},
    };
    // clang-format on
    for (const OperatorCase& row : cases) {
        SCOPED_TRACE(row.statement);
        const std::string source = std::string(R"(
#extension GL_OES_standard_derivatives : enable
#extension GL_EXT_shader_texture_lod : enable
precision mediump float;
uniform mat2 u_m;
uniform sampler2D u_s;
uniform samplerCube u_c;
varying vec4 v_a;
varying vec4 v_b;
void main() {
    )") + row.statement + "\n}\n";
        const StageCost cost = AnalyzeFragment(source);
        EXPECT_EQ(cost.arithmetic_ops, row.arithmetic_ops);
        EXPECT_EQ(cost.builtin_calls, row.builtin_calls);
        EXPECT_EQ(cost.branches, row.branches);
    }
}

TEST(StaticCostAnalyzerTest, MissingMainCostsNothing) {
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
float Helper(float x) { return x * x; }
)");
    EXPECT_EQ(cost.TotalOps(), 0);
    EXPECT_EQ(cost.longest_path_ops, 0);
}

TEST(StaticCostAnalyzerTest, RecursionIsCountedOnceInsteadOfForever) {
    // GLSL ES forbids recursion and glslang's linker rejects it, but the parser accepts it; the
    // recursive call must contribute nothing rather than hang the analysis.
    const StageCost cost = AnalyzeFragment(R"(
precision mediump float;
varying float v_x;
float Loop(float x) { return Loop(x * 0.5) + 1.0; }   // *, +
void main() { gl_FragColor = vec4(Loop(v_x)); }
)");
    EXPECT_EQ(cost.arithmetic_ops, 2);
    EXPECT_EQ(cost.longest_path_ops, 2);
}

TEST(StaticCostAnalyzerTest, InvalidSourceReturnsGlslangLog) {
    std::string log;
    const std::optional<StageCost> cost = AnalyzeSourceCost(
            "precision mediump float;\nvoid main() { gl_FragColor = undeclared; }\n", true, &log);
    EXPECT_FALSE(cost.has_value());
    EXPECT_NE(log.find("'undeclared' : undeclared identifier"), std::string::npos) << log;
}

TEST(StaticCostAnalyzerTest, ToJsonHasEveryFieldAndTotalOps) {
    StageCost cost;
    cost.arithmetic_ops = 4;
    cost.texture_samples = 1;
    cost.builtin_calls = {{"texture2D", 1}, {"pow", 2}};
    cost.branches = 1;
    cost.loops = 2;
    cost.uniforms = 3;
    cost.varyings = 4;
    cost.samplers = 1;
    cost.shortest_path_ops = 5;
    cost.longest_path_ops = 7;
    const nlohmann::json expected = {
            {"arithmetic_ops", 4},
            {"texture_samples", 1},
            {"builtin_calls", {{"pow", 2}, {"texture2D", 1}}},
            {"branches", 1},
            {"loops", 2},
            {"uniforms", 3},
            {"varyings", 4},
            {"samplers", 1},
            {"shortest_path_ops", 5},
            {"longest_path_ops", 7},
            {"total_ops", 7},
    };
    EXPECT_EQ(ToJson(cost), expected);
}

}  // namespace
}  // namespace tidepool
