// Configuration ids, uniform-bool names, filters, file names and the "no GL" message.
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/RenderConfig.h"

#include <gtest/gtest.h>

namespace tidepool::runner {
namespace {

TEST(RenderConfigTest, DefaultPassesHaveNoSuffix) {
    EXPECT_EQ(ConfigurationId(MakeVariant("water", {"ENABLE_REFRACTION", "ENABLE_FOG"}), {}),
              "water:ENABLE_FOG,ENABLE_REFRACTION");
}

TEST(RenderConfigTest, NonDefaultPassesAppendSuffixesInFixedOrder) {
    PassOptions passes;
    passes.reflection_size = 128;
    passes.refraction_size = 64;
    passes.low_res_water = true;
    passes.clip = "discard";
    passes.depth_fog = false;
    passes.culling = false;
    EXPECT_EQ(ConfigurationId(MakeVariant("water", {"ENABLE_FOG"}), passes),
              "water:ENABLE_FOG@refl128@refr64@lowres@discard@nodepthfog@nocull");
}

TEST(RenderConfigTest, UniformBoolNamesFollowTheInterface) {
    const std::pair<const char*, const char*> cases[] = {
            {"ENABLE_DISTORTION", "bDistortion"},
            {"ENABLE_SCALE_DISTORTION", "bScaleDistortion"},
            {"ENABLE_REFRACTION", "bRefraction"},
            {"ENABLE_FRESNEL", "bFresnel"},
            {"FRESNEL_EXACT", "bFresnelExact"},
            {"NORMALISE_CUBEMAP", "bNormaliseCubemap"},
            {"ENABLE_WATER_COLOUR", "bWaterColour"},
            {"ENABLE_ALPHA_BLEND", "bAlphaBlend"},
            {"ENABLE_FOG", "bFog"}};
    for (const auto& [define, name] : cases) {
        EXPECT_EQ(UniformBoolName(define), name) << define;
    }
}

TEST(RenderConfigTest, PresetsJoinTheWaterVariantsAndDeduplicate) {
    VariantConfig config;
    Preset same;
    same.name = "fog";
    same.program = "water";
    same.defines = {"ENABLE_FOG"};
    Preset low_res = same;
    low_res.name = "fog_low_res";
    low_res.passes.low_res_water = true;
    Preset uniform;
    uniform.name = "uniform_fog";
    uniform.program = "water_uniform";
    uniform.runtime_features = {"ENABLE_FOG"};
    config.presets = {same, low_res, uniform};
    const std::vector<Variant> variants = {MakeVariant("water", {}),
                                           MakeVariant("water", {"ENABLE_FOG"}),
                                           MakeVariant("skybox", {"CLIP_DISCARD"})};
    const ConfigurationSet set = BuildDefaultConfigurations(config, variants);
    ASSERT_EQ(set.configurations.size(), 4U);
    EXPECT_EQ(set.configurations[0].id, "water:");
    EXPECT_EQ(set.configurations[1].id, "water:ENABLE_FOG");
    EXPECT_EQ(set.configurations[1].presets, std::vector<std::string>{"fog"});
    EXPECT_EQ(set.configurations[2].id, "water:ENABLE_FOG@lowres");
    EXPECT_EQ(set.configurations[3].id, "water_uniform:ENABLE_FOG");
    EXPECT_EQ(set.configurations[3].variant.Id(), "water_uniform:");
    EXPECT_TRUE(set.configurations[3].Has("ENABLE_FOG"));
    EXPECT_TRUE(set.configurations[3].UsesUniformBools());

    const ConfigurationSet fog_only =
            FilterConfigurations(set, ConfigurationFilter{{"*FOG@*"}, {"uniform_fog"}});
    ASSERT_EQ(fog_only.configurations.size(), 2U);
    EXPECT_EQ(fog_only.configurations[0].id, "water:ENABLE_FOG@lowres");
    EXPECT_EQ(fog_only.configurations[1].id, "water_uniform:ENABLE_FOG");

    const ConfigurationSet unknown = FilterConfigurations(set, ConfigurationFilter{{}, {"nope"}});
    ASSERT_EQ(unknown.diagnostics.size(), 1U);
    EXPECT_EQ(unknown.diagnostics[0].message,
              "unknown preset 'nope'; see the presets in "
              "variants.yaml");
}

TEST(RenderConfigTest, FileNamesAreSafeAndDistinct) {
    EXPECT_EQ(SanitiseFileName("water:ENABLE_FOG,ENABLE_REFRACTION@lowres"),
              "water__ENABLE_FOG+ENABLE_REFRACTION-lowres");
    EXPECT_EQ(SanitiseFileName("a/b c"), "a_b_c");
    EXPECT_NE(SanitiseFileName("water:"), SanitiseFileName("water_"));
}

TEST(RenderConfigTest, NoGlMessageNamesPackagesAndVariables) {
    const std::string message = DescribeMissingGl(
            {{BackendKind::kEgl, "eglInitialize failed"}, {BackendKind::kOsMesa, "no libOSMesa"}});
    for (const char* needle :
         {"egl: eglInitialize failed", "osmesa: no libOSMesa", "libegl-mesa0", "libgl1-mesa-dri",
          "libosmesa6", "EGL_PLATFORM", "LIBGL_ALWAYS_SOFTWARE", "MESA_LOADER_DRIVER_OVERRIDE"}) {
        EXPECT_NE(message.find(needle), std::string::npos) << needle << "\n" << message;
    }
}

TEST(RenderConfigTest, BackendNamesRoundTrip) {
    for (BackendKind kind : {BackendKind::kAuto, BackendKind::kEgl, BackendKind::kOsMesa}) {
        BackendKind parsed = BackendKind::kAuto;
        ASSERT_TRUE(ParseBackendKind(BackendName(kind), &parsed));
        EXPECT_EQ(parsed, kind);
    }
    BackendKind untouched = BackendKind::kEgl;
    EXPECT_FALSE(ParseBackendKind("vulkan", &untouched));
    EXPECT_EQ(untouched, BackendKind::kEgl);
}

}  // namespace
}  // namespace tidepool::runner
