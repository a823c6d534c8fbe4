#include "tidepool/runner/WaterMath.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/ext/matrix_transform.hpp>

namespace tidepool::runner {
namespace {

// Relative tolerance for "this frustum corner lies on the plane" and "these two polygon vertices
// are the same point": 64 ulps of the frustum's size absorbs the rounding of unprojecting the
// corners through an inverse matrix (a few dozen operations) without merging distinct vertices.
template <typename T>
constexpr T kRelativeTolerance = T(64) * std::numeric_limits<T>::epsilon();

// Sign with sgn(0) = 0, as in Lengyel's code: a plane parallel to an axis picks the middle corner.
template <typename T>
T Sign(T value) {
    return value > T(0) ? T(1) : (value < T(0) ? T(-1) : T(0));
}

}  // namespace

template <typename T>
glm::mat<4, 4, T> MirrorMatrix(const glm::vec<4, T>& plane) {
    const glm::vec<3, T> normal(plane);
    const T length = glm::length(normal);
    if (length == T(0)) {
        return glm::mat<4, 4, T>(T(1));
    }
    const glm::vec<3, T> n = normal / length;
    const T d = plane.w / length;
    // x' = x - 2 (n·x + d) n: the linear part is I - 2 n nᵀ, the translation -2 d n.
    glm::mat<4, 4, T> mirror(glm::mat<3, 3, T>(T(1)) - T(2) * glm::outerProduct(n, n));
    mirror[3] = glm::vec<4, T>(T(-2) * d * n, T(1));
    return mirror;
}

template <typename T>
ObliqueProjection<T> ObliqueNearPlane(const glm::mat<4, 4, T>& projection,
                                      const glm::vec<4, T>& clip_plane_view_space) {
    const glm::vec<4, T>& plane = clip_plane_view_space;
    // The camera (view-space origin) must lie strictly on the clipped side, as it does for the
    // ordinary near plane; otherwise the oblique "frustum" would keep points behind the camera
    // and invert the depth order.
    if (!(plane.w < T(0))) {
        return {projection, false};
    }
    // The new far plane is skewed; scaling the plane so that the far corner on its kept side (in
    // clip space (±1, ±1, 1, 1)) stays on it keeps the whole old frustum inside the new one with
    // the least loss of depth precision (Lengyel, section 2; whitepaper figure 14).
    const glm::vec<4, T> corner_clip(Sign(plane.x), Sign(plane.y), T(1), T(1));
    const glm::vec<4, T> corner_view = glm::inverse(projection) * corner_clip;
    const T along = glm::dot(plane, corner_view);
    if (!(along > T(0))) {
        // No visible point is on the kept side (or the projection is singular).
        return {projection, false};
    }
    const glm::vec<4, T> scaled = plane * (T(2) / along);
    // Row 3 (the perspective row) stays; row 2 becomes scaled - row 3, so that
    // clip z + clip w = dot(scaled, p), which is 0 exactly on the plane.
    glm::mat<4, 4, T> oblique = projection;
    for (glm::length_t column = 0; column < 4; ++column) {
        oblique[column][2] = scaled[column] - projection[column][3];
    }
    return {oblique, true};
}

template <typename T>
std::vector<glm::vec<3, T>> InfinitePlanePolygon(const glm::mat<4, 4, T>& view_projection,
                                                 const glm::vec<4, T>& plane) {
    const T normal_length = glm::length(glm::vec<3, T>(plane));
    if (normal_length == T(0)) {
        return {};
    }
    const glm::mat<4, 4, T> inverse = glm::inverse(view_projection);
    const glm::vec<3, T> n = glm::vec<3, T>(plane) / normal_length;
    const T d = plane.w / normal_length;

    // Corner i has NDC x = ±1 by bit 0, y by bit 1, z (near -1, far +1) by bit 2.
    std::array<glm::vec<3, T>, 8> corners;
    std::array<T, 8> distances;
    T scale = T(0);
    for (std::size_t i = 0; i < 8; ++i) {
        const glm::vec<4, T> ndc((i & 1U) ? T(1) : T(-1), (i & 2U) ? T(1) : T(-1),
                                 (i & 4U) ? T(1) : T(-1), T(1));
        const glm::vec<4, T> world = inverse * ndc;
        corners[i] = glm::vec<3, T>(world) / world.w;
        if (!std::isfinite(corners[i].x) || !std::isfinite(corners[i].y) ||
            !std::isfinite(corners[i].z)) {
            return {};  // singular view-projection
        }
        distances[i] = glm::dot(n, corners[i]) + d;
        scale = std::max(
                {scale, std::abs(corners[i].x), std::abs(corners[i].y), std::abs(corners[i].z)});
    }
    const T tolerance = kRelativeTolerance<T> * std::max(scale, T(1));

    std::vector<glm::vec<3, T>> points;
    auto add_point = [&](const glm::vec<3, T>& p) {
        const bool duplicate = std::any_of(points.begin(), points.end(), [&](const auto& q) {
            return glm::length(p - q) <= tolerance;
        });
        if (!duplicate) {
            points.push_back(p);
        }
    };
    for (std::size_t i = 0; i < 8; ++i) {
        if (std::abs(distances[i]) <= tolerance) {
            add_point(corners[i]);
        }
    }
    // The 12 edges join corners that differ in exactly one bit.
    for (std::size_t a = 0; a < 8; ++a) {
        for (std::size_t bit = 1; bit < 8; bit <<= 1U) {
            const std::size_t b = a | bit;
            if (b == a) {
                continue;
            }
            const T da = distances[a];
            const T db = distances[b];
            // Corners within the tolerance were added above; an edge counts only when it truly
            // crosses, so a vertex is never produced twice from both sides of a corner.
            if ((da < -tolerance && db > tolerance) || (da > tolerance && db < -tolerance)) {
                add_point(corners[a] + (corners[b] - corners[a]) * (da / (da - db)));
            }
        }
    }
    if (points.size() < 3) {
        return {};
    }

    // Order by angle in the basis (u, v) with u × v = n: increasing angle is counter-clockwise
    // seen from the positive side. The centroid of a convex polygon's vertices lies inside it.
    glm::vec<3, T> centroid(T(0));
    for (const auto& p : points) {
        centroid += p;
    }
    centroid /= static_cast<T>(points.size());
    const glm::vec<3, T> axis =
            std::abs(n.x) < T(0.9) ? glm::vec<3, T>(1, 0, 0) : glm::vec<3, T>(0, 1, 0);
    const glm::vec<3, T> u = glm::normalize(glm::cross(axis, n));
    const glm::vec<3, T> v = glm::cross(n, u);
    std::vector<std::pair<T, glm::vec<3, T>>> by_angle;
    by_angle.reserve(points.size());
    for (const auto& p : points) {
        by_angle.emplace_back(std::atan2(glm::dot(p - centroid, v), glm::dot(p - centroid, u)), p);
    }
    std::sort(by_angle.begin(), by_angle.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });

    std::vector<glm::vec<3, T>> polygon;
    polygon.reserve(by_angle.size());
    T twice_area = T(0);
    for (const auto& [angle, p] : by_angle) {
        if (!polygon.empty()) {
            twice_area +=
                    glm::dot(glm::cross(polygon.back() - polygon.front(), p - polygon.front()), n);
        }
        polygon.push_back(p);
    }
    // Points along a single line (the plane grazes an edge) enclose no area and draw nothing;
    // a sliver one tolerance wide across the whole frustum is still nothing.
    if (twice_area <= tolerance * std::max(scale, T(1))) {
        return {};
    }
    return polygon;
}

template <typename T>
glm::vec<2, T> ProjectiveTexCoord(const glm::mat<4, 4, T>& view_projection,
                                  const glm::vec<3, T>& world) {
    const glm::vec<4, T> clip = view_projection * glm::vec<4, T>(world, T(1));
    return glm::vec<2, T>(clip) / clip.w * T(0.5) + T(0.5);
}

template <typename T>
glm::vec<2, T> AdvanceBumpTranslation(glm::vec<2, T> translation, glm::vec<2, T> velocity, T dt,
                                      bool wrap) {
    glm::vec<2, T> advanced = translation + velocity * dt;
    if (wrap) {
        advanced -= glm::floor(advanced);
        // x - floor(x) rounds to exactly 1 for tiny negative x (e.g. -1e-9f); 1 wraps to 0.
        for (glm::length_t i = 0; i < 2; ++i) {
            if (advanced[i] >= T(1)) {
                advanced[i] = T(0);
            }
        }
    }
    return advanced;
}

template <typename T>
glm::vec<4, T> TransformPlane(const glm::mat<4, 4, T>& matrix, const glm::vec<4, T>& plane) {
    // A plane is a row vector: dot(P, x) = 0 becomes dot(P M⁻¹, M x) = 0, i.e. P' = M⁻ᵀ P.
    return glm::transpose(glm::inverse(matrix)) * plane;
}

template <typename T>
glm::mat<4, 4, T> LookAtWithFallbackUp(const glm::vec<3, T>& eye, const glm::vec<3, T>& target) {
    const glm::vec<3, T> direction = target - eye;
    const T length = glm::length(direction);
    if (!(length > T(0))) {
        return glm::mat<4, 4, T>(T(1));
    }
    const glm::vec<3, T> up(T(0), T(1), T(0));
    const T sine = glm::length(glm::cross(direction / length, up));
    if (sine >= static_cast<T>(kVerticalViewSine)) {
        return glm::lookAt(eye, target, up);
    }
    // Looking down, screen-up is -z (north on a map); looking up, +z, so the image is the
    // limit of a view tilting towards vertical from the default views' side.
    const glm::vec<3, T> fallback(T(0), T(0), direction.y < T(0) ? T(-1) : T(1));
    return glm::lookAt(eye, target, fallback);
}

namespace {

// clamp(numerator / denominator, 0, 1) where a non-positive denominator means "reached at once".
float SaturatedRatio(float numerator, float denominator) {
    if (!(denominator > 0.0F)) {
        return numerator > 0.0F ? 1.0F : 0.0F;
    }
    return std::clamp(numerator / denominator, 0.0F, 1.0F);
}

}  // namespace

glm::vec3 ExtinctionColour(glm::vec3 refraction, float depth, float cos_view,
                           const ExtinctionModel& model) {
    const float path = depth / std::max(cos_view, kMinExtinctionViewCos);
    glm::vec3 colour =
            glm::mix(refraction, model.surface_colour, SaturatedRatio(path, model.visibility));
    for (int channel = 0; channel < 3; ++channel) {
        colour[channel] = glm::mix(colour[channel], model.depth_colour[channel],
                                   SaturatedRatio(depth, model.extinction[channel]));
    }
    return colour;
}

template glm::mat<4, 4, float> LookAtWithFallbackUp(const glm::vec<3, float>&,
                                                    const glm::vec<3, float>&);
template glm::mat<4, 4, double> LookAtWithFallbackUp(const glm::vec<3, double>&,
                                                     const glm::vec<3, double>&);
template glm::mat<4, 4, float> MirrorMatrix(const glm::vec<4, float>&);
template ObliqueProjection<float> ObliqueNearPlane(const glm::mat<4, 4, float>&,
                                                   const glm::vec<4, float>&);
template std::vector<glm::vec<3, float>> InfinitePlanePolygon(const glm::mat<4, 4, float>&,
                                                              const glm::vec<4, float>&);
template glm::vec<2, float> ProjectiveTexCoord(const glm::mat<4, 4, float>&,
                                               const glm::vec<3, float>&);
template glm::vec<2, float> AdvanceBumpTranslation(glm::vec<2, float>, glm::vec<2, float>, float,
                                                   bool);
template glm::vec<4, float> TransformPlane(const glm::mat<4, 4, float>&, const glm::vec<4, float>&);

template glm::mat<4, 4, double> MirrorMatrix(const glm::vec<4, double>&);
template ObliqueProjection<double> ObliqueNearPlane(const glm::mat<4, 4, double>&,
                                                    const glm::vec<4, double>&);
template std::vector<glm::vec<3, double>> InfinitePlanePolygon(const glm::mat<4, 4, double>&,
                                                               const glm::vec<4, double>&);
template glm::vec<2, double> ProjectiveTexCoord(const glm::mat<4, 4, double>&,
                                                const glm::vec<3, double>&);
template glm::vec<2, double> AdvanceBumpTranslation(glm::vec<2, double>, glm::vec<2, double>,
                                                    double, bool);
template glm::vec<4, double> TransformPlane(const glm::mat<4, 4, double>&,
                                            const glm::vec<4, double>&);

}  // namespace tidepool::runner
