// The frame plan of the water renderer: which passes, targets, clips and draws a configuration
// asks for. No GL here; runner/src/gl/WaterRenderer.cpp executes the plan.
#include "tidepool/runner/FramePlan.h"

#include "tidepool/runner/ShaderFeatures.h"
#include "tidepool/runner/WaterMath.h"

#include <algorithm>
#include <cmath>

namespace tidepool::runner {
namespace {

// The depth-based optics read the water depth the refraction pass stores in alpha.
bool NeedsWaterDepth(const RenderConfiguration& c) {
    return c.Has(ShaderFeature::kRefraction) &&
           (c.Has(ShaderFeature::kExtinction) || c.Has(ShaderFeature::kShoreFoam) ||
            c.Has(ShaderFeature::kSoftShore));
}

// The underwater depth fog of the refraction pass's models (whitepaper 2.4.1). Extinction
// replaces it: the same effect, done per channel in the water shader from the depth in alpha.
bool UsesDepthFog(const RenderConfiguration& c) {
    return c.Has(ShaderFeature::kFog) && c.passes.depth_fog && !c.Has(ShaderFeature::kExtinction);
}

// The sky is drawn as the demo drew it, never clipped by discard: the mirrored sky below the
// water plane is never sampled by an undistorted lookup, and the discard arm of row 10 must
// differ from the oblique arm in the models' clipping only.
Variant SkyProgram(const RenderConfiguration& c) {
    return MakeVariant("skybox", c.Has(ShaderFeature::kFog) ? DefineNames({ShaderFeature::kFog})
                                                            : std::vector<std::string>{});
}

Variant ModelProgram(const RenderConfiguration& c, PassKind kind, bool discard) {
    std::vector<std::string> defines = DefineNames({ShaderFeature::kLighting});
    if (kind == PassKind::kRefraction && UsesDepthFog(c)) {
        defines.emplace_back(DefineName(ShaderFeature::kFogDepth));
    }
    if (kind == PassKind::kRefraction && NeedsWaterDepth(c)) {
        defines.emplace_back(DefineName(ShaderFeature::kDepthAlpha));
    }
    if (discard && (kind == PassKind::kReflection || kind == PassKind::kRefraction)) {
        defines.emplace_back(DefineName(ShaderFeature::kClipDiscard));
    }
    return MakeVariant("model", defines);
}

}  // namespace

const char* PassName(PassKind kind) {
    switch (kind) {
        case PassKind::kReflection:
            return "reflection";
        case PassKind::kRefraction:
            return "refraction";
        case PassKind::kLowResWater:
            return "low_res_water";
        case PassKind::kMain:
            return "main";
    }
    return "?";
}

int LowResWaterSize(const RenderSettings& settings) {
    return settings.low_res_water_size > 0 ? settings.low_res_water_size
                                           : DemoTargetSize(settings.width, settings.height);
}

bool UsesPlanarReflection(const RenderConfiguration& c) {
    return !c.Has(ShaderFeature::kReflectionCubemap) && !c.Has(ShaderFeature::kReflectionFourier);
}

float TypicalWaterDistance(const CameraView& view, float water_height) {
    const glm::vec3 direction = view.target - view.eye;
    const float length = glm::length(direction);
    const float rise = view.eye.y - water_height;
    // The ray meets the plane only going down towards it (or up from below).
    if (!(length > 0.0F) || direction.y * rise >= 0.0F) {
        return view.far_plane;
    }
    const float distance = length * rise / -direction.y;
    return std::isfinite(distance) && distance < view.far_plane ? distance : view.far_plane;
}

float DistortionConstant(const RenderConfiguration& c, const RenderSettings& settings,
                         const Scene& scene, const CameraView& view) {
    if (c.Has(ShaderFeature::kScaleDistortion)) {
        return settings.wave_distortion;
    }
    // The near plane keeps the divisor positive for an eye on the water looking at it.
    const float distance = std::max(TypicalWaterDistance(view, scene.water_height),
                                    std::max(view.near_plane, 1.0F));
    return settings.wave_distortion / distance;
}

std::vector<Variant> HelperPrograms(const RenderConfiguration& c) {
    std::vector<Variant> helpers;
    const bool discard = c.passes.clip == "discard";
    for (PassKind kind : {PassKind::kReflection, PassKind::kRefraction, PassKind::kMain}) {
        if ((kind == PassKind::kRefraction && !c.Has(ShaderFeature::kRefraction)) ||
            (kind == PassKind::kReflection && !UsesPlanarReflection(c))) {
            continue;
        }
        helpers.push_back(SkyProgram(c));
        helpers.push_back(ModelProgram(c, kind, discard));
    }
    if (c.passes.low_res_water) {
        helpers.push_back(MakeVariant("water_composite", {}));
    }
    return helpers;
}

FramePlan PlanFrame(const RenderConfiguration& c, const RenderSettings& settings,
                    const Scene& scene, const CameraView& view) {
    FramePlan plan;
    const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    // Not ViewMatrix(view): that is NaN for a view straight down or up (hard cases
    // "straight_down", "straight_up"); elsewhere the two are the same matrix.
    const glm::mat4 view_matrix = LookAtWithFallbackUp(view.eye, view.target);
    const glm::mat4 projection = ProjectionMatrix(view, aspect);
    const float h = scene.water_height;
    const glm::vec4 water_plane(0.0F, 1.0F, 0.0F, -h);
    plan.view_projection = projection * view_matrix;
    plan.eye = view.eye;
    plan.polygon = InfinitePlanePolygon(plan.view_projection, water_plane);
    if (plan.polygon.size() > static_cast<std::size_t>(kMaxWaterPolygonVertices)) {
        // Cannot happen for a convex cut of a frustum.
        plan.polygon.resize(kMaxWaterPolygonVertices);
    }
    // In double, then rounded: velocity × 10^6 s in float keeps only ~3 fractional bits of the
    // wrapped translation (hard case "long_run_wrapped"); double keeps it to 1e-10.
    plan.bump_translation0 = glm::vec2(AdvanceBumpTranslation(
            glm::dvec2(0.0), glm::dvec2(settings.bump_velocity0),
            static_cast<double>(settings.animation_time), settings.wrap_bump_translation));
    plan.bump_translation1 = glm::vec2(AdvanceBumpTranslation(
            glm::dvec2(0.0), glm::dvec2(settings.bump_velocity1),
            static_cast<double>(settings.animation_time), settings.wrap_bump_translation));
    plan.wave_distortion = DistortionConstant(c, settings, scene, view);
    const bool water_visible = !plan.polygon.empty();
    const bool fog = c.Has(ShaderFeature::kFog);
    const bool discard = c.passes.clip == "discard";
    const bool culling = c.passes.culling;
    const int object_count = static_cast<int>(scene.objects.size());
    auto mesh_of = [&](int index) -> const Mesh& {
        return index < 0 ? scene.terrain : scene.objects[static_cast<std::size_t>(index)];
    };

    // Clips with the oblique near plane, or falls back to discard when the camera is on the kept
    // side (ObliqueNearPlane refuses then).
    auto clip = [&](PassPlan* pass) {
        if (!discard) {
            const ObliqueProjection<float> oblique =
                    ObliqueNearPlane(projection, TransformPlane(pass->view, pass->clip_plane));
            pass->projection = oblique.projection;
            pass->clip_oblique = oblique.applied;
            plan.oblique_fallback = plan.oblique_fallback || !oblique.applied;
        }
        pass->clip_discard = !pass->clip_oblique;
        pass->model_program = ModelProgram(c, pass->kind, pass->clip_discard);
    };

    if (water_visible && UsesPlanarReflection(c)) {
        PassPlan mirror;
        mirror.kind = PassKind::kReflection;
        mirror.width = mirror.height = ReflectionSize(c.passes, settings.width, settings.height);
        mirror.view = view_matrix * MirrorMatrix(water_plane);
        mirror.projection = projection;
        mirror.mirrored = true;
        // Keep what is above the plane, moved down by the offset (whitepaper 3.3.4).
        mirror.clip_plane = glm::vec4(0.0F, 1.0F, 0.0F, -(h - settings.clip_plane_offset));
        clip(&mirror);
        mirror.draw_sky = true;
        mirror.sky_program = SkyProgram(c);
        for (int i = -1; i < object_count; ++i) {
            if (culling && IsEntirelyBelow(mesh_of(i), h - settings.clip_plane_offset)) {
                continue;
            }
            mirror.meshes.push_back(i);
        }
        plan.passes.push_back(std::move(mirror));
    }
    if (water_visible && c.Has(ShaderFeature::kRefraction)) {
        PassPlan pass;
        pass.kind = PassKind::kRefraction;
        pass.width = pass.height = RefractionSize(c.passes, settings.width, settings.height);
        pass.view = view_matrix;
        pass.projection = projection;
        // Keep what is below the plane, moved up by the offset.
        pass.clip_plane = glm::vec4(0.0F, -1.0F, 0.0F, h + settings.clip_plane_offset);
        clip(&pass);
        // With fog the water colour hides the distance, so the sky is left out (whitepaper).
        pass.draw_sky = !fog;
        if (pass.draw_sky) {
            pass.sky_program = SkyProgram(c);
        }
        pass.clear_colour = fog ? glm::vec4(settings.underwater_colour, 1.0F)
                                : glm::vec4(0.0F, 0.0F, 0.0F, 1.0F);
        // The depth fog hides what lies deeper than its maximum, so the CPU can skip it
        // (whitepaper 2.4.1); without the depth fog everything below the water may show.
        const bool depth_cull = UsesDepthFog(c);
        const float max_depth = 1.0F / MediumpFogReciprocal(settings.rcp_max_fog_depth);
        for (int i = -1; i < object_count; ++i) {
            const Mesh& mesh = mesh_of(i);
            if (culling && (IsEntirelyAbove(mesh, h + settings.clip_plane_offset) ||
                            (depth_cull && !IntersectsDepthBand(mesh, h, max_depth)))) {
                continue;
            }
            pass.meshes.push_back(i);
        }
        plan.passes.push_back(std::move(pass));
    }
    PassPlan main_pass;
    main_pass.kind = PassKind::kMain;
    main_pass.width = settings.width;
    main_pass.height = settings.height;
    main_pass.view = view_matrix;
    main_pass.projection = projection;
    main_pass.draw_sky = true;
    main_pass.sky_program = SkyProgram(c);
    main_pass.model_program = ModelProgram(c, PassKind::kMain, false);
    for (int i = -1; i < object_count; ++i) {
        main_pass.meshes.push_back(i);
    }
    main_pass.draw_water = water_visible;
    main_pass.water_program = c.variant;
    if (water_visible && c.passes.low_res_water) {
        // The same water work at lower resolution (whitepaper 3.3.3): the ground that hides
        // water is drawn first with depth, as the demo drew its terrain, with the main pass's
        // shader so its edges match; the boat and other objects are left out as the demo left
        // its boat. Cleared to the fog colour, which is what the fogged water reaches at the far
        // plane, so bilinear fetches across the horizon bring in no foreign colour.
        PassPlan pass;
        pass.kind = PassKind::kLowResWater;
        pass.width = pass.height = LowResWaterSize(settings);
        pass.view = view_matrix;
        pass.projection = projection;
        pass.clear_colour =
                fog ? glm::vec4(settings.fog_colour, 1.0F) : glm::vec4(0.0F, 0.0F, 0.0F, 0.0F);
        pass.meshes.push_back(-1);
        pass.model_program = main_pass.model_program;
        pass.draw_water = true;
        pass.water_program = c.variant;
        plan.passes.push_back(std::move(pass));
        main_pass.water_program = MakeVariant("water_composite", {});
    }
    plan.passes.push_back(std::move(main_pass));
    return plan;
}

}  // namespace tidepool::runner
