// Backend selection and Mesa's GLSL compiler: which contexts exist, that `#version 100` compiles
// on both, and that Mesa's info-log lines are the user's lines.
#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/MesaInfoLog.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/Renderer.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace tidepool::runner {
namespace {

// The error sits on line 9 of the user's file, inside a block only one define enables.
constexpr const char* kUserFragment =
        "#version 100\n"                           // 1
        "precision mediump float;\n"               // 2
        "uniform vec3 FogColour;\n"                // 3
        "void main()\n"                            // 4
        "{\n"                                      // 5
        "    vec3 colour = vec3(0.0);\n"           // 6
        "#ifdef ENABLE_FOG\n"                      // 7
        "    colour = FogColour;\n"                // 8
        "    colour = undeclaredThing * 2.0;\n"    // 9
        "#endif\n"                                 // 10
        "    gl_FragColor = vec4(colour, 1.0);\n"  // 11
        "}\n";                                     // 12
constexpr int kErrorLine = 9;
constexpr int kErrorColumn = 14;  // 1-based column of `undeclaredThing`

void ExpectLineMapping(GlContext& context) {
    const std::string gated = AssembleDriverSource(kUserFragment, {"ENABLE_A", "ENABLE_FOG"},
                                                   Stage::kFragment, GlslTarget::kEs100);
    const DriverStageResult failed = CompileDriverStage(context, Stage::kFragment, gated);
    ASSERT_FALSE(failed.compiled);
    const std::vector<Diagnostic> diagnostics =
            ParseMesaInfoLog(failed.log, "user.fsh", "user:ENABLE_FOG", kUserFragment);
    ASSERT_FALSE(diagnostics.empty()) << failed.log;
    EXPECT_EQ(diagnostics[0].line, kErrorLine) << failed.log;
    EXPECT_EQ(diagnostics[0].column, kErrorColumn) << failed.log;
    EXPECT_NE(diagnostics[0].message.find("undeclaredThing"), std::string::npos);

    const std::string ungated =
            AssembleDriverSource(kUserFragment, {}, Stage::kFragment, GlslTarget::kEs100);
    const DriverStageResult passed = CompileDriverStage(context, Stage::kFragment, ungated);
    EXPECT_TRUE(passed.compiled) << passed.log;
}

TEST(GlBackendGlTest, EglLineNumbersInMesasLogAreTheUsersLines) {
    GlContextResult egl = CreateGlContext(BackendKind::kEgl);
    if (!egl.context) {
        GTEST_SKIP() << egl.error;
    }
    EXPECT_EQ(egl.context->Environment().backend, "egl");
    EXPECT_EQ(egl.context->Environment().context_api, "OpenGL ES");
    EXPECT_FALSE(egl.context->Environment().mesa_version.empty());
    ExpectLineMapping(*egl.context);
}

// OSMesa gives a desktop compatibility context; `#version 100` compiles there because Mesa
// exposes ARB_ES2_compatibility. The same water variant must compile, link and render.
TEST(GlBackendGlTest, ForcingOsMesaCompilesAndRendersTheEsShaders) {
    GlContextResult osmesa = CreateGlContext(BackendKind::kOsMesa);
    ASSERT_TRUE(osmesa.context) << osmesa.error;
    ASSERT_EQ(osmesa.attempts.size(), 1U);
    EXPECT_EQ(osmesa.context->Environment().backend, "osmesa");
    EXPECT_EQ(osmesa.context->Environment().context_api, "OpenGL compatibility");
    ExpectLineMapping(*osmesa.context);

    ConfigResult loaded =
            LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
    ASSERT_TRUE(loaded.config);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    std::string error;
    std::unique_ptr<WaterRenderer> renderer =
            WaterRenderer::Create(*osmesa.context, *loaded.config, settings, &error);
    ASSERT_TRUE(renderer) << error;
    RenderConfiguration c;
    c.variant = MakeVariant(
            "water", {"ENABLE_REFRACTION", "ENABLE_FRESNEL", "ENABLE_FOG", "ENABLE_DISTORTION"});
    c.effects = c.variant.defines;
    c.id = c.variant.Id();
    const DriverVerdict verdict = renderer->Prepare(c);
    ASSERT_TRUE(verdict.valid) << verdict.vertex_log << verdict.fragment_log << verdict.link_log;
    const FrameReport report = renderer->RenderFrame(c, DefaultViews().front());
    EXPECT_EQ(report.gl_error, "");
    EXPECT_EQ(report.passes, 3);
}

TEST(GlBackendGlTest, AutoPrefersEgl) {
    GlContextResult any = CreateGlContext(BackendKind::kAuto);
    ASSERT_TRUE(any.context) << any.error;
    ASSERT_FALSE(any.attempts.empty());
    EXPECT_EQ(any.attempts.front().kind, BackendKind::kEgl);
    if (any.attempts.front().failure.empty()) {
        EXPECT_EQ(any.context->Environment().backend, "egl");
    }
}

}  // namespace
}  // namespace tidepool::runner
