// Water geometry against hand-derived values, at float and double precision; the CPU reference
// of the extinction formula; the guards the hard cases needed (look-at straight down, the fog
// reciprocal in mediump range).
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/WaterMath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace tidepool::runner {
namespace {

template <typename T>
class WaterMathTest : public ::testing::Test {
protected:
    // float: the frustum tests unproject corners 1000 units away through an inverse matrix whose
    // depth row is ill-conditioned by far / near = 1000, costing about 1000 ulps (1e-4); 1e-3
    // leaves room. double: the same loss is around 1e-13.
    static constexpr T kTolerance = sizeof(T) == sizeof(float) ? T(1e-3) : T(1e-9);
};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(WaterMathTest, Precisions);

template <typename T>
glm::vec<3, T> Apply(const glm::mat<4, 4, T>& m, const glm::vec<3, T>& p) {
    const glm::vec<4, T> q = m * glm::vec<4, T>(p, T(1));
    return glm::vec<3, T>(q) / q.w;
}

template <typename T>
void ExpectNear(const glm::vec<3, T>& actual, const glm::vec<3, T>& expected, T tolerance) {
    for (glm::length_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
    }
}

// ----- MirrorMatrix ---------------------------------------------------------------------------

TYPED_TEST(WaterMathTest, MirrorAboutWaterPlaneNegatesY) {
    using T = TypeParam;
    const auto mirror = MirrorMatrix(glm::vec<4, T>(0, 1, 0, 0));
    ExpectNear(Apply(mirror, glm::vec<3, T>(1, 2, 3)), glm::vec<3, T>(1, -2, 3), this->kTolerance);
}

TYPED_TEST(WaterMathTest, MirrorAboutRaisedPlaneReflectsAcrossIt) {
    using T = TypeParam;
    // y = 5 is (0, 1, 0, -5); a point 3 below it lands 3 above it. The normal is normalised
    // inside, so a scaled plane equation gives the same mirror.
    for (const glm::vec<4, T>& plane :
         {glm::vec<4, T>(0, 1, 0, -5), glm::vec<4, T>(0, 2, 0, -10)}) {
        const auto mirror = MirrorMatrix(plane);
        ExpectNear(Apply(mirror, glm::vec<3, T>(1, 2, 3)), glm::vec<3, T>(1, 8, 3),
                   this->kTolerance);
    }
}

TYPED_TEST(WaterMathTest, MirrorTwiceIsIdentity) {
    using T = TypeParam;
    const auto mirror = MirrorMatrix(glm::vec<4, T>(1, 2, 3, 4));
    const glm::mat<4, 4, T> twice = mirror * mirror;
    for (glm::length_t c = 0; c < 4; ++c) {
        for (glm::length_t r = 0; r < 4; ++r) {
            EXPECT_NEAR(twice[c][r], c == r ? T(1) : T(0), this->kTolerance);
        }
    }
}

TYPED_TEST(WaterMathTest, MirrorFlipsHandednessSoFrontFacesFlip) {
    using T = TypeParam;
    EXPECT_NEAR(glm::determinant(MirrorMatrix(glm::vec<4, T>(1, 2, 3, 4))), T(-1),
                this->kTolerance);
}

TYPED_TEST(WaterMathTest, MirrorOfZeroNormalIsIdentity) {
    using T = TypeParam;
    const glm::mat<4, 4, T> identity(T(1));
    EXPECT_EQ(MirrorMatrix(glm::vec<4, T>(0, 0, 0, 3)), identity);
}

// ----- ObliqueNearPlane -----------------------------------------------------------------------

template <typename T>
glm::mat<4, 4, T> TestProjection() {
    return glm::perspective(glm::radians(T(60)), T(4) / T(3), T(1), T(100));
}

// View space, kept side up and away: 0.3 y - z - 5 >= 0, i.e. z <= 0.3 y - 5. The camera at the
// origin gives -5 < 0, so it is on the clipped side, as the reflection pass needs.
template <typename T>
glm::vec<4, T> TiltedClipPlane() {
    return {T(0), T(0.3), T(-1), T(-5)};
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneMapsPlanePointsToNearClipDepth) {
    using T = TypeParam;
    const auto oblique = ObliqueNearPlane(TestProjection<T>(), TiltedClipPlane<T>());
    ASSERT_TRUE(oblique.applied);
    for (const T x : {T(-2), T(0), T(1.5)}) {
        for (const T y : {T(-1), T(0), T(2)}) {
            const glm::vec<4, T> clip =
                    oblique.projection * glm::vec<4, T>(x, y, T(0.3) * y - T(5), T(1));
            EXPECT_NEAR(clip.z / clip.w, T(-1), this->kTolerance) << x << ", " << y;
        }
    }
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneKeepsDepthOrderInFront) {
    using T = TypeParam;
    const auto oblique = ObliqueNearPlane(TestProjection<T>(), TiltedClipPlane<T>());
    ASSERT_TRUE(oblique.applied);
    T previous = T(-1);
    // Along a view ray from just beyond the plane (z = -5.1 here) outwards.
    for (const T distance : {T(5.2), T(6), T(10), T(20), T(40)}) {
        const glm::vec<3, T> p = glm::vec<3, T>(T(0.1), T(0.05), T(-1)) * distance;
        const glm::vec<4, T> clip = oblique.projection * glm::vec<4, T>(p, T(1));
        EXPECT_GT(clip.z / clip.w, previous) << distance;
        previous = clip.z / clip.w;
    }
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneKeepsScreenPositionAndW) {
    using T = TypeParam;
    const auto original = TestProjection<T>();
    const auto oblique = ObliqueNearPlane(original, TiltedClipPlane<T>());
    const glm::vec<4, T> p(T(1), T(-2), T(-30), T(1));
    const glm::vec<4, T> a = original * p;
    const glm::vec<4, T> b = oblique.projection * p;
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.w, b.w);
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneClipsPointsOnTheClippedSide) {
    using T = TypeParam;
    const auto oblique = ObliqueNearPlane(TestProjection<T>(), TiltedClipPlane<T>());
    // z = -3 is in front of the camera but before the plane (0.3 * 0 - 5 = -5).
    const glm::vec<4, T> clip = oblique.projection * glm::vec<4, T>(0, 0, -3, 1);
    EXPECT_GT(clip.w, T(0));
    EXPECT_LT(clip.z, -clip.w);
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneRejectsPlaneFacingTheCamera) {
    using T = TypeParam;
    const auto projection = TestProjection<T>();
    // Kept side z >= -5 contains the camera; a plane through the camera is rejected as well.
    for (const glm::vec<4, T>& plane : {glm::vec<4, T>(0, 0, 1, 5), glm::vec<4, T>(0, 1, 0, 0)}) {
        const auto oblique = ObliqueNearPlane(projection, plane);
        EXPECT_FALSE(oblique.applied);
        EXPECT_EQ(oblique.projection, projection);
    }
}

TYPED_TEST(WaterMathTest, ObliqueNearPlaneClipsMirroredSceneAtTheWaterPlane) {
    using T = TypeParam;
    const glm::vec<4, T> water(0, 1, 0, 0);  // keep what is above the water
    const auto view =
            glm::lookAt(glm::vec<3, T>(0, 5, 10), glm::vec<3, T>(0, 0, 0), glm::vec<3, T>(0, 1, 0));
    const glm::mat<4, 4, T> mirrored_view = view * MirrorMatrix(water);
    const auto oblique =
            ObliqueNearPlane(TestProjection<T>(), TransformPlane(mirrored_view, water));
    ASSERT_TRUE(oblique.applied);
    const glm::mat<4, 4, T> mvp = oblique.projection * mirrored_view;
    const auto ndc_z = [&](T x, T y, T z) {
        const glm::vec<4, T> clip = mvp * glm::vec<4, T>(x, y, z, T(1));
        return clip.z / clip.w;
    };
    EXPECT_NEAR(ndc_z(3, 0, -2), T(-1), this->kTolerance);
    EXPECT_GT(ndc_z(0, 2, 0), T(-1));
    EXPECT_LT(ndc_z(0, -1, 0), T(-1));
}

// ----- InfinitePlanePolygon -------------------------------------------------------------------

template <typename T>
glm::mat<4, 4, T> LookFrom(const glm::vec<3, T>& eye, const glm::vec<3, T>& target,
                           const glm::vec<3, T>& up = {0, 1, 0}) {
    return glm::perspective(glm::radians(T(60)), T(4) / T(3), T(1), T(1000)) *
           glm::lookAt(eye, target, up);
}

// Counter-clockwise seen from +y: every turn of the polygon bends left.
template <typename T>
void ExpectCounterClockwiseFromAbove(const std::vector<glm::vec<3, T>>& polygon) {
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const auto& a = polygon[i];
        const auto& b = polygon[(i + 1) % polygon.size()];
        const auto& c = polygon[(i + 2) % polygon.size()];
        EXPECT_GT(glm::cross(b - a, c - b).y, T(0)) << "turn at vertex " << (i + 1);
    }
}

TYPED_TEST(WaterMathTest, InfinitePlanePolygonTowardsHorizonLiesOnPlaneInsideFrustum) {
    using T = TypeParam;
    const auto view_projection = LookFrom<T>({0, 10, 0}, {0, 10, -1});
    const auto polygon = InfinitePlanePolygon(view_projection, glm::vec<4, T>(0, 1, 0, 0));
    // The lower half of the frustum cuts the plane from the bottom screen edge to the far plane.
    ASSERT_EQ(polygon.size(), 4U);
    for (const auto& p : polygon) {
        // An edge intersection is on the plane up to one rounding of coordinates of about 600.
        EXPECT_NEAR(p.y, T(0), this->kTolerance);
        const glm::vec<4, T> clip = view_projection * glm::vec<4, T>(p, T(1));
        for (glm::length_t i = 0; i < 3; ++i) {
            EXPECT_LE(std::abs(clip[i]), clip.w * (T(1) + this->kTolerance)) << "axis " << i;
        }
    }
    ExpectCounterClockwiseFromAbove(polygon);
}

TYPED_TEST(WaterMathTest, InfinitePlanePolygonLookingStraightDownIsTheFootprintSquare) {
    using T = TypeParam;
    // 90 degrees, square aspect, 10 above the plane: the footprint is the square |x|, |z| <= 10.
    const auto view_projection = glm::perspective(glm::radians(T(90)), T(1), T(1), T(100)) *
                                 glm::lookAt(glm::vec<3, T>(0, 10, 0), glm::vec<3, T>(0, 0, 0),
                                             glm::vec<3, T>(0, 0, -1));
    const auto polygon = InfinitePlanePolygon(view_projection, glm::vec<4, T>(0, 1, 0, 0));
    ASSERT_EQ(polygon.size(), 4U);
    for (const auto& p : polygon) {
        EXPECT_NEAR(std::abs(p.x), T(10), this->kTolerance * T(10));
        EXPECT_NEAR(p.y, T(0), this->kTolerance);
        EXPECT_NEAR(std::abs(p.z), T(10), this->kTolerance * T(10));
    }
    ExpectCounterClockwiseFromAbove(polygon);
}

TYPED_TEST(WaterMathTest, InfinitePlanePolygonLookingUpIsEmpty) {
    using T = TypeParam;
    // 63 degrees up with a 60-degree field of view: the lowest ray still climbs 33 degrees.
    const auto view_projection = LookFrom<T>({0, 10, 0}, {0, 20, -5});
    EXPECT_TRUE(InfinitePlanePolygon(view_projection, glm::vec<4, T>(0, 1, 0, 0)).empty());
}

TYPED_TEST(WaterMathTest, InfinitePlanePolygonBeyondFarPlaneIsEmpty) {
    using T = TypeParam;
    const auto view_projection = LookFrom<T>({0, 10, 0}, {0, 10, -1});
    EXPECT_TRUE(InfinitePlanePolygon(view_projection, glm::vec<4, T>(0, 0, 1, 5000)).empty());
    EXPECT_TRUE(InfinitePlanePolygon(view_projection, glm::vec<4, T>(0, 0, 0, 1)).empty());
}

// ----- ProjectiveTexCoord ---------------------------------------------------------------------

TYPED_TEST(WaterMathTest, ProjectiveTexCoordOfScreenCentreIsHalf) {
    using T = TypeParam;
    const glm::vec<3, T> target(1, 0, -2);
    const auto view_projection = LookFrom<T>({3, 5, 10}, target);
    const glm::vec<2, T> st = ProjectiveTexCoord(view_projection, target);
    EXPECT_NEAR(st.x, T(0.5), this->kTolerance);
    EXPECT_NEAR(st.y, T(0.5), this->kTolerance);
}

TYPED_TEST(WaterMathTest, ProjectiveTexCoordAtFrustumEdgesIsZeroOrOne) {
    using T = TypeParam;
    // 90 degrees, square, identity view: x = -z is the right edge, y = z / 2 a quarter up.
    const auto projection = glm::perspective(glm::radians(T(90)), T(1), T(1), T(100));
    const glm::vec<2, T> right = ProjectiveTexCoord(projection, glm::vec<3, T>(5, 0, -5));
    const glm::vec<2, T> low = ProjectiveTexCoord(projection, glm::vec<3, T>(0, -2.5, -5));
    EXPECT_NEAR(right.x, T(1), this->kTolerance);
    EXPECT_NEAR(right.y, T(0.5), this->kTolerance);
    EXPECT_NEAR(low.x, T(0.5), this->kTolerance);
    EXPECT_NEAR(low.y, T(0.25), this->kTolerance);
}

// ----- AdvanceBumpTranslation -----------------------------------------------------------------

TYPED_TEST(WaterMathTest, AdvanceBumpTranslationWrapsToFractionalPart) {
    using T = TypeParam;
    const auto t = AdvanceBumpTranslation<T>({T(0.9), T(0.5)}, {T(0.15), T(0.05)}, T(2), true);
    EXPECT_NEAR(t.x, T(0.2), this->kTolerance);
    EXPECT_NEAR(t.y, T(0.6), this->kTolerance);
}

TYPED_TEST(WaterMathTest, AdvanceBumpTranslationWrapsNegativeValuesUpwards) {
    using T = TypeParam;
    const auto t = AdvanceBumpTranslation<T>({T(0.1), T(-2.3)}, {T(-0.35), T(0)}, T(1), true);
    // fmod would keep the sign (-0.25); the shader needs the fraction in [0, 1): x - floor(x).
    EXPECT_NEAR(t.x, T(0.75), this->kTolerance);
    EXPECT_NEAR(t.y, T(0.7), this->kTolerance);
    EXPECT_NEAR(t.x, T(-0.25) - std::floor(T(-0.25)), this->kTolerance);
}

TYPED_TEST(WaterMathTest, AdvanceBumpTranslationNeverReachesOne) {
    using T = TypeParam;
    // -1e-20 - floor(-1e-20) is 1 - 1e-20, which rounds to exactly 1 in both precisions.
    const auto t = AdvanceBumpTranslation<T>({T(0), T(0)}, {T(-1e-20), T(-1)}, T(1), true);
    EXPECT_GE(t.x, T(0));
    EXPECT_LT(t.x, T(1));
    EXPECT_EQ(t.y, T(0));
}

TYPED_TEST(WaterMathTest, AdvanceBumpTranslationWithoutWrapKeepsTheSum) {
    using T = TypeParam;
    const auto t = AdvanceBumpTranslation<T>({T(0.9), T(-0.5)}, {T(0.5), T(-1)}, T(2), false);
    EXPECT_NEAR(t.x, T(1.9), this->kTolerance);
    EXPECT_NEAR(t.y, T(-2.5), this->kTolerance);
}

// ----- TransformPlane -------------------------------------------------------------------------

TYPED_TEST(WaterMathTest, TransformPlaneFollowsTranslation) {
    using T = TypeParam;
    const auto up5 = glm::translate(glm::mat<4, 4, T>(T(1)), glm::vec<3, T>(0, 5, 0));
    const glm::vec<4, T> plane = TransformPlane(up5, glm::vec<4, T>(0, 1, 0, 0));
    const glm::vec<4, T> expected(0, 1, 0, -5);
    for (glm::length_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(plane[i], expected[i], this->kTolerance);
    }
}

TYPED_TEST(WaterMathTest, TransformPlaneKeepsSignedDistanceOfTransformedPoints) {
    using T = TypeParam;
    // Rigid motion plus uniform scale 2: signed distances scale by 2 in the plane equation's
    // units, but dot(plane', M p) = dot(plane, p) holds for any invertible M.
    glm::mat<4, 4, T> m = glm::translate(glm::mat<4, 4, T>(T(1)), glm::vec<3, T>(3, -1, 7));
    m = glm::rotate(m, T(0.7), glm::normalize(glm::vec<3, T>(1, 2, 3)));
    m = glm::scale(m, glm::vec<3, T>(2));
    const glm::vec<4, T> plane(1, -2, 0.5, 4);
    const glm::vec<4, T> moved = TransformPlane(m, plane);
    for (const glm::vec<3, T>& p :
         {glm::vec<3, T>(0, 0, 0), glm::vec<3, T>(1, 2, 3), glm::vec<3, T>(-4, 0.5, 9)}) {
        const glm::vec<4, T> point(p, T(1));
        EXPECT_NEAR(glm::dot(moved, m * point), glm::dot(plane, point), this->kTolerance * T(10));
    }
}

TEST(WaterMathExtinctionTest, MatchesTheFormulaAtSampledDepths) {
    const ExtinctionModel model;
    const glm::vec3 floor(0.8F, 0.7F, 0.5F);
    // Depth 0: nothing changes.
    const glm::vec3 at_surface = ExtinctionColour(floor, 0.0F, 1.0F, model);
    EXPECT_FLOAT_EQ(at_surface.r, floor.r);
    EXPECT_FLOAT_EQ(at_surface.b, floor.b);
    // Looking straight down at depth 2: path 2 = 5% of visibility 40, then red 2/4.5 extinct,
    // green 2/75, blue 2/300, each towards the deep colour.
    const glm::vec3 seen = ExtinctionColour(floor, 2.0F, 1.0F, model);
    const glm::vec3 tinted = glm::mix(floor, model.surface_colour, 2.0F / model.visibility);
    EXPECT_NEAR(seen.r, glm::mix(tinted.r, model.depth_colour.r, 2.0F / 4.5F), 1e-6);
    EXPECT_NEAR(seen.g, glm::mix(tinted.g, model.depth_colour.g, 2.0F / 75.0F), 1e-6);
    EXPECT_NEAR(seen.b, glm::mix(tinted.b, model.depth_colour.b, 2.0F / 300.0F), 1e-6);
    // Red is gone at 4.5, blue only at 300.
    const glm::vec3 deep = ExtinctionColour(floor, 4.5F, 1.0F, model);
    EXPECT_FLOAT_EQ(deep.r, model.depth_colour.r);
    EXPECT_GT(deep.b, model.depth_colour.b);
    // A grazing view lengthens the path (at most 20x): the surface colour takes over sooner;
    // at depth 2 the grazing path is 40, the whole visibility.
    const glm::vec3 grazing = ExtinctionColour(floor, 2.0F, 0.0F, model);
    const glm::vec3 steep = ExtinctionColour(floor, 2.0F, 1.0F, model);
    EXPECT_LT(glm::length(grazing - glm::mix(model.surface_colour, model.depth_colour,
                                             glm::vec3(2.0F / 4.5F, 2.0F / 75, 2.0F / 300))),
              glm::length(steep - glm::mix(model.surface_colour, model.depth_colour,
                                           glm::vec3(2.0F / 4.5F, 2.0F / 75, 2.0F / 300))));
}

TEST(WaterMathGuardTest, PlainViewMatrixIsNanStraightDownButFallbackIsNot) {
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

TEST(WaterMathGuardTest, FallbackLookAtEqualsLookAtAwayFromVertical) {
    const CameraView view = DefaultViews().front();
    EXPECT_EQ(LookAtWithFallbackUp(view.eye, view.target), ViewMatrix(view));
}

TEST(WaterMathGuardTest, FogReciprocalIsClampedToMediumpRange) {
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::infinity()), kMaxMediump);
    EXPECT_EQ(MediumpFogReciprocal(std::numeric_limits<float>::quiet_NaN()), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(-1.0F), 0.0F);
    EXPECT_EQ(MediumpFogReciprocal(1.0F / 2000.0F), 1.0F / 2000.0F);
}

}  // namespace
}  // namespace tidepool::runner
