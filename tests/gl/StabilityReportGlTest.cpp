// The GL side of the hard-case catalogue: every water variant rendered at every GL hard case
// into an RGBA32F target has no NaN, no Inf and no channel outside [0, 1]; the shader guards
// change the default views by less than an 8-bit step; the mediump fallback compiles.
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/lab/HardCases.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/Renderer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "GlTestEnvironment.h"

namespace tidepool::lab {
namespace {

// Tiny: 141 variants × ~20 cases must render in about a minute on llvmpipe.
constexpr int kWidth = 32;
constexpr int kHeight = 24;

struct Shared {
    GlContext* context = nullptr;
    const VariantConfig* config = nullptr;
    std::vector<RenderConfiguration> configurations;
    std::string error;
};

Shared& Get() {
    static Shared shared = [] {
        Shared s;
        test_support::GlTestEnvironment& environment = test_support::SharedGlEnvironment();
        if (!environment.error.empty()) {
            s.error = environment.error;
            return s;
        }
        s.context = environment.context.get();
        s.config = &*environment.config;
        s.configurations = WaterVariantConfigurations(
                ExpandVariants(*s.config, ExpansionOptions{s.config->max_variants}).variants);
        if (!s.context->Environment().float_render_target) {
            s.error = "the context cannot render to RGBA32F";
        }
        return s;
    }();
    return shared;
}

class StabilityReportGlCaseTest : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        if (!Get().error.empty()) {
            GTEST_SKIP() << Get().error;
        }
    }
};

std::vector<std::string> GlCaseNames() {
    std::vector<std::string> names;
    for (const HardCase& c : HardCaseCatalogue()) {
        if (c.kind == HardCaseKind::kGl) {
            names.push_back(c.name);
        }
    }
    return names;
}

TEST_P(StabilityReportGlCaseTest, EveryWaterVariantIsFiniteAndInRange) {
    Shared& s = Get();
    // The default water matrix: the whitepaper's 54, the depth optics and the two other
    // reflection techniques (tests/unit/DefaultMatrixTest.cpp).
    constexpr std::size_t kWaterVariants = 54 + 15 + 2 * 36;
    ASSERT_EQ(s.configurations.size(), kWaterVariants);
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const HardCase* hard_case = FindHardCase(catalogue, GetParam());
    ASSERT_NE(hard_case, nullptr);
    std::string error;
    std::vector<double> shares_done;
    const std::vector<StabilityCaseResult> results =
            RunGlHardCases(*s.context, *s.config, s.configurations, {*hard_case},
                           GlStabilityOptions{kWidth, kHeight,
                                              [&](double share) { shares_done.push_back(share); }},
                           &error);
    ASSERT_EQ(error, "");
    EXPECT_EQ(shares_done, std::vector<double>{1.0});  // the one case, all of the progress
    ASSERT_EQ(results.size(), 1U);
    const StabilityCaseResult& r = results.front();
    EXPECT_EQ(r.variants_checked, static_cast<int>(kWaterVariants));
    EXPECT_EQ(r.nan_count, 0) << r.note;
    EXPECT_EQ(r.inf_count, 0) << r.note;
    EXPECT_LE(r.max_error, r.bound) << r.note;
    EXPECT_TRUE(r.passed) << r.note;
}

INSTANTIATE_TEST_SUITE_P(AllGlCases, StabilityReportGlCaseTest, ::testing::ValuesIn(GlCaseNames()),
                         [](const auto& param_info) { return param_info.param; });

class StabilityReportGlTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!Get().error.empty()) {
            GTEST_SKIP() << Get().error;
        }
    }
};

TEST_F(StabilityReportGlTest, GuardsChangeTheDefaultViewsByLessThanTheirTolerance) {
    Shared& s = Get();
    std::string error;
    const std::vector<GuardResult> guards =
            MeasureGuards(*s.context, *s.config, GlStabilityOptions{kWidth, kHeight, {}}, &error);
    ASSERT_EQ(error, "");
    ASSERT_EQ(guards.size(), 4U);
    for (const GuardResult& g : guards) {
        EXPECT_LE(g.max_channel_diff_normal_views, g.tolerance) << g.guard;
        EXPECT_TRUE(g.passed) << g.guard;
    }
}

TEST_F(StabilityReportGlTest, MediumpFallbackOfEveryShaderCompilesAndRendersFinite) {
    Shared& s = Get();
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.float_target = true;
    std::string error;
    auto renderer = WaterRenderer::Create(*s.context, *s.config, settings, &error);
    ASSERT_NE(renderer, nullptr) << error;
    for (std::vector<std::string> defines :
         {std::vector<std::string>{"ENABLE_DISTORTION", "ENABLE_FOG", "ENABLE_FRESNEL",
                                   "ENABLE_REFRACTION", "ENABLE_SCALE_DISTORTION",
                                   "TP_FORCE_MEDIUMP"},
          std::vector<std::string>{"ENABLE_DISTORTION", "ENABLE_FRESNEL", "ENABLE_REFRACTION",
                                   "FRESNEL_EXACT", "TP_FORCE_MEDIUMP"}}) {
        RenderConfiguration c;
        c.variant = MakeVariant("water", defines);
        c.effects = c.variant.defines;
        c.id = ConfigurationId(c.variant, c.passes);
        const DriverVerdict verdict = renderer->Prepare(c);
        ASSERT_TRUE(verdict.valid) << verdict.fragment_log << verdict.link_log;
        for (const CameraView& view : DefaultViews()) {
            ASSERT_EQ(renderer->RenderFrame(c, view).gl_error, "");
            for (const float v : renderer->ReadFloatPixels()) {
                ASSERT_TRUE(std::isfinite(v)) << c.id << " at " << view.name;
            }
        }
    }
}

}  // namespace
}  // namespace tidepool::lab
