// One frame of the water renderer as data: its passes, each pass's target, clip method and
// clear, and every draw with the program it uses. WaterRenderer::RenderFrame executes exactly
// this plan, and it needs no GL context, so tests can check that the two arms of a whitepaper
// comparison differ only in what the whitepaper changed (tests/unit/FramePlanTest.cpp).
#pragma once

#include "tidepool/VariantExpander.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tidepool::runner {

/// Upper bound on water polygon vertices: a plane cuts a frustum (6 faces) in at most 6 corners.
inline constexpr int kMaxWaterPolygonVertices = 8;

/// The render passes of a frame, in the order they are drawn.
enum class PassKind { kReflection, kRefraction, kLowResWater, kMain };

/// "reflection", "refraction", "low_res_water" or "main". Never fails.
const char* PassName(PassKind kind);

/// Everything one pass needs, computed on the CPU before any GL call.
struct PassPlan {
    PassKind kind = PassKind::kMain;
    int width = 0;  // the target's size in pixels
    int height = 0;
    glm::mat4 view{1.0F};
    glm::mat4 projection{1.0F};
    bool mirrored = false;       // front faces flip (glFrontFace(GL_CW))
    bool clip_discard = false;   // models clip with CLIP_DISCARD instead of the projection
    bool clip_oblique = false;   // the projection's near plane is the clip plane
    glm::vec4 clip_plane{0.0F};  // world space, kept side >= 0
    glm::vec4 clear_colour{0.0F, 0.0F, 0.0F, 1.0F};
    bool draw_sky = false;
    Variant sky_program;      // skybox variant, when draw_sky
    std::vector<int> meshes;  // -1 is the terrain, k >= 0 is scene.objects[k]
    Variant model_program;    // model variant, when meshes is not empty
    bool draw_water = false;
    Variant water_program;  // the configuration's, or water_composite applying low-res
};

/// A whole frame.
struct FramePlan {
    glm::mat4 view_projection{1.0F};
    glm::vec3 eye{0.0F};
    std::vector<glm::vec3> polygon;  // the water polygon ("infinite plane")
    glm::vec2 bump_translation0{0.0F};
    glm::vec2 bump_translation1{0.0F};
    // The WaveDistortion uniform: texture units of lookup offset per unit of bump normal, to be
    // divided by the eye distance under ENABLE_SCALE_DISTORTION (DistortionConstant).
    float wave_distortion = 0.0F;
    std::vector<PassPlan> passes;
    bool oblique_fallback = false;  // the oblique near plane was impossible; discard clipped
};

/// The frame `configuration` renders from `view` over `scene` with `settings`. Never fails: a
/// view that sees no water plans the main pass alone.
FramePlan PlanFrame(const RenderConfiguration& configuration, const RenderSettings& settings,
                    const Scene& scene, const CameraView& view);

/// The helper programs (skybox, model, water_composite variants) `configuration`'s passes draw
/// with its own clip method (the oblique fallback's discard variants are compiled when first
/// used). Never fails.
std::vector<Variant> HelperPrograms(const RenderConfiguration& configuration);

/// The WaveDistortion uniform of `configuration`: settings.wave_distortion (the demo's 100) when
/// ENABLE_SCALE_DISTORTION divides it by the eye distance; otherwise that divided by the
/// distance at which the view's centre ray meets the water (TypicalWaterDistance), so both arms
/// of whitepaper row 6 give the same offset there. Never fails.
float DistortionConstant(const RenderConfiguration& configuration, const RenderSettings& settings,
                         const Scene& scene, const CameraView& view);

/// The distance from the eye to where the view's centre ray meets the water plane, or the far
/// plane when it misses (looking up, or the water beyond the far plane). Never fails.
float TypicalWaterDistance(const CameraView& view, float water_height);

/// The low-resolution water texture's size: settings.low_res_water_size, or DemoTargetSize of the
/// window when that is 0. Never fails.
int LowResWaterSize(const RenderSettings& settings);

/// The planar reflection (a reflection pass) unless the configuration reflects the sky
/// direction (REFLECTION_CUBEMAP, REFLECTION_FOURIER). Never fails.
bool UsesPlanarReflection(const RenderConfiguration& configuration);

}  // namespace tidepool::runner
