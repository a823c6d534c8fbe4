// The CPU side of the hard-case catalogue (lab/HardCases.h): every CPU sweep passes its
// stated bound.
#include "tidepool/lab/HardCases.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/WaterMath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace tidepool::lab {
namespace {

TEST(HardCasesTest, NamesAreUniqueAndEveryCaseIsDocumented) {
    std::set<std::string> names;
    for (const HardCase& c : HardCaseCatalogue()) {
        EXPECT_TRUE(names.insert(c.name).second) << c.name;
        EXPECT_FALSE(c.description.empty()) << c.name;
    }
    EXPECT_NE(FindHardCase(HardCaseCatalogue(), "camera_on_water"), nullptr);
    EXPECT_EQ(FindHardCase(HardCaseCatalogue(), "no_such_case"), nullptr);
}

class HardCasesCpuCaseTest : public ::testing::TestWithParam<std::string> {};

TEST_P(HardCasesCpuCaseTest, SweepIsFiniteAndWithinItsBound) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const HardCase* hard_case = FindHardCase(catalogue, GetParam());
    ASSERT_NE(hard_case, nullptr);
    const StabilityCaseResult r = RunCpuHardCase(*hard_case);
    EXPECT_EQ(r.nan_count, 0) << r.note;
    EXPECT_EQ(r.inf_count, 0) << r.note;
    EXPECT_LE(r.max_error, r.bound) << r.note;
    EXPECT_TRUE(r.passed) << r.note;
}

INSTANTIATE_TEST_SUITE_P(AllCpuCases, HardCasesCpuCaseTest,
                         ::testing::Values("cpu_mirror_matrix", "cpu_oblique_near_plane",
                                           "cpu_infinite_plane_polygon", "cpu_projective_tex_coord",
                                           "cpu_view_matrix_vertical",
                                           "cpu_bump_translation_long_run",
                                           "cpu_fresnel_unnormalised_normal",
                                           "cpu_distortion_eye_distance_zero",
                                           "cpu_fog_depth_extremes"));

TEST(HardCasesTest, EveryCpuCaseOfTheCatalogueIsCovered) {
    for (const HardCase& c : HardCaseCatalogue()) {
        if (c.kind == HardCaseKind::kCpu) {
            EXPECT_TRUE(RunCpuHardCase(c).passed) << c.name;
        }
    }
}

TEST(HardCasesTest, PlainViewMatrixIsNanStraightDownButFallbackIsNot) {
    const CameraView down{"down", {20.0F, 60.0F, 20.0F}, {20.0F, 0.0F, 20.0F}, 0.8F, 1.0F, 2000.0F};
    EXPECT_FALSE(std::isfinite(ViewMatrix(down)[0][0]));  // why the fallback exists
    const glm::mat4 view = LookAtWithFallbackUp(down.eye, down.target);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_TRUE(std::isfinite(view[c][r]));
        }
    }
    // The eye maps to the origin and the target straight ahead (-z).
    const glm::vec4 target = view * glm::vec4(down.target, 1.0F);
    EXPECT_NEAR(target.x, 0.0F, 1e-4F);
    EXPECT_NEAR(target.y, 0.0F, 1e-4F);
    EXPECT_NEAR(target.z, -60.0F, 1e-3F);
}

TEST(HardCasesTest, FallbackLookAtEqualsLookAtAwayFromVertical) {
    const CameraView view = DefaultViews().front();
    EXPECT_EQ(LookAtWithFallbackUp(view.eye, view.target), ViewMatrix(view));
}

TEST(HardCasesTest, FogReciprocalIsClampedToMediumpRange) {
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::infinity()), kMaxMediump);
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::quiet_NaN()), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(-1.0F), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(1.0F / 2000.0F), 1.0F / 2000.0F);
}

}  // namespace
}  // namespace tidepool::lab
