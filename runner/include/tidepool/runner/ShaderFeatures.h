// The shader features the renderer, the frame plan, the scene planner and the stability run
// switch, named once: each feature's #define, the programs of variants.yaml that declare it and
// what it does. Code names a feature through ShaderFeature; its define name is written only in
// this table. The shaders test the same defines in GLSL (shaders/*.vsh, *.fsh) and variants.yaml
// declares them with the rules between them; tests/unit/ShaderFeaturesTest.cpp checks every
// entry against the shipped variants.yaml, so the table and the file cannot drift apart.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::runner {

/// A #define that C++ code switches on or tests, in the order of kShaderFeatures.
enum class ShaderFeature {
    // The water program's features, the whitepaper's first (water_uniform reads these as bools).
    kDistortion,
    kScaleDistortion,
    kRefraction,
    kFresnel,
    kFresnelExact,
    kNormaliseCubemap,
    kWaterColour,
    kAlphaBlend,
    kFog,
    // The depth-based optics (seeds/003).
    kExtinction,
    kShoreFoam,
    kSoftShore,
    kSunSpecular,
    // The values of the water's REFLECTION axis that add a define (planar, the default, adds none).
    kReflectionCubemap,
    kReflectionFourier,
    // The helper programs' defines, which the frame plan sets per pass.
    kLighting,
    kFogDepth,
    kDepthAlpha,
    kClipDiscard,
};

/// One row of the feature table.
struct ShaderFeatureInfo {
    ShaderFeature feature;
    std::string_view define;  // the #define name, as variants.yaml and the shaders spell it
    // The programs of variants.yaml that declare it (a feature or an axis value); "" pads.
    std::array<std::string_view, 2> programs;
    bool uniform_bool;  // water_uniform reads it as a uniform bool (UniformBoolName)
    std::string_view what;
};

/// Every feature, in enumerator order (ShaderFeatureInfoOf indexes it by the enumerator).
// Not clang-formatted: one row per feature with its columns aligned reads as the table it is.
// clang-format off
inline constexpr std::array<ShaderFeatureInfo, 19> kShaderFeatures = {{
    {ShaderFeature::kDistortion,        "ENABLE_DISTORTION",       {"water", ""},       true,
     "two animated bump layers perturb the screen-space lookup"},
    {ShaderFeature::kScaleDistortion,   "ENABLE_SCALE_DISTORTION", {"water", ""},       true,
     "the distortion is divided by the eye distance"},
    {ShaderFeature::kRefraction,        "ENABLE_REFRACTION",       {"water", ""},       true,
     "a refraction pass, mixed with the reflection by a constant"},
    {ShaderFeature::kFresnel,           "ENABLE_FRESNEL",          {"water", ""},       true,
     "Schlick's Fresnel term mixes reflection and refraction instead of the constant"},
    {ShaderFeature::kFresnelExact,      "FRESNEL_EXACT",           {"water", ""},       true,
     "the full dielectric Fresnel equations: the accuracy reference"},
    {ShaderFeature::kNormaliseCubemap,  "NORMALISE_CUBEMAP",       {"water", ""},       true,
     "the eye vector is normalised by a cube-map lookup"},
    {ShaderFeature::kWaterColour,       "ENABLE_WATER_COLOUR",     {"water", ""},       true,
     "the reflection is mixed with a constant water colour"},
    {ShaderFeature::kAlphaBlend,        "ENABLE_ALPHA_BLEND",      {"water", ""},       true,
     "the water is blended over the scene below"},
    {ShaderFeature::kFog,               "ENABLE_FOG",              {"water", "skybox"}, true,
     "distance fog on the water and the sky (and the underwater depth fog of the models)"},
    {ShaderFeature::kExtinction,        "ENABLE_EXTINCTION",       {"water", ""},       false,
     "per-channel colour extinction with depth and horizontal visibility"},
    {ShaderFeature::kShoreFoam,         "ENABLE_SHORE_FOAM",       {"water", ""},       false,
     "foam in shallow water"},
    {ShaderFeature::kSoftShore,         "ENABLE_SOFT_SHORE",       {"water", ""},       false,
     "the water blends back to the refraction at the shore"},
    {ShaderFeature::kSunSpecular,       "ENABLE_SUN_SPECULAR",     {"water", ""},       false,
     "the sun's glare, weighted by 1 - Fresnel"},
    {ShaderFeature::kReflectionCubemap, "REFLECTION_CUBEMAP",      {"water", ""},       false,
     "the view ray reflected into the sky cube map instead of a reflection pass"},
    {ShaderFeature::kReflectionFourier, "REFLECTION_FOURIER",      {"water", ""},       false,
     "sky and terrain from per-vertex Fourier coefficients instead of a reflection pass"},
    {ShaderFeature::kLighting,          "ENABLE_LIGHTING",         {"model", ""},       false,
     "per-vertex sun lighting of the terrain and objects"},
    {ShaderFeature::kFogDepth,          "ENABLE_FOG_DEPTH",        {"model", ""},       false,
     "underwater depth fog on the models of the refraction pass"},
    {ShaderFeature::kDepthAlpha,        "ENABLE_DEPTH_ALPHA",      {"model", ""},       false,
     "the refraction pass stores the water depth in alpha for the depth optics"},
    {ShaderFeature::kClipDiscard,       "CLIP_DISCARD",            {"skybox", "model"}, false,
     "clip by discard instead of the oblique projection"},
}};
// clang-format on

/// The table row of `feature`. Never fails: every enumerator has its row.
constexpr const ShaderFeatureInfo& ShaderFeatureInfoOf(ShaderFeature feature) {
    return kShaderFeatures[static_cast<std::size_t>(feature)];
}

/// The #define name of `feature`, e.g. "ENABLE_FOG". Never fails.
constexpr std::string_view DefineName(ShaderFeature feature) {
    return ShaderFeatureInfoOf(feature).define;
}

/// The feature whose #define is `define`; nullopt for a name not in the table.
std::optional<ShaderFeature> FeatureFromDefine(std::string_view define);

/// The define names of `features`, in the order given. Never fails.
std::vector<std::string> DefineNames(std::initializer_list<ShaderFeature> features);

namespace detail {
constexpr bool RowsFollowTheEnumerators() {
    for (std::size_t i = 0; i < kShaderFeatures.size(); ++i) {
        if (static_cast<std::size_t>(kShaderFeatures[i].feature) != i) {
            return false;
        }
    }
    return true;
}
}  // namespace detail
static_assert(detail::RowsFollowTheEnumerators(),
              "kShaderFeatures must list its rows in the order of ShaderFeature");
static_assert(kShaderFeatures.size() == static_cast<std::size_t>(ShaderFeature::kClipDiscard) + 1,
              "every ShaderFeature needs a row in kShaderFeatures");

}  // namespace tidepool::runner
