// The embedded water renderer through Mesa: what the passes put on screen, determinism, GL
// errors and NaN/Inf, on small images so the whole suite stays fast.
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/runner/FramePlan.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/runner/Results.h"
#include "tidepool/runner/WaterMath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "SharedWaterRenderer.h"
#include <glm/glm.hpp>

namespace tidepool::runner {
namespace {

using test_support::kRendererHeight;
using test_support::kRendererWidth;

test_support::SharedRenderer& Get() {
    return test_support::SharedWaterRenderer();
}

RenderConfiguration Configuration(std::vector<std::string> defines, PassOptions passes = {}) {
    return test_support::WaterConfiguration(std::move(defines), passes);
}

base::RgbaImage Render(const RenderConfiguration& c, const std::string& view_name,
                       WaterRenderer* renderer = nullptr) {
    test_support::SharedRenderer& s = Get();
    WaterRenderer& r = renderer ? *renderer : *s.renderer;
    s.context->MakeCurrent();  // another test file's context may be current
    const DriverVerdict verdict = r.Prepare(c);
    EXPECT_TRUE(verdict.valid) << c.id << "\n"
                               << verdict.vertex_log << verdict.fragment_log << verdict.link_log;
    const std::vector<CameraView> views = DefaultViews();
    const CameraView* view = FindView(views, view_name);
    EXPECT_NE(view, nullptr);
    const FrameReport report = r.RenderFrame(c, *view);
    EXPECT_EQ(report.gl_error, "") << c.id;
    r.Finish();
    base::RgbaImage image = r.ReadImage();
    if (const char* dump = std::getenv("TIDEPOOL_TEST_IMAGES")) {
        base::WritePngAtomically(
                std::filesystem::path(dump) / (SanitiseFileName(c.id) + "-" + view_name + ".png"),
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

class WaterRendererGlTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!Get().renderer) {
            GTEST_SKIP() << "no GL renderer: " << Get().error;
        }
    }
};

// Hue in degrees (0..360) and saturation (0..1) of an RGB colour.
std::pair<float, float> HueSaturation(const glm::vec3& c) {
    const float high = std::max({c.r, c.g, c.b});
    const float low = std::min({c.r, c.g, c.b});
    const float chroma = high - low;
    if (chroma <= 0.0F) {
        return {0.0F, 0.0F};
    }
    float hue = 0;
    if (high == c.r) {
        hue = 60.0F * std::fmod((c.g - c.b) / chroma + 6.0F, 6.0F);
    } else if (high == c.g) {
        hue = 60.0F * ((c.b - c.r) / chroma + 2.0F);
    } else {
        hue = 60.0F * ((c.r - c.g) / chroma + 4.0F);
    }
    return {hue, chroma / high};
}

// Counts pixels with a saturated hue in [low, high] degrees.
int CountHue(const base::RgbaImage& image, float low, float high) {
    int count = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const auto [hue, saturation] = HueSaturation(Pixel(image, x, y));
            // 0.4: the scene's object colours are fully saturated; sky, water and terrain are
            // far below that, so only the objects (and their reflections) count.
            count += saturation > 0.4F && hue >= low && hue <= high ? 1 : 0;
        }
    }
    return count;
}

// Whether a saturated pixel of hue [low, high] lies within `radius` pixels of `centre`.
bool HueNear(const base::RgbaImage& image, glm::ivec2 centre, int radius, float low, float high) {
    for (int y = centre.y - radius; y <= centre.y + radius; ++y) {
        for (int x = centre.x - radius; x <= centre.x + radius; ++x) {
            if (x < 0 || y < 0 || x >= image.width || y >= image.height) {
                continue;
            }
            const auto [hue, saturation] = HueSaturation(Pixel(image, x, y));
            if (saturation > 0.4F && hue >= low && hue <= high) {
                return true;
            }
        }
    }
    return false;
}

const Mesh& FindMesh(const Scene& scene, const std::string& name) {
    for (const Mesh& mesh : scene.objects) {
        if (mesh.name == name) {
            return mesh;
        }
    }
    ADD_FAILURE() << "no mesh " << name;
    return scene.terrain;
}

// The pixel (rows top to bottom) where `world` lands at `view`.
glm::ivec2 ScreenPixel(const CameraView& view, const glm::vec3& world) {
    const float aspect = static_cast<float>(kRendererWidth) / static_cast<float>(kRendererHeight);
    const glm::vec2 uv =
            ProjectiveTexCoord(ProjectionMatrix(view, aspect) * ViewMatrix(view), world);
    return glm::ivec2(static_cast<int>(uv.x * kRendererWidth),
                      static_cast<int>((1.0F - uv.y) * kRendererHeight));
}

TEST_F(WaterRendererGlTest, ReflectionOfTheTowerAppearsMirroredBelowTheWaterline) {
    const Scene& scene = Get().renderer->GetScene();
    const Mesh& tower = FindMesh(scene, "tower");
    const glm::vec3 centre = (tower.world_bounds_min + tower.world_bounds_max) * 0.5F;
    // A point on the tower well above the water, and its mirror image about y = water height.
    const glm::vec3 point(
            centre.x, glm::mix(tower.world_bounds_min.y, tower.world_bounds_max.y, 0.6F), centre.z);
    const glm::vec3 mirrored(point.x, 2.0F * scene.water_height - point.y, point.z);
    const CameraView view = *FindView(DefaultViews(), "grazing");
    const base::RgbaImage image = Render(Configuration({}), "grazing");
    const glm::ivec2 direct = ScreenPixel(view, point);
    const glm::ivec2 reflected = ScreenPixel(view, mirrored);
    ASSERT_GT(reflected.y, direct.y) << "the mirrored point must project below the tower";
    // The tower is orange (hue about 25 degrees); 2 pixels of slack for the 256x256 reflection
    // texture being magnified onto a 128x96 image and for linear filtering at its edges.
    EXPECT_TRUE(HueNear(image, direct, 2, 10.0F, 45.0F))
            << "tower not at " << direct.x << "," << direct.y;
    EXPECT_TRUE(HueNear(image, reflected, 2, 10.0F, 45.0F))
            << "no reflection at " << reflected.x << "," << reflected.y;
}

TEST_F(WaterRendererGlTest, RefractionShowsTheSubmergedRocksAndReflectionOnlyDoesNot) {
    // Magenta is about 300 degrees; no other object, nor sky or terrain, is near that hue.
    // The rocks are small at 128x96, so two views look for them.
    int with_refraction = 0;
    int reflection_only = 0;
    for (const char* view : {"high", "three_quarter"}) {
        with_refraction +=
                CountHue(Render(Configuration({"ENABLE_REFRACTION"}), view), 280.0F, 320.0F);
        reflection_only += CountHue(Render(Configuration({}), view), 280.0F, 320.0F);
    }
    // 4 pixels: each rock covers a few pixels at this size; none may show without refraction.
    EXPECT_GE(with_refraction, 4);
    EXPECT_EQ(reflection_only, 0);
}

TEST_F(WaterRendererGlTest, FogMovesFarWaterTowardsTheFogColour) {
    const CameraView view = *FindView(DefaultViews(), "three_quarter");
    // Water 1500 units away along the view direction, projected onto the plane.
    glm::vec3 forward = view.target - view.eye;
    forward.y = 0.0F;
    const glm::vec3 far_water = view.eye + glm::normalize(forward) * 1500.0F;
    const glm::ivec2 pixel = ScreenPixel(view, glm::vec3(far_water.x, 0.0F, far_water.z));
    ASSERT_GE(pixel.y, 0);
    ASSERT_LT(pixel.y, kRendererHeight);
    const glm::vec3 fog = RenderSettings{}.fog_colour;
    const glm::vec3 clear = Pixel(Render(Configuration({}), "three_quarter"), pixel.x, pixel.y);
    const glm::vec3 fogged =
            Pixel(Render(Configuration({"ENABLE_FOG"}), "three_quarter"), pixel.x, pixel.y);
    // At 1500 of 2000 units the fog factor is 0.75, so the distance to the fog colour must
    // shrink to about a quarter; 0.5 leaves room for the sky's own horizon colour.
    EXPECT_LT(glm::length(fogged - fog), 0.5F * glm::length(clear - fog))
            << "clear " << clear.r << "," << clear.g << "," << clear.b << " fogged " << fogged.r
            << "," << fogged.g << "," << fogged.b;
}

TEST_F(WaterRendererGlTest, TwoRendersOfOneConfigurationAreByteEqual) {
    const RenderConfiguration full = Configuration(
            {"ENABLE_REFRACTION", "ENABLE_FRESNEL", "ENABLE_DISTORTION", "ENABLE_FOG"});
    const base::RgbaImage first = Render(full, "shore");
    Render(Configuration({"ENABLE_WATER_COLOUR"}), "high");  // something else in between
    const base::RgbaImage second = Render(full, "shore");
    EXPECT_TRUE(first.pixels == second.pixels);
}

TEST_F(WaterRendererGlTest, EveryDefaultConfigurationRendersWithoutGlError) {
    test_support::SharedRenderer& s = Get();
    const ConfigurationSet set = BuildDefaultConfigurations(*s.config, s.variants);
    ASSERT_TRUE(set.diagnostics.empty());
    ASSERT_GT(set.configurations.size(), 10U);
    const CameraView view = *FindView(DefaultViews(), "three_quarter");
    s.context->MakeCurrent();
    // Prepare everything first, then render: as a run does, so per-size targets must persist.
    for (const RenderConfiguration& c : set.configurations) {
        const DriverVerdict verdict = s.renderer->Prepare(c);
        ASSERT_TRUE(verdict.valid) << c.id << "\n" << verdict.fragment_log << verdict.link_log;
    }
    for (const RenderConfiguration& c : set.configurations) {
        const FrameReport report = s.renderer->RenderFrame(c, view);
        EXPECT_EQ(report.gl_error, "") << c.id;
        // Main at least; the planar reflection (no REFLECTION_ define) adds a pass, refraction
        // one, low-resolution water another.
        const bool planar = !c.Has("REFLECTION_CUBEMAP") && !c.Has("REFLECTION_FOURIER");
        const int expected = 1 + (planar ? 1 : 0) + (c.Has("ENABLE_REFRACTION") ? 1 : 0) +
                             (c.passes.low_res_water ? 1 : 0);
        EXPECT_EQ(report.passes, expected) << c.id;
        // The frame drawn is the plan FramePlanTest checks the whitepaper's rows on: the same
        // passes, each with the planned number of draws and the planned target size.
        const FramePlan plan = PlanFrame(c, s.renderer->Settings(), s.renderer->GetScene(), view);
        ASSERT_EQ(report.pass_names.size(), plan.passes.size()) << c.id;
        for (std::size_t i = 0; i < plan.passes.size(); ++i) {
            const PassPlan& pass = plan.passes[i];
            EXPECT_EQ(report.pass_names[i], PassName(pass.kind)) << c.id;
            const int draws = (pass.draw_sky ? 1 : 0) + static_cast<int>(pass.meshes.size()) +
                              (pass.draw_water ? 1 : 0);
            EXPECT_EQ(report.pass_draw_calls[i], draws) << c.id << " " << report.pass_names[i];
            EXPECT_EQ(report.pass_pixels[i], static_cast<long long>(pass.width) * pass.height)
                    << c.id << " " << report.pass_names[i];
        }
    }
}

TEST_F(WaterRendererGlTest, NoNanOrInfInAnyConfigurationAtAnyView) {
    test_support::SharedRenderer& s = Get();
    if (!s.float_renderer) {
        GTEST_SKIP() << "the context cannot render to RGBA32F";
    }
    const ConfigurationSet set = BuildDefaultConfigurations(*s.config, s.variants);
    for (const RenderConfiguration& c : set.configurations) {
        s.context->MakeCurrent();
        ASSERT_TRUE(s.float_renderer->Prepare(c).valid) << c.id;
        for (const CameraView& view : DefaultViews()) {
            const FrameReport report = s.float_renderer->RenderFrame(c, view);
            ASSERT_EQ(report.gl_error, "") << c.id;
            const std::vector<float> pixels = s.float_renderer->ReadFloatPixels();
            ASSERT_EQ(pixels.size(),
                      static_cast<std::size_t>(kRendererWidth * kRendererHeight * 4));
            const auto bad = std::find_if(pixels.begin(), pixels.end(),
                                          [](float v) { return !std::isfinite(v); });
            EXPECT_EQ(bad, pixels.end())
                    << c.id << " at " << view.name << ", pixel " << (bad - pixels.begin()) / 4;
        }
    }
}

TEST_F(WaterRendererGlTest, CullingDrawsOnlyWhatEachPassNeeds) {
    const RenderConfiguration culled = Configuration({"ENABLE_REFRACTION", "ENABLE_FOG"});
    PassOptions no_culling;
    no_culling.culling = false;
    const RenderConfiguration unculled =
            Configuration({"ENABLE_REFRACTION", "ENABLE_FOG"}, no_culling);
    test_support::SharedRenderer& s = Get();
    const CameraView view = *FindView(DefaultViews(), "three_quarter");
    s.context->MakeCurrent();
    ASSERT_TRUE(s.renderer->Prepare(culled).valid);
    const FrameReport with = s.renderer->RenderFrame(culled, view);
    ASSERT_TRUE(s.renderer->Prepare(unculled).valid);
    const FrameReport without = s.renderer->RenderFrame(unculled, view);
    EXPECT_LT(with.draw_calls, without.draw_calls);
    // Same passes either way; culling changes draws, not passes.
    EXPECT_EQ(with.pass_names, without.pass_names);
}

}  // namespace
}  // namespace tidepool::runner
