#include "tidepool/lab/HardCases.h"

#include <algorithm>
#include <limits>
#include <utility>

#include <glm/gtc/constants.hpp>

namespace tidepool::lab {
namespace {

// The default views' lens: 50° vertical field, near 1, far 2000 (ProceduralScene.cpp).
CameraView Camera(std::string name, glm::vec3 eye, glm::vec3 target, float near_plane = 1.0F,
                  float far_plane = 2000.0F) {
    return CameraView{std::move(name), eye, target, glm::radians(50.0F), near_plane, far_plane};
}

HardCase Cpu(std::string name, std::string description, std::string fix = "") {
    HardCase c;
    c.name = std::move(name);
    c.description = std::move(description);
    c.kind = HardCaseKind::kCpu;
    c.fix = std::move(fix);
    return c;
}

HardCase Gl(std::string name, std::string description, CameraView view, std::string fix = "") {
    HardCase c;
    c.name = std::move(name);
    c.description = std::move(description);
    c.kind = HardCaseKind::kGl;
    c.fix = std::move(fix);
    c.view = std::move(view);
    c.view.name = c.name;
    return c;
}

// The renderer's reflection clip plane sits RenderSettings::clip_plane_offset below the water,
// so the mirrored camera reaches it when the real one is that high above the water.
constexpr float kClipOffset = 0.5F;

}  // namespace

const char* HardCaseKindName(HardCaseKind kind) {
    return kind == HardCaseKind::kCpu ? "cpu" : "gl";
}

std::vector<HardCase> HardCaseCatalogue() {
    std::vector<HardCase> cases;
    // ---- CPU sweeps against a double-precision reference ------------------------------------
    cases.push_back(Cpu("cpu_mirror_matrix",
                        "MirrorMatrix over 2000 planes (tilted, unnormalised, far from the origin) "
                        "and points: float against double, and mirroring twice is the identity."));
    cases.push_back(
            Cpu("cpu_oblique_near_plane",
                "ObliqueNearPlane with the camera above, on, just beside and below the clip "
                "plane (the band where the oblique near plane meets the camera) and at "
                "every pitch: plane points map to clip z = -w, x/y/w rows stay, and a clip "
                "plane facing the camera falls back to the unmodified projection.",
                "none needed: the fallback (applied = false, the renderer clips with "
                "discard) already existed; the sweep now proves it and the band's bound"));
    cases.push_back(Cpu("cpu_infinite_plane_polygon",
                        "InfinitePlanePolygon for cameras on, just above and below the water, "
                        "straight down, straight up, at the horizon and with far planes up to "
                        "1e6: vertices on the plane, inside the frustum, float against double."));
    cases.push_back(Cpu("cpu_projective_tex_coord",
                        "ProjectiveTexCoord of polygon vertices and random visible points, far "
                        "plane up to 1e6: float against double, in [0, 1] when visible."));
    cases.push_back(Cpu("cpu_view_matrix_vertical",
                        "The view matrix looking straight down and straight up, where lookAt with "
                        "a y up vector normalises a zero cross product.",
                        "LookAtWithFallbackUp (WaterMath.h) uses -z/+z as the up vector within "
                        "1e-4 rad of vertical; the renderer plans with it instead of ViewMatrix"));
    cases.push_back(Cpu("cpu_bump_translation_long_run",
                        "Bump translation after 1e6 s, wrapped and unwrapped, float against "
                        "double: float keeps only ~1e-3 of the fraction at 1e6 s.",
                        "the renderer advances the translation in double and rounds the wrapped "
                        "fraction to float (error < 1e-7 instead of ~1e-3)"));
    cases.push_back(Cpu("cpu_fresnel_unnormalised_normal",
                        "The Fresnel term with summed bump normals of length 0..2 and eye vectors "
                        "at grazing angles: the whitepaper's 1 - dot(N, E) goes negative (pow of "
                        "a negative base is undefined in GLSL); the shader's form stays in "
                        "[R(0), 1].",
                        "water.fsh clamps cos to [0, 1] and takes the fifth power by "
                        "multiplication; the accumulated normal is the demo's mean of the two "
                        "layers (length <= 1), normalised with a floored inversesqrt only where a "
                        "unit normal is needed (exact Fresnel, sun glare)"));
    cases.push_back(Cpu("cpu_distortion_eye_distance_zero",
                        "Distortion scaling WaveDistortion / eye distance for distances down to 0: "
                        "the floored distance keeps the offset finite and bounded.",
                        "water.fsh floors the eye distance at 1e-3 and, since the demo's "
                        "WaveDistortion of 100 over 1e-3 overflows mediump, caps the factor at 16 "
                        "texture units"));
    cases.push_back(Cpu("cpu_fog_depth_extremes",
                        "Fog factors for maximum fog depths 0, 1e-30, 1e30 and infinite: the "
                        "reciprocal the renderer uploads stays in mediump range and the factor in "
                        "[0, 1] without 0 x Inf.",
                        "the renderer clamps fog reciprocals to [0, 65504] (mediump's largest) "
                        "before uploading them"));

    // ---- GL renders of every variant ----------------------------------------------------------
    const glm::vec3 far_target(-20.0F, 2.0F, -20.0F);
    cases.push_back(Gl("camera_on_water", "Camera exactly on the water plane (y = 0).",
                       Camera("", {80.0F, 0.0F, 60.0F}, far_target)));
    cases.push_back(Gl("camera_just_above", "Camera 1e-4 above the water.",
                       Camera("", {80.0F, 1e-4F, 60.0F}, far_target)));
    cases.push_back(Gl("camera_just_below",
                       "Camera 1e-4 below the water: the reflection clip plane faces the camera, "
                       "the oblique method's assumption breaks.",
                       Camera("", {80.0F, -1e-4F, 60.0F}, far_target),
                       "none needed: ObliqueNearPlane refuses and the pass clips with discard"));
    cases.push_back(Gl("camera_underwater_looking_up",
                       "Camera 10 below the water looking straight up at it.",
                       Camera("", {20.0F, -10.0F, 20.0F}, {20.0F, 60.0F, 20.0F}),
                       "LookAtWithFallbackUp (the view matrix was NaN)"));
    cases.push_back(Gl("oblique_band_above",
                       "Camera 1e-4 above the height where the mirrored camera meets the "
                       "reflection clip plane (clip offset 0.5): the oblique near plane passes "
                       "1e-4 from the camera.",
                       Camera("", {80.0F, kClipOffset + 1e-4F, 60.0F}, far_target)));
    cases.push_back(Gl("oblique_band_on",
                       "Camera exactly where the mirrored camera lies on the clip plane.",
                       Camera("", {80.0F, kClipOffset, 60.0F}, far_target),
                       "none needed: falls back to discard clipping"));
    cases.push_back(Gl("oblique_band_below", "Camera 1e-4 below that height.",
                       Camera("", {80.0F, kClipOffset - 1e-4F, 60.0F}, far_target)));
    cases.push_back(Gl("straight_down", "Looking straight down at the water from 60 up.",
                       Camera("", {20.0F, 60.0F, 20.0F}, {20.0F, 0.0F, 20.0F}),
                       "LookAtWithFallbackUp (the view matrix was NaN)"));
    cases.push_back(Gl("straight_up",
                       "Looking straight up from 5 above the water (no water "
                       "visible: the polygon is empty, only the main pass draws).",
                       Camera("", {20.0F, 5.0F, 20.0F}, {20.0F, 60.0F, 20.0F}),
                       "LookAtWithFallbackUp (the view matrix was NaN)"));
    cases.push_back(Gl("horizon",
                       "Looking exactly at the horizon from 10 up (the polygon's far "
                       "edge lies on the screen's centre line).",
                       Camera("", {80.0F, 10.0F, 60.0F}, {-20.0F, 10.0F, -20.0F})));
    cases.push_back(Gl("grazing_fresnel",
                       "Eye 0.05 above the water looking along it: cos(incidence) -> 0 over "
                       "most of the water, back-facing bump normals push it below 0.",
                       Camera("", {80.0F, 0.05F, 60.0F}, {-20.0F, 0.05F, -20.0F})));
    cases.push_back(Gl("eye_distance_zero",
                       "Near plane 1e-4 and eye 1e-3 above the water looking down at 45°: "
                       "fragments at eye distance ~1e-3 divide the distortion by it.",
                       Camera("", {30.0F, 1e-3F, 30.0F}, {20.0F, -10.0F, 20.0F}, 1e-4F, 2000.0F),
                       "water.fsh floors the eye distance at 1e-3 (existed) and scales the eye "
                       "vector before squaring"));
    HardCase fog_zero = Gl("fog_depth_zero",
                           "Maximum fog depth and distance 0 (reciprocals +Inf): 0 x Inf at the "
                           "water line.",
                           DefaultViews().front(),
                           "the renderer clamps the reciprocals to [0, 65504] before upload");
    fog_zero.settings.rcp_max_fog_depth = std::numeric_limits<float>::infinity();
    fog_zero.settings.rcp_max_fog_distance = std::numeric_limits<float>::infinity();
    cases.push_back(fog_zero);
    HardCase fog_huge = Gl("fog_depth_huge",
                           "Maximum fog depth and distance 1e30 "
                           "(reciprocals 1e-30, below fp16's smallest).",
                           DefaultViews().front());
    fog_huge.settings.rcp_max_fog_depth = 1e-30F;
    fog_huge.settings.rcp_max_fog_distance = 1e-30F;
    cases.push_back(fog_huge);
    HardCase wrapped =
            Gl("long_run_wrapped",
               "Animation time 1e6 s, translation wrapped to "
               "its fractional part (whitepaper 2.2).",
               DefaultViews().front(), "the translation is advanced in double before wrapping");
    wrapped.settings.animation_time = 1e6F;
    cases.push_back(wrapped);
    HardCase unwrapped = Gl("long_run_unwrapped",
                            "Animation time 1e6 s, translation not wrapped (~1.3e4 texture units "
                            "into the shader): finite on llvmpipe's fp32, but see the precision "
                            "table for what mediump hardware makes of it.",
                            DefaultViews().front());
    unwrapped.settings.animation_time = 1e6F;
    unwrapped.settings.wrap_bump_translation = false;
    cases.push_back(unwrapped);
    HardCase opaque = Gl("extinction_zero",
                         "Extinction and visibility 0 (the water opaque at once): 0/0 at the "
                         "water line in ENABLE_EXTINCTION.",
                         DefaultViews().front(),
                         "water.fsh floors both divisors at 1e-3 (the CPU reference already "
                         "treated 0 as opaque)");
    opaque.settings.extinction.extinction = glm::vec3(0.0F);
    opaque.settings.extinction.visibility = 0.0F;
    cases.push_back(opaque);
    HardCase deep = Gl("max_water_depth_huge",
                       "MaxWaterDepth 1e6, past mediump's 65504: Inf x 0 at the water line on "
                       "fp16 hardware (llvmpipe runs mediump at fp32; the precision study "
                       "emulates fp16).",
                       DefaultViews().front(),
                       "the renderer clamps it to [0.5, 3000] on upload (MediumpMaxWaterDepth)");
    deep.settings.max_water_depth = 1e6F;
    cases.push_back(deep);
    CameraView far_view = DefaultViews().front();
    far_view.far_plane = 1e6F;
    cases.push_back(Gl("far_plane_1e6",
                       "The default view with the far plane at 1e6 (the water "
                       "polygon reaches a million units; 24-bit depth).",
                       far_view));
    HardCase tiny_reflection =
            Gl("reflection_1x1", "1x1 reflection and refraction textures.", DefaultViews().front());
    tiny_reflection.reflection_size = 1;
    cases.push_back(tiny_reflection);
    HardCase odd = Gl("odd_window_61x37",
                      "A 61x37 window (odd sizes, non-power-of-two, "
                      "aspect 1.65).",
                      DefaultViews().front());
    odd.fixed_size = true;
    odd.settings.width = 61;
    odd.settings.height = 37;
    cases.push_back(odd);
    HardCase pixel = Gl("window_1x1", "A 1x1 window (RcpWindowSize = 1, one fragment).",
                        DefaultViews().front());
    pixel.fixed_size = true;
    pixel.settings.width = 1;
    pixel.settings.height = 1;
    cases.push_back(pixel);
    return cases;
}

const HardCase* FindHardCase(const std::vector<HardCase>& cases, std::string_view name) {
    const auto found = std::find_if(cases.begin(), cases.end(),
                                    [&](const HardCase& c) { return c.name == name; });
    return found == cases.end() ? nullptr : &*found;
}

}  // namespace tidepool::lab
