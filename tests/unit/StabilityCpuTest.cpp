// The CPU side of the hard-case catalogue: every CPU sweep passes its stated bound, and the
// mediump precision study names the expressions it should.
#include "tidepool/lab/HardCases.h"
#include "tidepool/lab/PrecisionStudy.h"
#include "tidepool/lab/StabilityReport.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/WaterMath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace tidepool::runner {
namespace {

TEST(StabilityCatalogueTest, NamesAreUniqueAndEveryCaseIsDocumented) {
    std::set<std::string> names;
    for (const HardCase& c : HardCaseCatalogue()) {
        EXPECT_TRUE(names.insert(c.name).second) << c.name;
        EXPECT_FALSE(c.description.empty()) << c.name;
    }
    EXPECT_NE(FindHardCase(HardCaseCatalogue(), "camera_on_water"), nullptr);
    EXPECT_EQ(FindHardCase(HardCaseCatalogue(), "no_such_case"), nullptr);
}

class StabilityCpuCaseTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StabilityCpuCaseTest, SweepIsFiniteAndWithinItsBound) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const HardCase* hard_case = FindHardCase(catalogue, GetParam());
    ASSERT_NE(hard_case, nullptr);
    const StabilityCaseResult r = RunCpuHardCase(*hard_case);
    EXPECT_EQ(r.nan_count, 0) << r.note;
    EXPECT_EQ(r.inf_count, 0) << r.note;
    EXPECT_LE(r.max_error, r.bound) << r.note;
    EXPECT_TRUE(r.passed) << r.note;
}

INSTANTIATE_TEST_SUITE_P(AllCpuCases, StabilityCpuCaseTest,
                         ::testing::Values("cpu_mirror_matrix", "cpu_oblique_near_plane",
                                           "cpu_infinite_plane_polygon", "cpu_projective_tex_coord",
                                           "cpu_view_matrix_vertical",
                                           "cpu_bump_translation_long_run",
                                           "cpu_fresnel_unnormalised_normal",
                                           "cpu_distortion_eye_distance_zero",
                                           "cpu_fog_depth_extremes"));

TEST(StabilityCpuTest, EveryCpuCaseOfTheCatalogueIsCovered) {
    for (const HardCase& c : HardCaseCatalogue()) {
        if (c.kind == HardCaseKind::kCpu) {
            EXPECT_TRUE(RunCpuHardCase(c).passed) << c.name;
        }
    }
}

TEST(StabilityCpuTest, PlainViewMatrixIsNanStraightDownButFallbackIsNot) {
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

TEST(StabilityCpuTest, FallbackLookAtEqualsLookAtAwayFromVertical) {
    const CameraView view = DefaultViews().front();
    EXPECT_EQ(LookAtWithFallbackUp(view.eye, view.target), ViewMatrix(view));
}

TEST(StabilityCpuTest, FogReciprocalIsClampedToMediumpRange) {
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::infinity()), kMaxMediump);
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::quiet_NaN()), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(-1.0F), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(1.0F / 2000.0F), 1.0F / 2000.0F);
}

TEST(PrecisionStudyTest, RoundToHalfMatchesBinary16) {
    EXPECT_EQ(RoundToHalf(1.0), 1.0);
    EXPECT_EQ(RoundToHalf(65504.0), 65504.0);
    EXPECT_TRUE(std::isinf(RoundToHalf(65520.0)));
    EXPECT_EQ(RoundToHalf(65519.0), 65504.0);
    EXPECT_EQ(RoundToHalf(2049.0), 2048.0);  // spacing 2 above 2048, tie to even
    EXPECT_EQ(RoundToHalf(2051.0), 2052.0);
    EXPECT_EQ(RoundToHalf(1.0 + 1.0 / 2048.0), 1.0);  // half an ulp of 1, tie to even
    EXPECT_EQ(RoundToHalf(std::ldexp(1.0, -24)), std::ldexp(1.0, -24));  // smallest subnormal
    EXPECT_EQ(RoundToHalf(std::ldexp(1.0, -26)), 0.0);
    EXPECT_EQ((Half(256.0) * Half(256.0)).value, std::numeric_limits<double>::infinity());
}

const PrecisionRow& Row(const std::vector<PrecisionRow>& rows, const std::string& prefix) {
    for (const PrecisionRow& row : rows) {
        if (row.expression.rfind(prefix, 0) == 0) {
            return row;
        }
    }
    static const PrecisionRow missing = [] {
        PrecisionRow row;
        row.expression = "missing";
        return row;
    }();
    ADD_FAILURE() << "no expression starting with " << prefix;
    return missing;
}

TEST(PrecisionStudyTest, NamesTheExpressionsThatLosePrecisionAtMediump) {
    const std::vector<PrecisionRow> rows = RunPrecisionStudy();
    // Squared eye lengths overflow fp16 beyond 256 units: the pre-guard forms lose.
    EXPECT_TRUE(Row(rows, "length(EyeVector)").loses_precision);
    EXPECT_GT(Row(rows, "length(EyeVector)").non_finite_fp16, 0);
    EXPECT_TRUE(Row(rows, "E * inversesqrt").loses_precision);
    // Unwrapped bump translation after 1e6 s and far bump coordinates lose texels.
    EXPECT_TRUE(Row(rows, "BumpCoord with BumpTranslation unwrapped").loses_precision);
    EXPECT_TRUE(Row(rows, "BumpCoord = ").loses_precision);
    // Issue 16's numerics: the seed's glare power bands, extinction 0 is 0/0, MaxWaterDepth
    // beyond 65504 is Inf.
    EXPECT_TRUE(Row(rows, "pow(dot(m, s)").loses_precision);
    EXPECT_GT(Row(rows, "clamp(D / Extinction").non_finite_fp16, 0);
    EXPECT_GT(Row(rows, "a^2 * MaxWaterDepth").non_finite_fp16, 0);
    // The guarded forms the shaders use stay within the bound (1e-2 relative, see
    // PrecisionStudy.cpp), and in float every expression is within 1e-3 (a few float ulps of
    // the largest values swept, eye distances of 2000).
    for (const char* kept :
         {"eyeScale * sqrt", "(E / eyeScale)", "Schlick", "exact Fresnel", "bump * inversesqrt",
          "Fresnel chain", "bumpNormal.x", "clamp(eyeDistance", "exp2(-738.65",
          "clamp(D / max(Extinction", "a^2 * min(MaxWaterDepth"}) {
        const PrecisionRow& row = Row(rows, kept);
        EXPECT_FALSE(row.loses_precision) << kept << ": " << row.max_rel_error_fp16;
        EXPECT_EQ(row.non_finite_fp16, 0) << kept;
        EXPECT_LE(row.max_rel_error_fp16, row.bound_fp16) << kept;
    }
    for (const PrecisionRow& row : rows) {
        // Depth paths reach 2e6 units (60000 clamped), where a float ulp is 0.125 (0.004).
        if (row.expression.rfind("BumpCoord with", 0) != 0 &&
            row.expression.rfind("gl_FragCoord", 0) != 0 &&
            row.expression.rfind("a^2 * ", 0) != 0) {
            EXPECT_LE(row.max_abs_error_float, 1e-3) << row.expression;
        }
    }
}

}  // namespace
}  // namespace tidepool::runner
