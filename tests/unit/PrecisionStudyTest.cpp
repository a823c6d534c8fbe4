// The mediump precision study (lab/PrecisionStudy.h): binary16 rounding, and the expressions
// the study names as losing precision at mediump.
#include "tidepool/lab/PrecisionStudy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace tidepool::lab {
namespace {

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
}  // namespace tidepool::lab
