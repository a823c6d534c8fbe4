#include "tidepool/lab/StabilityReport.h"

#include "tidepool/Manifest.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/runner/ShaderFeatures.h"
#include "tidepool/runner/WaterMath.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

namespace tidepool::lab {
namespace {

using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;
using dmat4 = glm::dmat4;

// Counts NaN and Inf in `values` into the result.
template <typename Range>
void CountNonFinite(const Range& values, StabilityCaseResult* result) {
    for (const auto v : values) {
        const double d = static_cast<double>(v);
        result->nan_count += std::isnan(d) ? 1 : 0;
        result->inf_count += std::isinf(d) ? 1 : 0;
    }
}

template <typename T, int N>
std::vector<T> Components(const glm::vec<N, T>& v) {
    std::vector<T> out;
    out.reserve(N);
    for (int i = 0; i < N; ++i) {
        out.push_back(v[i]);
    }
    return out;
}

template <typename T>
std::vector<T> Components(const glm::mat<4, 4, T>& m) {
    std::vector<T> out;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            out.push_back(m[c][r]);
        }
    }
    return out;
}

// A camera for the sweeps: eye, pitch (radians, negative looks down), yaw, far plane.
struct SweepCamera {
    dvec3 eye;
    double pitch;
    double yaw;
    double far_plane;
};

std::vector<SweepCamera> SweepCameras() {
    std::vector<SweepCamera> cameras;
    const double pi = 3.14159265358979323846;
    for (const double height : {-50.0, -1.0, -1e-4, 0.0, 1e-4, 0.4999, 0.5, 0.5001, 1.5, 40.0}) {
        for (const double pitch : {-pi / 2, -1.2, -0.5, -0.05, 0.0, 0.05, 0.5, 1.2, pi / 2}) {
            for (const double far_plane : {2000.0, 1e6}) {
                cameras.push_back({{17.0, height, -23.0}, pitch, 0.7, far_plane});
            }
        }
    }
    return cameras;
}

template <typename T>
glm::mat<4, 4, T> SweepViewProjection(const SweepCamera& c, glm::mat<4, 4, T>* view = nullptr,
                                      glm::mat<4, 4, T>* projection = nullptr) {
    using V = glm::vec<3, T>;
    const V eye(c.eye);
    const V dir(std::cos(c.pitch) * std::cos(c.yaw), std::sin(c.pitch),
                std::cos(c.pitch) * std::sin(c.yaw));
    const glm::mat<4, 4, T> v = LookAtWithFallbackUp(eye, eye + dir * T(10));
    const glm::mat<4, 4, T> p =
            glm::perspective(T(0.872665), T(4.0 / 3.0), T(1), static_cast<T>(c.far_plane));
    if (view != nullptr) {
        *view = v;
    }
    if (projection != nullptr) {
        *projection = p;
    }
    return p * v;
}

StabilityCaseResult MirrorSweep() {
    StabilityCaseResult r;
    // Float against double on reflected points, relative to the larger of the point's and the
    // plane's distance from the origin: about ten float operations, so 1e-5 (~80 ulps) leaves
    // room for cancellation near the plane without hiding a wrong formula.
    r.bound = 1e-5;
    r.note = "max |float - double| of reflected points / max(1, |p|, |d|); the double mirror "
             "applied twice must be the identity to 1e-12 (1 + |d|)";
    for (int i = 0; i < 40; ++i) {
        const double theta = 0.05 + 3.0 * i / 39.0;
        const double phi = 0.3 + 0.9 * i;
        const double length = std::pow(10.0, -2.0 + 4.0 * (i % 10) / 9.0);  // unnormalised
        for (const double d : {-1000.0, -0.5, 0.0, 1e-4, 3.0, 1000.0}) {
            const dvec4 plane(length * std::sin(theta) * std::cos(phi), length * std::cos(theta),
                              length * std::sin(theta) * std::sin(phi), d * length);
            const dmat4 md = MirrorMatrix(plane);
            const glm::mat4 mf = MirrorMatrix(glm::vec4(plane));
            CountNonFinite(Components(mf), &r);
            const dmat4 twice = md * md;
            for (int c = 0; c < 4; ++c) {
                for (int k = 0; k < 4; ++k) {
                    // The translation column carries d: a few double ulps of it.
                    if (std::abs(twice[c][k] - (c == k ? 1.0 : 0.0)) >
                        1e-12 * (1.0 + std::abs(d))) {
                        r.max_error = std::max(r.max_error, 1.0);  // fails the case
                    }
                }
            }
            for (const dvec3 p : {dvec3(0.0), dvec3(10, -3, 7), dvec3(-500, 20, 1500)}) {
                const dvec4 ref = md * dvec4(p, 1.0);
                const glm::vec4 got = mf * glm::vec4(glm::vec3(p), 1.0F);
                const double scale = std::max({1.0, glm::length(p), std::abs(d)});
                r.max_error = std::max(r.max_error, glm::length(dvec3(got) - dvec3(ref)) / scale);
            }
        }
    }
    return r;
}

StabilityCaseResult ObliqueSweep() {
    StabilityCaseResult r;
    // Points of the clip plane must land on the near plane: |z/w + 1| in float. The error grows
    // as the camera nears the plane (the band: the scaled plane's entries grow like 1/distance);
    // 1e-3 of the NDC depth range still keeps the clip within a sliver of the 0.5-unit clip
    // offset, and the sweep reaches 1e-4 from the plane.
    r.bound = 1e-3;
    int fallbacks = 0;
    int expected_fallbacks = 0;
    int applied = 0;
    for (const SweepCamera& camera : SweepCameras()) {
        dmat4 view_d;
        dmat4 projection_d;
        SweepViewProjection<double>(camera, &view_d, &projection_d);
        glm::mat4 view_f;
        glm::mat4 projection_f;
        SweepViewProjection<float>(camera, &view_f, &projection_f);
        // The reflection pass keeps y >= 0 seen from a camera at `height`; below the plane the
        // camera is on the clipped side as the method needs, above it the plane faces it.
        const dvec4 world_plane(0.0, 1.0, 0.0, 0.0);
        const dvec4 plane_d = TransformPlane(view_d, world_plane);
        const glm::vec4 plane_f = TransformPlane(view_f, glm::vec4(world_plane));
        const ObliqueProjection<float> oblique = ObliqueNearPlane(projection_f, plane_f);
        CountNonFinite(Components(oblique.projection), &r);
        // Within 1e-6 of the plane float rounding of the view matrix decides the side, and
        // either answer is defined behaviour; beyond it the side is certain.
        const bool camera_kept_side = plane_d.w > 1e-6;
        expected_fallbacks += camera_kept_side ? 1 : 0;
        if (!oblique.applied) {
            ++fallbacks;
            if (oblique.projection != projection_f) {
                r.max_error = std::max(r.max_error, 1.0);
                r.note += "fallback changed the projection; ";
            }
            continue;
        }
        ++applied;
        if (camera_kept_side) {
            r.max_error = std::max(r.max_error, 1.0);
            r.note += fmt::format("applied with the camera on the kept side at y = {}; ",
                                  camera.eye.y);
        }
        // x, y and w rows stay untouched.
        for (int c = 0; c < 4; ++c) {
            for (const int row : {0, 1, 3}) {
                if (oblique.projection[c][row] != projection_f[c][row]) {
                    r.max_error = std::max(r.max_error, 1.0);
                }
            }
        }
        // Points of the world plane in front of the camera.
        const dmat4 oblique_d(oblique.projection);
        for (const double forward : {2.0, 30.0, 500.0}) {
            for (const double side : {-20.0, 0.0, 20.0}) {
                const dvec3 p(camera.eye.x + forward * std::cos(camera.yaw) + side, 0.0,
                              camera.eye.z + forward * std::sin(camera.yaw));
                const dvec4 eye_space = view_d * dvec4(p, 1.0);
                if (eye_space.z > -1.0) {
                    continue;  // behind the camera or before the near plane
                }
                const dvec4 clip = oblique_d * eye_space;
                r.max_error = std::max(r.max_error, std::abs(clip.z / clip.w + 1.0));
            }
        }
    }
    r.note += fmt::format(
            "max |z/w + 1| for clip-plane points (float matrix); {} applied, {} "
            "fell back (clip plane facing the camera or camera on it: {} expected)",
            applied, fallbacks, expected_fallbacks);
    if (fallbacks < expected_fallbacks) {
        r.max_error = std::max(r.max_error, 1.0);
    }
    return r;
}

StabilityCaseResult PolygonAndTexCoordSweep(bool tex_coords) {
    StabilityCaseResult r;
    // Polygon: a float vertex may be off the plane or outside the frustum by rounding of the
    // unprojected corners, which scale with the far plane (1e6): 1e-5 of the frustum's size is
    // ~100 float ulps. Texture coordinates: float against double in [0,1] units; 1e-4 is 1/16
    // of a texel of a 640 target.
    r.bound = tex_coords ? 1e-4 : 1e-5;
    int empty = 0;
    for (const SweepCamera& camera : SweepCameras()) {
        const dmat4 vp_d = SweepViewProjection<double>(camera);
        const glm::mat4 vp_f = SweepViewProjection<float>(camera);
        const dvec4 plane(0.0, 1.0, 0.0, 0.0);
        const auto polygon_d = InfinitePlanePolygon(vp_d, plane);
        const auto polygon_f = InfinitePlanePolygon(vp_f, glm::vec4(plane));
        if (polygon_d.empty() != polygon_f.empty()) {
            // A plane grazing a frustum corner may be a sliver in one precision only; both are
            // nothing to draw, so only a large polygon missing in float counts.
            if (!polygon_d.empty() && polygon_d.size() >= 3) {
                double area = 0;
                for (std::size_t i = 1; i + 1 < polygon_d.size(); ++i) {
                    area += glm::length(glm::cross(polygon_d[i] - polygon_d[0],
                                                   polygon_d[i + 1] - polygon_d[0]));
                }
                if (area > 1e-3 * camera.far_plane * camera.far_plane) {
                    r.max_error = std::max(r.max_error, 1.0);
                    r.note += fmt::format("float lost the polygon at y = {}; ", camera.eye.y);
                }
            }
            continue;
        }
        if (polygon_f.empty()) {
            ++empty;
            continue;
        }
        for (const glm::vec3& v : polygon_f) {
            CountNonFinite(Components(v), &r);
        }
        if (!tex_coords) {
            for (const glm::vec3& v : polygon_f) {
                const dvec3 p(v);
                r.max_error = std::max(r.max_error, std::abs(p.y) / camera.far_plane);
                const dvec4 clip = vp_d * dvec4(p, 1.0);
                const double overshoot =
                        std::max({std::abs(clip.x), std::abs(clip.y), std::abs(clip.z)}) / clip.w -
                        1.0;
                r.max_error = std::max(r.max_error, std::max(overshoot, 0.0) * 1e-2);
            }
            continue;
        }
        // Vertices and interior points (towards the centroid) of the double polygon.
        dvec3 centroid(0.0);
        for (const dvec3& v : polygon_d) {
            centroid += v;
        }
        centroid /= static_cast<double>(polygon_d.size());
        for (const dvec3& v : polygon_d) {
            for (const double t : {0.0, 0.5, 0.99}) {
                const dvec3 p = v + (centroid - v) * t;
                const glm::dvec2 ref = ProjectiveTexCoord(vp_d, p);
                const glm::vec2 got = ProjectiveTexCoord(vp_f, glm::vec3(p));
                CountNonFinite(Components(got), &r);
                r.max_error = std::max(r.max_error, glm::length(glm::dvec2(got) - ref));
            }
        }
    }
    r.note = tex_coords ? "max |float - double| of [0,1] screen coordinates of polygon points"
                        : "max float vertex distance from the plane / far plane (and 1e-2 x NDC "
                          "overshoot outside the frustum)";
    r.note += fmt::format("; {} views see no water (empty polygon, as defined)", empty);
    return r;
}

StabilityCaseResult VerticalViewSweep() {
    StabilityCaseResult r;
    // The rotation part must be orthonormal: 1e-6 is ~8 float ulps for a 3x3 product.
    r.bound = 1e-6;
    int view_matrix_nan = 0;
    for (const double dy : {-1.0, 1.0}) {
        for (const double tilt : {0.0, 1e-7, 1e-5, 9e-5, 1.1e-4, 1e-3}) {
            const glm::vec3 eye(20.0F, 30.0F, 20.0F);
            const glm::vec3 target = eye + glm::vec3(static_cast<float>(tilt) * 10.0F,
                                                     static_cast<float>(dy) * 10.0F, 0.0F);
            const glm::mat4 view = LookAtWithFallbackUp(eye, target);
            CountNonFinite(Components(view), &r);
            const glm::mat3 rotation(view);
            const glm::mat3 identity = rotation * glm::transpose(rotation);
            for (int c = 0; c < 3; ++c) {
                for (int k = 0; k < 3; ++k) {
                    r.max_error = std::max(
                            r.max_error,
                            static_cast<double>(std::abs(identity[c][k] - (c == k ? 1.0F : 0.0F))));
                }
            }
            CameraView camera{"", eye, target, 0.87F, 1.0F, 2000.0F};
            const glm::mat4 plain = ViewMatrix(camera);
            view_matrix_nan += std::isfinite(plain[0][0]) ? 0 : 1;
        }
    }
    r.note = fmt::format(
            "max |R Rᵀ - I|; the plain y-up ViewMatrix is NaN in {} of the 12 "
            "views (why the renderer uses LookAtWithFallbackUp)",
            view_matrix_nan);
    return r;
}

StabilityCaseResult BumpTranslationSweep() {
    StabilityCaseResult r;
    // The renderer's path (double, rounded once to float) must match double to float rounding
    // of a number in [0, 1): 1e-7 > 2^-24.
    r.bound = 1e-7;
    double float_path_error = 0;
    for (const double time : {0.0, 2.0, 3600.0, 86400.0, 1e6, 1e7}) {
        for (const glm::dvec2 velocity : {glm::dvec2(0.013, 0.021), glm::dvec2(-0.017, 0.009)}) {
            const glm::dvec2 ref = AdvanceBumpTranslation(glm::dvec2(0.0), velocity, time, true);
            const glm::vec2 renderer(ref);
            const glm::vec2 single = AdvanceBumpTranslation(glm::vec2(0.0F), glm::vec2(velocity),
                                                            static_cast<float>(time), true);
            const glm::vec2 unwrapped = AdvanceBumpTranslation(glm::vec2(0.0F), glm::vec2(velocity),
                                                               static_cast<float>(time), false);
            CountNonFinite(Components(renderer), &r);
            CountNonFinite(Components(single), &r);
            CountNonFinite(Components(unwrapped), &r);
            for (int k = 0; k < 2; ++k) {
                if (renderer[k] < 0.0F || renderer[k] >= 1.0F) {
                    r.max_error = std::max(r.max_error, 1.0);
                }
                r.max_error =
                        std::max(r.max_error, std::abs(static_cast<double>(renderer[k]) - ref[k]));
                // Wrapped distance: 0.999 and 0.001 are 0.002 apart on the torus.
                double e = std::abs(static_cast<double>(single[k]) - ref[k]);
                e = std::min(e, 1.0 - e);
                float_path_error = std::max(float_path_error, e);
            }
        }
    }
    r.note = fmt::format(
            "max |renderer - double| of the wrapped translation up to 1e7 s; the "
            "all-float path is off by up to {:.3g} texture units",
            float_path_error);
    return r;
}

template <typename S>
S SchlickOf(S cos_incidence) {
    const S m = S(1) - cos_incidence;
    return S(0.02037) + S(0.97963) * (m * m * m * m * m);
}

StabilityCaseResult FresnelSweep() {
    StabilityCaseResult r;
    // The reflectance must stay in [R(0), 1]: 1e-6 allows float rounding of the endpoints.
    r.bound = 1e-6;
    int negative_base = 0;
    int samples = 0;
    for (int a = 0; a < 40; ++a) {
        for (int b = 0; b < 40; ++b) {
            // Summed normals of two layers: lengths from ~0 (opposed tilts) to 2.
            const float t0 = 1.4F * static_cast<float>(a) / 39.0F;
            const float t1 = 1.4F * static_cast<float>(b) / 39.0F;
            const glm::vec3 n = glm::vec3(std::sin(t0), std::cos(t0), 0.0F) +
                                glm::vec3(-std::sin(t1) * 0.9F, std::cos(t1) * 0.2F, 0.1F);
            for (int e = 0; e <= 20; ++e) {
                const float elevation = -0.05F + 1.6F * static_cast<float>(e) / 20.0F;
                const glm::vec3 eye(std::cos(elevation), std::sin(elevation), 0.0F);
                ++samples;
                // Whitepaper: assumes |n| = 1 and no clamp.
                negative_base += 1.0F - glm::dot(n, eye) < 0.0F ? 1 : 0;
                // water.fsh: floored inversesqrt, clamp, fifth power by multiplication.
                const glm::vec3 unit = n * (1.0F / std::sqrt(std::max(glm::dot(n, n), 1e-4F)));
                const float cos_i = std::clamp(glm::dot(unit, eye), 0.0F, 1.0F);
                const float f = SchlickOf(cos_i);
                CountNonFinite(std::vector<float>{f}, &r);
                r.max_error = std::max({r.max_error, static_cast<double>(0.02037F - f),
                                        static_cast<double>(f - 1.0F)});
            }
        }
    }
    r.note = fmt::format(
            "max distance of the guarded reflectance outside [R(0), 1]; the "
            "whitepaper's unguarded 1 - dot(N, E) is negative at {} of {} samples",
            negative_base, samples);
    return r;
}

StabilityCaseResult DistortionSweep() {
    StabilityCaseResult r;
    // water.fsh: the demo's WaveDistortion (100, texture units) over the floored eye distance,
    // capped at 16 (cMaxDistortion), times the mean bump normal (|xz| <= 1).
    const float wave = 100.0F;
    constexpr float kMaxDistortion = 16.0F;
    r.bound = kMaxDistortion;
    for (int i = 0; i <= 200; ++i) {
        const float distance =
                i == 0 ? 0.0F : std::pow(10.0F, -8.0F + 0.05F * static_cast<float>(i));
        const float eye_distance = std::max(distance, 1e-3F);
        const float offset = std::min(wave / eye_distance, kMaxDistortion);
        CountNonFinite(std::vector<float>{offset}, &r);
        r.max_error = std::max(r.max_error, static_cast<double>(std::abs(offset)));
    }
    r.note = "max |offset| in texture widths for eye distances 0 .. 100";
    return r;
}

StabilityCaseResult FogSweep() {
    StabilityCaseResult r;
    r.bound = 0.0;  // the factor must lie in [0, 1] exactly (clamp)
    const float inf = std::numeric_limits<float>::infinity();
    for (const float rcp :
         {0.0F, 1e-30F, 1e-3F, 1.0F, 1e30F, inf, -1.0F, std::numeric_limits<float>::quiet_NaN()}) {
        const float uploaded = MediumpFogReciprocal(rcp);
        CountNonFinite(std::vector<float>{uploaded}, &r);
        for (const float depth : {0.0F, 1e-3F, 1.0F, 2000.0F, 1e6F}) {
            const float factor = std::clamp(depth * uploaded, 0.0F, 1.0F);
            CountNonFinite(std::vector<float>{factor}, &r);
            r.max_error = std::max({r.max_error, static_cast<double>(-factor),
                                    static_cast<double>(factor - 1.0F)});
        }
    }
    r.note = "fog factor outside [0, 1] with the uploaded (clamped) reciprocal";
    return r;
}

}  // namespace

StabilityCaseResult RunCpuHardCase(const HardCase& hard_case) {
    StabilityCaseResult r;
    if (hard_case.name == "cpu_mirror_matrix") {
        r = MirrorSweep();
    } else if (hard_case.name == "cpu_oblique_near_plane") {
        r = ObliqueSweep();
    } else if (hard_case.name == "cpu_infinite_plane_polygon") {
        r = PolygonAndTexCoordSweep(false);
    } else if (hard_case.name == "cpu_projective_tex_coord") {
        r = PolygonAndTexCoordSweep(true);
    } else if (hard_case.name == "cpu_view_matrix_vertical") {
        r = VerticalViewSweep();
    } else if (hard_case.name == "cpu_bump_translation_long_run") {
        r = BumpTranslationSweep();
    } else if (hard_case.name == "cpu_fresnel_unnormalised_normal") {
        r = FresnelSweep();
    } else if (hard_case.name == "cpu_distortion_eye_distance_zero") {
        r = DistortionSweep();
    } else if (hard_case.name == "cpu_fog_depth_extremes") {
        r = FogSweep();
    } else {
        r.note = fmt::format("'{}' is not a CPU hard case", hard_case.name);
        r.max_error = 1.0;
    }
    r.name = hard_case.name;
    r.description = hard_case.description;
    r.kind = HardCaseKindName(HardCaseKind::kCpu);
    r.fix = hard_case.fix;
    r.passed = hard_case.kind == HardCaseKind::kCpu && r.nan_count == 0 && r.inf_count == 0 &&
               r.max_error <= r.bound;
    return r;
}

std::vector<RenderConfiguration> WaterVariantConfigurations(const std::vector<Variant>& variants) {
    std::vector<RenderConfiguration> configs;
    for (const Variant& variant : variants) {
        if (variant.program != kWaterProgram) {
            continue;
        }
        RenderConfiguration c;
        c.variant = variant;
        c.effects = variant.defines;
        c.id = ConfigurationId(c.variant, c.passes);
        configs.push_back(std::move(c));
    }
    return configs;
}

namespace {

// Float pixels outside [0, 1] by more than this are out of range: mix() of values in [0, 1]
// with a weight in [0, 1] can overshoot by a few float ulps of 1, never by 1e-5.
constexpr double kRangeTolerance = 1e-5;

// The smallest renderer settings a case needs: shared textures stay small.
RenderSettings CaseSettings(const HardCase& c, const GlStabilityOptions& options) {
    RenderSettings settings = c.settings;
    if (!c.fixed_size) {
        settings.width = options.width;
        settings.height = options.height;
    }
    settings.float_target = true;
    settings.sky_size = 32;
    settings.normal_map_size = 64;
    settings.normalisation_cube_size = 16;
    settings.low_res_water_size = 32;
    return settings;
}

// A renderer per render size, kept for every case of that size.
struct RendererPool {
    GlContext* context;
    const VariantConfig* config;
    std::map<std::pair<int, int>, std::unique_ptr<WaterRenderer>> renderers;

    WaterRenderer* For(const RenderSettings& settings, std::string* error) {
        auto& slot = renderers[{settings.width, settings.height}];
        if (!slot) {
            slot = WaterRenderer::Create(*context, *config, settings, error);
            if (!slot) {
                return nullptr;
            }
        }
        slot->UpdateFrameSettings(settings);
        return slot.get();
    }
};

}  // namespace

std::vector<StabilityCaseResult> RunGlHardCases(GlContext& context, const VariantConfig& config,
                                                const std::vector<RenderConfiguration>& configs,
                                                const std::vector<HardCase>& cases,
                                                const GlStabilityOptions& options,
                                                std::string* error) {
    std::vector<StabilityCaseResult> results;
    if (!context.Environment().float_render_target) {
        *error = "the GL context cannot render to RGBA32F, so NaN and Inf cannot be seen";
        return results;
    }
    RendererPool pool{&context, &config, {}};
    const auto gl_cases =
            static_cast<double>(std::count_if(cases.begin(), cases.end(), [](const HardCase& c) {
                return c.kind == HardCaseKind::kGl;
            }));
    for (const HardCase& hard_case : cases) {
        if (hard_case.kind != HardCaseKind::kGl) {
            continue;
        }
        StabilityCaseResult r;
        r.name = hard_case.name;
        r.description = hard_case.description;
        r.kind = HardCaseKindName(HardCaseKind::kGl);
        r.fix = hard_case.fix;
        r.bound = kRangeTolerance;
        const RenderSettings settings = CaseSettings(hard_case, options);
        WaterRenderer* renderer = pool.For(settings, error);
        if (renderer == nullptr) {
            return {};
        }
        int failures = 0;
        int fallbacks = 0;
        for (RenderConfiguration c : configs) {
            if (hard_case.reflection_size > 0) {
                c.passes.reflection_size = hard_case.reflection_size;
                c.passes.refraction_size = hard_case.reflection_size;
                c.id = ConfigurationId(c.variant, c.passes);
            }
            const DriverVerdict verdict = renderer->Prepare(c);
            ++r.variants_checked;
            if (!verdict.valid) {
                ++failures;
                r.note += fmt::format("{} does not compile; ", c.id);
                continue;
            }
            const FrameReport frame = renderer->RenderFrame(c, hard_case.view);
            fallbacks += frame.oblique_fallback ? 1 : 0;
            if (!frame.gl_error.empty()) {
                ++failures;
                r.note += fmt::format("{}: {}; ", c.id, frame.gl_error);
                continue;
            }
            const std::vector<float> pixels = renderer->ReadFloatPixels();
            const long nan_before = r.nan_count + r.inf_count;
            CountNonFinite(pixels, &r);
            double excess = 0;
            for (const float v : pixels) {
                if (std::isfinite(v)) {
                    excess = std::max(
                            {excess, static_cast<double>(-v), static_cast<double>(v) - 1.0});
                }
            }
            if (r.nan_count + r.inf_count > nan_before || excess > kRangeTolerance) {
                ++failures;
                if (failures <= 3) {
                    r.note += fmt::format("{} fails (out of range by {:.3g}); ", c.id, excess);
                }
            }
            r.max_error = std::max(r.max_error, excess);
        }
        r.note += fmt::format(
                "max channel distance outside [0, 1] over {} configurations at "
                "{}x{}; {} fell back to discard clipping",
                r.variants_checked, settings.width, settings.height, fallbacks);
        r.passed = failures == 0 && r.nan_count == 0 && r.inf_count == 0 && r.max_error <= r.bound;
        results.push_back(std::move(r));
        if (options.on_case_done) {
            options.on_case_done(static_cast<double>(results.size()) / gl_cases);
        }
    }
    return results;
}

std::vector<GuardResult> MeasureGuards(GlContext& context, const VariantConfig& config,
                                       const GlStabilityOptions& options, std::string* error) {
    std::vector<GuardResult> results;
    if (!context.Environment().float_render_target) {
        *error = "the GL context cannot render to RGBA32F";
        return results;
    }
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.float_target = true;
    std::unique_ptr<WaterRenderer> renderer =
            WaterRenderer::Create(context, config, settings, error);
    if (!renderer) {
        return results;
    }
    // One 8-bit colour step: below it a guard cannot change the delivered RGBA8 image.
    constexpr double kOneStep = 1.0 / 255.0;
    struct Guard {
        const char* text;
        const char* define;
        double tolerance;
    };
    const Guard guards[] = {
            // Unlike the others this guard corrects normal views: on the default "grazing" view
            // back-facing summed bump normals give cos slightly below 0, where the unclamped F
            // exceeds 1 and mix() extrapolates past the reflection. Measured: 0.071 at 64x48 with
            // distortion in the demo's units (before: 0.032 at 32x24, 0.084 at 64x48; finer
            // pixels reach steeper normals). 0.1 (F = 1.1, cos ≈ -0.02) bounds that sliver; more
            // would mean the clamp acts beyond back-facing normals.
            {"clamp(dot(N, E), 0, 1) before the Fresnel power", "TP_NO_COS_CLAMP", 0.1},
            {"floored inversesqrt normalising the summed bump normal", "TP_NO_NORMAL_FLOOR",
             kOneStep},
            {"eye distance floored at 1e-3 (distortion divide, fog)", "TP_NO_EYE_FLOOR", kOneStep},
            {"eye vector divided by its largest component before squaring", "TP_NO_EYE_SCALING",
             kOneStep},
    };
    // The variants every guard is live in: the full effect with Schlick and with exact Fresnel.
    const std::vector<std::vector<std::string>> variants = {
            DefineNames({ShaderFeature::kDistortion, ShaderFeature::kFog, ShaderFeature::kFresnel,
                         ShaderFeature::kRefraction, ShaderFeature::kScaleDistortion}),
            DefineNames({ShaderFeature::kDistortion, ShaderFeature::kFog, ShaderFeature::kFresnel,
                         ShaderFeature::kRefraction, ShaderFeature::kScaleDistortion,
                         ShaderFeature::kFresnelExact}),
    };
    auto render = [&](const std::vector<std::string>& defines, const CameraView& view,
                      std::vector<float>* pixels) {
        RenderConfiguration c;
        c.variant = MakeVariant(std::string(kWaterProgram), defines);
        c.effects = c.variant.defines;
        c.id = ConfigurationId(c.variant, c.passes);
        if (!renderer->Prepare(c).valid) {
            return false;
        }
        renderer->RenderFrame(c, view);
        *pixels = renderer->ReadFloatPixels();
        return true;
    };
    for (const Guard& guard : guards) {
        GuardResult g;
        g.guard = fmt::format("{} ({} removes it)", guard.text, guard.define);
        g.tolerance = guard.tolerance;
        bool ok = true;
        for (const auto& defines : variants) {
            std::vector<std::string> unguarded = defines;
            unguarded.emplace_back(guard.define);
            for (const CameraView& view : DefaultViews()) {
                std::vector<float> with;
                std::vector<float> without;
                ok = ok && render(defines, view, &with) && render(unguarded, view, &without);
                if (!ok || with.size() != without.size()) {
                    ok = false;
                    break;
                }
                for (std::size_t i = 0; i < with.size(); ++i) {
                    const double diff = std::abs(static_cast<double>(with[i]) - without[i]);
                    // NaN without the guard is an infinite difference.
                    g.max_channel_diff_normal_views =
                            std::isfinite(diff) ? std::max(g.max_channel_diff_normal_views, diff)
                                                : 1e30;
                }
            }
        }
        g.passed = ok && g.max_channel_diff_normal_views <= g.tolerance;
        results.push_back(std::move(g));
    }
    return results;
}

}  // namespace tidepool::lab
