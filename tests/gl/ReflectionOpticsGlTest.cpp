// The seeds' alternatives through Mesa: cube-map and Fourier reflections against the planar
// reflection pass, and the depth-based optics against their formulas.
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/runner/WaterMath.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "GlTestEnvironment.h"
#include <glm/glm.hpp>

namespace tidepool::runner {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

using test_support::GlTestEnvironment;

GlTestEnvironment& Get() {
    return test_support::SharedGlEnvironment();
}

class ReflectionOpticsGlTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!Get().error.empty()) {
            GTEST_SKIP() << Get().error;
        }
    }
};

RenderConfiguration Configuration(std::vector<std::string> defines) {
    RenderConfiguration c;
    c.variant = MakeVariant("water", std::move(defines));
    c.effects = c.variant.defines;
    c.id = ConfigurationId(c.variant, c.passes);
    return c;
}

// A scene with nothing above the water: the flat sea floor at `depth` and the sky.
Scene OnlySkyAbove(float depth) {
    SceneDescription description;
    description.name = "only_sky_above";
    description.water_depth = depth;
    description.above_terrain = false;
    description.above_objects = false;
    description.below_terrain = true;
    description.below_objects = false;
    return BuildSceneFromDescription(description);
}

std::unique_ptr<WaterRenderer> MakeRenderer(const Scene* scene) {
    GlTestEnvironment& s = Get();
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    std::string error;
    auto renderer = WaterRenderer::Create(*s.context, *s.config, settings, &error, scene);
    EXPECT_NE(renderer, nullptr) << error;
    return renderer;
}

base::RgbaImage Render(WaterRenderer& renderer, const RenderConfiguration& c,
                       const CameraView& view) {
    const DriverVerdict verdict = renderer.Prepare(c);
    EXPECT_TRUE(verdict.valid) << c.id << "\n"
                               << verdict.vertex_log << verdict.fragment_log << verdict.link_log;
    const FrameReport report = renderer.RenderFrame(c, view);
    EXPECT_EQ(report.gl_error, "") << c.id;
    renderer.Finish();
    base::RgbaImage image = renderer.ReadImage();
    if (const char* dump = std::getenv("TIDEPOOL_TEST_IMAGES")) {
        base::WritePngAtomically(
                std::filesystem::path(dump) / (SanitiseFileName(c.id) + "-" + view.name + ".png"),
                image);
    }
    return image;
}

glm::vec3 Pixel(const base::RgbaImage& image, int x, int y) {
    const auto i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                    static_cast<std::size_t>(x)) *
                   4;
    return glm::vec3(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]) / 255.0F;
}

CameraView LookingAt(glm::vec3 eye, glm::vec3 target) {
    CameraView view = DefaultViews().front();
    view.name = "test";
    view.eye = eye;
    view.target = target;
    return view;
}

TEST_F(ReflectionOpticsGlTest, CubeMapReflectionMatchesPlanarWhenOnlySkyIsAbove) {
    // With nothing above the water, the mirrored scene is the sky at infinity, whose direction
    // at every pixel is the reflected view ray: exactly what the cube-map lookup reads. What is
    // left is the reflection texture's resampling (256² stretched over the screen).
    const Scene scene = OnlySkyAbove(20.0F);
    std::unique_ptr<WaterRenderer> renderer = MakeRenderer(&scene);
    ASSERT_NE(renderer, nullptr);
    for (const CameraView& view :
         {LookingAt({0, 30, 80}, {0, 0, 0}), LookingAt({40, 8, 60}, {-20, 0, -40})}) {
        const base::RgbaImage planar = Render(*renderer, Configuration({}), view);
        const base::RgbaImage cubemap =
                Render(*renderer, Configuration({"REFLECTION_CUBEMAP"}), view);
        EXPECT_GE(base::Psnr(planar, cubemap), 35.0) << "eye " << view.eye.x << "," << view.eye.y;
    }
}

TEST_F(ReflectionOpticsGlTest, CubeMapReflectionMissesTheLocalObjectsPlanarShows) {
    // The default scene at the shore view reflects the island and the objects; the cube map
    // cannot, so it differs from planar far more than the resampling difference above.
    std::unique_ptr<WaterRenderer> renderer = MakeRenderer(nullptr);
    ASSERT_NE(renderer, nullptr);
    const CameraView view = *FindView(DefaultViews(), "shore");
    const base::RgbaImage planar = Render(*renderer, Configuration({}), view);
    const base::RgbaImage cubemap = Render(*renderer, Configuration({"REFLECTION_CUBEMAP"}), view);
    EXPECT_LT(base::Psnr(planar, cubemap), 30.0);
}

TEST_F(ReflectionOpticsGlTest, FourierReflectionIsCloserToPlanarThanTheCubeMapWhereTerrainIs) {
    // The island's reflection: the Fourier coefficients put the terrain colour where planar
    // shows the island, where the cube map shows sky; away from the terrain they agree.
    std::unique_ptr<WaterRenderer> renderer = MakeRenderer(nullptr);
    ASSERT_NE(renderer, nullptr);
    const auto images = [&](const char* name) {
        const CameraView view = *FindView(DefaultViews(), name);
        return std::array<base::RgbaImage, 3>{
                Render(*renderer, Configuration({}), view),
                Render(*renderer, Configuration({"REFLECTION_CUBEMAP"}), view),
                Render(*renderer, Configuration({"REFLECTION_FOURIER"}), view)};
    };
    // three_quarter looks at the island across the water.
    const auto island = images("three_quarter");
    EXPECT_GT(base::Psnr(island[0], island[2]), base::Psnr(island[0], island[1]) + 0.5);
    // shore looks out to sea with the island behind: no terrain to reflect, so the Fourier
    // reflection is the cube map's sky, and both miss the boat and pillars alike.
    const auto sea = images("shore");
    EXPECT_NEAR(base::Psnr(sea[0], sea[2]), base::Psnr(sea[0], sea[1]), 0.5);
}

TEST_F(ReflectionOpticsGlTest, NoReflectionPassForCubeMapOrFourier) {
    std::unique_ptr<WaterRenderer> renderer = MakeRenderer(nullptr);
    ASSERT_NE(renderer, nullptr);
    const CameraView view = DefaultViews().front();
    for (const char* reflection : {"REFLECTION_CUBEMAP", "REFLECTION_FOURIER"}) {
        const RenderConfiguration c = Configuration({reflection, "ENABLE_REFRACTION"});
        ASSERT_TRUE(renderer->Prepare(c).valid) << c.id;
        const FrameReport report = renderer->RenderFrame(c, view);
        EXPECT_EQ(report.pass_names, (std::vector<std::string>{"refraction", "main"})) << c.id;
    }
    const RenderConfiguration planar = Configuration({"ENABLE_REFRACTION"});
    ASSERT_TRUE(renderer->Prepare(planar).valid);
    EXPECT_EQ(renderer->RenderFrame(planar, view).pass_names,
              (std::vector<std::string>{"reflection", "refraction", "main"}));
}

TEST_F(ReflectionOpticsGlTest, ExtinctionMatchesItsFormulaAtSampledDepths) {
    // TP_OUTPUT_REFRACTION shows the refracted colour after the optics. Over a flat floor at a
    // known depth, the colour with ENABLE_EXTINCTION must be ExtinctionColour() of the colour
    // without it, at the depth the refraction pass's 8-bit alpha can store.
    const glm::vec3 eye(0.0F, 25.0F, 50.0F);
    const CameraView view = LookingAt(eye, {0.0F, 0.0F, 0.0F});
    // The cosine of the view angle where the ray through pixel (x, y) meets the water (y = 0).
    const glm::mat4 inverse = glm::inverse(
            ProjectionMatrix(view, static_cast<float>(kWidth) / kHeight) * ViewMatrix(view));
    const auto cos_view_at = [&](int x, int y) {
        const glm::vec4 ndc((static_cast<float>(x) + 0.5F) / kWidth * 2.0F - 1.0F,
                            1.0F - (static_cast<float>(y) + 0.5F) / kHeight * 2.0F, 1.0F, 1.0F);
        const glm::vec4 far = inverse * ndc;
        const glm::vec3 direction = glm::normalize(glm::vec3(far) / far.w - eye);
        const glm::vec3 on_water = eye + direction * (-eye.y / direction.y);
        return glm::normalize(eye - on_water).y;
    };
    for (const float depth : {1.0F, 4.5F, 10.0F, 30.0F}) {
        const Scene scene = OnlySkyAbove(depth);
        std::unique_ptr<WaterRenderer> renderer = MakeRenderer(&scene);
        ASSERT_NE(renderer, nullptr);
        const RenderSettings& settings = renderer->Settings();
        const base::RgbaImage plain = Render(
                *renderer, Configuration({"ENABLE_REFRACTION", "TP_OUTPUT_REFRACTION"}), view);
        const base::RgbaImage extinct = Render(
                *renderer,
                Configuration({"ENABLE_REFRACTION", "ENABLE_EXTINCTION", "TP_OUTPUT_REFRACTION"}),
                view);
        // The refraction pass stores sqrt(depth / max) in 8 bits (shaders/model.fsh).
        const float stored =
                std::round(std::sqrt(depth / settings.max_water_depth) * 255.0F) / 255.0F;
        const float stored_depth = stored * stored * settings.max_water_depth;
        for (const auto& [x, y] :
             {std::pair{kWidth / 2, kHeight / 2}, std::pair{kWidth / 2 - 10, kHeight / 2 + 8}}) {
            const glm::vec3 expected = ExtinctionColour(Pixel(plain, x, y), stored_depth,
                                                        cos_view_at(x, y), settings.extinction);
            const glm::vec3 measured = Pixel(extinct, x, y);
            for (int channel = 0; channel < 3; ++channel) {
                // Two 8-bit roundings: the refraction and the output.
                EXPECT_NEAR(measured[channel], expected[channel], 3.0F / 255.0F)
                        << "depth " << depth << ", channel " << channel << ", pixel " << x << ","
                        << y;
            }
        }
        // The formula's point: red is gone by 4.5 units, blue lasts to 300.
        if (depth >= 4.5F) {
            const glm::vec3 centre = Pixel(extinct, kWidth / 2, kHeight / 2);
            EXPECT_LT(centre.r, centre.b) << "depth " << depth;
        }
    }
}

TEST_F(ReflectionOpticsGlTest, SoftShoreShowsTheRefractionAtTheWaterline) {
    // At depth 0 the soft shore blends entirely back to the refraction: over a floor right at
    // the surface, the water with the soft shore is the refraction itself.
    const Scene scene = OnlySkyAbove(0.05F);
    std::unique_ptr<WaterRenderer> renderer = MakeRenderer(&scene);
    ASSERT_NE(renderer, nullptr);
    const CameraView view = LookingAt({0, 25, 50}, {0, 0, 0});
    const base::RgbaImage refraction =
            Render(*renderer, Configuration({"ENABLE_REFRACTION", "TP_OUTPUT_REFRACTION"}), view);
    const base::RgbaImage soft =
            Render(*renderer, Configuration({"ENABLE_REFRACTION", "ENABLE_SOFT_SHORE"}), view);
    const base::RgbaImage hard = Render(*renderer, Configuration({"ENABLE_REFRACTION"}), view);
    const glm::vec3 r = Pixel(refraction, kWidth / 2, kHeight / 2);
    const glm::vec3 s = Pixel(soft, kWidth / 2, kHeight / 2);
    const glm::vec3 h = Pixel(hard, kWidth / 2, kHeight / 2);
    EXPECT_LT(glm::length(s - r), glm::length(h - r));
    EXPECT_LT(glm::length(s - r), 0.1F);
}

}  // namespace
}  // namespace tidepool::runner
