// CPU-side geometry of the water renderer: the mirrored camera, the oblique near plane, the
// "infinite" water polygon, screen-space texture coordinates and bump animation.
//
// Every function is a template on the scalar type and is instantiated for float and double, so a
// precision study can run the same code at both precisions and compare. Conventions follow
// shaders/INTERFACE.md: world space, y up, column-major GLM matrices, OpenGL clip space (clip z in
// [-w, w]). A plane is (n, d) with n·x + d = 0; its kept (positive) side is n·x + d >= 0.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace tidepool::runner {

/// Returns the matrix that reflects points about `plane` (the reflection pass multiplies the view
/// matrix by it); the normal is normalised inside. Fails by returning the identity when the
/// plane's normal has length zero. The result has determinant -1, so front faces flip.
template <typename T>
glm::mat<4, 4, T> MirrorMatrix(const glm::vec<4, T>& plane);

/// A projection whose near plane may have been replaced by a user clip plane.
template <typename T>
struct ObliqueProjection {
    glm::mat<4, 4, T> projection;  ///< the projection to use (unmodified when `applied` is false)
    bool applied = false;          ///< true when the near plane is the clip plane
};

/// Replaces the near plane of an OpenGL-style `projection` by `clip_plane_view_space` (view space,
/// kept side dot(plane, p) >= 0), after Lengyel, "Oblique View Frustum Depth Projection and
/// Clipping" (2005), including the far-plane rescale the whitepaper describes. Points on the plane
/// map to clip z = -w and the perspective row is untouched, so x, y and w are unchanged. Fails
/// (returns the projection unmodified with applied = false) when the camera is not strictly on the
/// clipped side (plane.w >= 0: the camera is on the kept side or on the plane) or when no part of
/// the kept side is inside the frustum; the caller must then clip with discard instead.
template <typename T>
ObliqueProjection<T> ObliqueNearPlane(const glm::mat<4, 4, T>& projection,
                                      const glm::vec<4, T>& clip_plane_view_space);

/// Returns the convex polygon where `plane` cuts the view frustum of `view_projection` (between
/// its near and far planes), in world space, ordered as a triangle fan counter-clockwise seen from
/// the plane's positive side. Fails by returning an empty vector when the plane misses the
/// frustum, only touches it along an edge or corner, has a zero normal, or `view_projection` is
/// singular.
template <typename T>
std::vector<glm::vec<3, T>> InfinitePlanePolygon(const glm::mat<4, 4, T>& view_projection,
                                                 const glm::vec<4, T>& plane);

/// Returns the [0,1]^2 screen coordinate of `world` (gl_FragCoord.xy / window size for that
/// point). Fails silently: a point behind the camera (clip w <= 0) gives a meaningless value.
template <typename T>
glm::vec<2, T> ProjectiveTexCoord(const glm::mat<4, 4, T>& view_projection,
                                  const glm::vec<3, T>& world);

/// Returns translation + velocity * dt, wrapped to its fractional part in [0, 1) when `wrap` is
/// true (negative values wrap upwards: -0.25 gives 0.75), which keeps the shader's mediump bump
/// coordinates accurate however long the animation runs. Never fails.
template <typename T>
glm::vec<2, T> AdvanceBumpTranslation(glm::vec<2, T> translation, glm::vec<2, T> velocity, T dt,
                                      bool wrap);

/// Transforms `plane` by the point transform `matrix` (multiplies by its inverse transpose), e.g.
/// a world plane by the view matrix into view space. Fails silently (non-finite values) when
/// `matrix` is singular.
template <typename T>
glm::vec<4, T> TransformPlane(const glm::mat<4, 4, T>& matrix, const glm::vec<4, T>& plane);

/// Returns the world → view matrix looking from `eye` at `target` with y up, exactly as
/// glm::lookAt(eye, target, y) does, except where that is undefined: when the view direction is
/// within kVerticalViewSine of the y axis (looking straight down or up), y is no usable up vector
/// (lookAt normalises a zero cross product into NaN), so -z (looking down) or +z (looking up)
/// serves instead. Fails by returning the identity when eye equals target.
template <typename T>
glm::mat<4, 4, T> LookAtWithFallbackUp(const glm::vec<3, T>& eye, const glm::vec<3, T>& target);

/// Sine of the angle to the y axis below which LookAtWithFallbackUp switches its up vector: the
/// cross product with y is then shorter than 1e-4, which float still normalises, but the view's
/// roll would swing with rounding; 1e-4 rad (0.006°) is far below any view the renderer sets.
inline constexpr double kVerticalViewSine = 1e-4;

/// Largest finite mediump (fp16) number, the top of the range a mediump uniform can hold.
inline constexpr float kMaxMediump = 65504.0F;

/// Returns a fog reciprocal (1 / maximum fog depth or distance) as the renderer uploads it to a
/// mediump uniform: clamped to [0, kMaxMediump], with NaN and negative values giving 0 (no fog).
/// A maximum depth of 0 would otherwise upload +Inf, and 0 × Inf at the water line is NaN; at
/// 1/65504 units no pixel can tell the clamped fog from the exact one. Never fails.
inline float MediumpFogReciprocal(float reciprocal) {
    return std::fmin(std::fmax(reciprocal, 0.0F), kMaxMediump);  // fmax drops a NaN
}

/// Bounds of MaxWaterDepth (world units) as water.fsh reads it: the depth optics divide the
/// depth by a view cosine floored at kMinExtinctionViewCos, so a path reaches 20 times the depth,
/// and 20 x 3000 = 60000 stays below fp16's 65504. The lower bound is the refraction clip
/// plane's sliver (0.5 units), below which no stored depth can be told apart.
inline constexpr float kMinMaxWaterDepth = 0.5F;
inline constexpr float kMaxMaxWaterDepth = 3000.0F;

/// Returns max_water_depth as the renderer uploads it (MaxWaterDepth, and its reciprocal for
/// model.fsh): clamped to [kMinMaxWaterDepth, kMaxMaxWaterDepth], NaN giving the upper bound.
/// Unclamped, a depth past 65504 is Inf in mediump and Inf x 0 at the water line is NaN. Never
/// fails.
inline float MediumpMaxWaterDepth(float depth) {
    return std::isnan(depth) ? kMaxMaxWaterDepth
                             : std::fmin(std::fmax(depth, kMinMaxWaterDepth), kMaxMaxWaterDepth);
}

/// The depth-based colour model of ../shared/seeds/003 as water.fsh evaluates it
/// (ENABLE_EXTINCTION). Units are world units (the default scene's are metres).
struct ExtinctionModel {
    glm::vec3 extinction{4.5F, 75.0F, 300.0F};         ///< depth at which red, green, blue are gone
    float visibility = 40.0F;                          ///< path length at which the water is opaque
    glm::vec3 surface_colour{0.0078F, 0.5176F, 0.7F};  ///< the water's own colour (the seed's)
    glm::vec3 depth_colour{0.0039F, 0.00196F, 0.145F};  ///< what deep water fades to (the seed's)
};

/// Floor under the cosine of the view angle in ExtinctionColour (and water.fsh): the path
/// through the water is at most 20 times the depth.
inline constexpr float kMinExtinctionViewCos = 0.05F;

/// The refracted colour `refraction` seen through water of vertical depth `depth` from a view
/// whose direction to the eye makes cosine `cos_view` with the up axis:
///   path = depth / max(cos_view, kMinExtinctionViewCos)
///   c = mix(refraction, surface_colour, clamp(path / visibility, 0, 1))
///   c = mix(c, depth_colour, clamp(depth / extinction, 0, 1))   (per channel)
/// the CPU reference for water.fsh's ENABLE_EXTINCTION. Never fails; a non-positive visibility
/// or extinction channel counts as opaque at any depth above 0.
glm::vec3 ExtinctionColour(glm::vec3 refraction, float depth, float cos_view,
                           const ExtinctionModel& model);

// Defined in WaterMath.cpp for float and double only.
extern template glm::mat<4, 4, float> MirrorMatrix(const glm::vec<4, float>&);
extern template ObliqueProjection<float> ObliqueNearPlane(const glm::mat<4, 4, float>&,
                                                          const glm::vec<4, float>&);
extern template std::vector<glm::vec<3, float>> InfinitePlanePolygon(const glm::mat<4, 4, float>&,
                                                                     const glm::vec<4, float>&);
extern template glm::vec<2, float> ProjectiveTexCoord(const glm::mat<4, 4, float>&,
                                                      const glm::vec<3, float>&);
extern template glm::vec<2, float> AdvanceBumpTranslation(glm::vec<2, float>, glm::vec<2, float>,
                                                          float, bool);
extern template glm::vec<4, float> TransformPlane(const glm::mat<4, 4, float>&,
                                                  const glm::vec<4, float>&);
extern template glm::mat<4, 4, float> LookAtWithFallbackUp(const glm::vec<3, float>&,
                                                           const glm::vec<3, float>&);
extern template glm::mat<4, 4, double> LookAtWithFallbackUp(const glm::vec<3, double>&,
                                                            const glm::vec<3, double>&);
extern template glm::mat<4, 4, double> MirrorMatrix(const glm::vec<4, double>&);
extern template ObliqueProjection<double> ObliqueNearPlane(const glm::mat<4, 4, double>&,
                                                           const glm::vec<4, double>&);
extern template std::vector<glm::vec<3, double>> InfinitePlanePolygon(const glm::mat<4, 4, double>&,
                                                                      const glm::vec<4, double>&);
extern template glm::vec<2, double> ProjectiveTexCoord(const glm::mat<4, 4, double>&,
                                                       const glm::vec<3, double>&);
extern template glm::vec<2, double> AdvanceBumpTranslation(glm::vec<2, double>, glm::vec<2, double>,
                                                           double, bool);
extern template glm::vec<4, double> TransformPlane(const glm::mat<4, 4, double>&,
                                                   const glm::vec<4, double>&);

}  // namespace tidepool::runner
