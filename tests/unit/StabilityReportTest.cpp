// The stability catalogue's CPU side (lab/StabilityReport.h): every CPU sweep of the hard-case
// catalogue passes its stated bound, and the water variants become configurations. The GL side
// is tested in tests/gl/StabilityReportGlTest.cpp.
#include "tidepool/VariantExpander.h"
#include "tidepool/lab/HardCases.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/runner/RenderConfig.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace tidepool::lab {
namespace {

class StabilityReportCpuCaseTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityReportCpuCaseTest, SweepIsFiniteAndWithinItsBound) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const HardCase* hard_case = FindHardCase(catalogue, GetParam());
    ASSERT_NE(hard_case, nullptr);
    const StabilityCaseResult r = RunCpuHardCase(*hard_case);
    EXPECT_EQ(r.nan_count, 0) << r.note;
    EXPECT_EQ(r.inf_count, 0) << r.note;
    EXPECT_LE(r.max_error, r.bound) << r.note;
    EXPECT_TRUE(r.passed) << r.note;
}

INSTANTIATE_TEST_SUITE_P(AllCpuCases, StabilityReportCpuCaseTest,
                         ::testing::Values("cpu_mirror_matrix", "cpu_oblique_near_plane",
                                           "cpu_infinite_plane_polygon", "cpu_projective_tex_coord",
                                           "cpu_view_matrix_vertical",
                                           "cpu_bump_translation_long_run",
                                           "cpu_fresnel_unnormalised_normal",
                                           "cpu_distortion_eye_distance_zero",
                                           "cpu_fog_depth_extremes"));

TEST(StabilityReportTest, EveryCpuCaseOfTheCatalogueIsCovered) {
    for (const HardCase& c : HardCaseCatalogue()) {
        if (c.kind == HardCaseKind::kCpu) {
            EXPECT_TRUE(RunCpuHardCase(c).passed) << c.name;
        }
    }
}

TEST(StabilityReportTest, AGlCaseGivenToTheCpuSweepFailsWithANote) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const auto gl = std::find_if(catalogue.begin(), catalogue.end(),
                                 [](const HardCase& c) { return c.kind == HardCaseKind::kGl; });
    ASSERT_NE(gl, catalogue.end());
    const StabilityCaseResult r = RunCpuHardCase(*gl);
    EXPECT_FALSE(r.passed);
    EXPECT_FALSE(r.note.empty());
}

TEST(StabilityReportTest, OnlyWaterVariantsBecomeConfigurationsWithDefaultPasses) {
    const std::vector<Variant> variants = {MakeVariant("water", {"ENABLE_FOG"}),
                                           MakeVariant("sky", {}), MakeVariant("water", {})};
    const std::vector<RenderConfiguration> configs = WaterVariantConfigurations(variants);
    ASSERT_EQ(configs.size(), 2U);
    EXPECT_EQ(configs[0].variant.Id(), "water:ENABLE_FOG");
    EXPECT_EQ(configs[0].effects, std::vector<std::string>{"ENABLE_FOG"});
    EXPECT_EQ(configs[0].id, ConfigurationId(configs[0].variant, PassOptions{}));
    EXPECT_EQ(configs[1].variant.Id(), "water:");
    EXPECT_TRUE(WaterVariantConfigurations({}).empty());
}

}  // namespace
}  // namespace tidepool::lab
