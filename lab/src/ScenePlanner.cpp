// The scene planner. Rules only propose: every candidate is rendered and timed, and the choice
// is made on the measurements, so a rule that guesses wrong costs time, never quality.
#include "tidepool/lab/ScenePlanner.h"

#include "tidepool/GlslValidator.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/runner/FramePlan.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/ShaderFeatures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include <fmt/format.h>

namespace tidepool::lab {
namespace {

// The longest candidate list: the budget for a short search, which keeps a plan at the
// default size under a minute on two llvmpipe threads.
constexpr std::size_t kMaxCandidates = 12;

// Below this wave strength the distortion moves the reflection by less than a pixel or so at
// the default 25 px per unit of bump normal; the rules then propose flat water.
constexpr float kCalmWaves = 0.2F;

// From this eye height (world units) the view looks down steeply on most of the water, where
// the Fresnel term is nearly constant, so a constant mix is worth trying.
constexpr float kHighCamera = 100.0F;

// The rules' guess at whether the floor shows: a floor deeper than the fog depth is hidden.
bool FloorVisible(const SceneDescription& scene) {
    return scene.below_terrain && scene.water_depth < scene.fog_depth;
}

// Anything below the water in sight: the floor, or submerged objects within the fog depth
// (the rocks lie a few units down).
bool BelowVisible(const SceneDescription& scene) {
    return FloorVisible(scene) || scene.below_objects;
}

std::vector<std::string> Without(std::vector<std::string> defines,
                                 std::initializer_list<ShaderFeature> drop) {
    for (ShaderFeature feature : drop) {
        defines.erase(std::remove(defines.begin(), defines.end(), DefineName(feature)),
                      defines.end());
    }
    return defines;
}

std::vector<std::string> With(std::vector<std::string> defines,
                              std::initializer_list<ShaderFeature> add) {
    for (ShaderFeature feature : add) {
        if (std::find(defines.begin(), defines.end(), DefineName(feature)) == defines.end()) {
            defines.emplace_back(DefineName(feature));
        }
    }
    return defines;
}

// Without the Fresnel term and the two features that refine it (variants.yaml's rules: both
// require ENABLE_FRESNEL).
std::vector<std::string> WithoutFresnel(std::vector<std::string> defines) {
    using enum ShaderFeature;
    return Without(std::move(defines), {kFresnel, kNormaliseCubemap, kFresnelExact});
}

// Without refraction and the Fresnel mix that needs it (variants.yaml: Fresnel mixes reflection
// with refraction).
std::vector<std::string> WithoutRefraction(std::vector<std::string> defines) {
    return WithoutFresnel(Without(std::move(defines), {ShaderFeature::kRefraction}));
}

// Flat water: without the distortion and its scaling.
std::vector<std::string> WithoutDistortion(std::vector<std::string> defines) {
    using enum ShaderFeature;
    return Without(std::move(defines), {kDistortion, kScaleDistortion});
}

bool MeetsQuality(const QualityTarget& target, const ImageError& error) {
    if (target.min_psnr_db && error.psnr_db < *target.min_psnr_db) {
        return false;
    }
    if (target.max_share_visible && error.share_visible > *target.max_share_visible) {
        return false;
    }
    return true;
}

// The settings a description moves: fog depth, wave strength and view range.
RenderSettings SceneSettings(const SceneDescription& scene, RenderSettings settings) {
    settings.rcp_max_fog_depth = 1.0F / scene.fog_depth;
    // Wave strength 1 is the renderer's default distortion.
    settings.wave_distortion *= scene.wave_strength;
    settings.rcp_max_fog_distance = 1.0F / scene.camera.view_range;
    return settings;
}

// Schlick's reflectance of water (n = 1.33, so R0 = ((n - 1) / (n + 1))^2 = 0.02) where the
// view's centre ray meets the water: how much of the reflection the full effect shows there.
float CentreReflectance(const SceneDescription& scene) {
    constexpr float kR0 = 0.02F;
    const float height = scene.camera.height;
    const float slant = std::sqrt(height * height + scene.camera.distance * scene.camera.distance);
    const float cosine = height / slant;
    return kR0 + (1.0F - kR0) * std::pow(1.0F - cosine, 5.0F);
}

// Fills `candidate` with a `water` variant and its passes; false when a define is not declared
// by the program or the combination breaks one of its rules.
bool MakeCandidate(const ProgramConfig& water, const SceneDescription& scene,
                   std::vector<std::string> defines, const PassOptions& passes,
                   PlanCandidate* candidate) {
    const std::vector<std::string> declared = water.AllDefines();
    for (const std::string& d : defines) {
        if (std::find(declared.begin(), declared.end(), d) == declared.end()) {
            return false;
        }
    }
    const Variant variant = MakeVariant(std::string(kWaterProgram), std::move(defines));
    if (FirstBrokenRule(water, variant.defines) != nullptr) {
        return false;
    }
    candidate->configuration.variant = variant;
    candidate->configuration.effects = variant.defines;
    candidate->configuration.passes = passes;
    candidate->configuration.id = ConfigurationId(variant, passes);
    if (candidate->configuration.Has(ShaderFeature::kWaterColour)) {
        candidate->water_colour_alpha = 1.0F - CentreReflectance(scene);
    }
    return true;
}

// Half the reflection texture of `passes` in the settings' window.
int HalfReflectionSize(const PassOptions& passes, const RenderSettings& settings) {
    return std::max(1, ReflectionSize(passes, settings.width, settings.height) / 2);
}

// Applies the drop of `effect` (a PlanCandidate::drops name) to a configuration rendered with
// `settings`.
void ApplyDrop(const std::string& effect, const RenderSettings& settings,
               std::vector<std::string>* defines, PassOptions* passes) {
    using enum ShaderFeature;
    if (effect == "refraction") {
        *defines = With(WithoutRefraction(*defines), {kWaterColour});
    } else if (effect == "fresnel") {
        *defines = WithoutFresnel(*defines);
    } else if (effect == "distortion") {
        *defines = WithoutDistortion(*defines);
    } else if (effect == "distortion_scaling") {
        *defines = Without(*defines, {kScaleDistortion});
    } else if (effect == "fog") {
        *defines = Without(*defines, {kFog});
    } else if (effect == "planar_reflection") {
        *defines = With(Without(*defines, {kReflectionFourier}), {kReflectionCubemap});
    } else if (effect == "reflection_resolution") {
        passes->reflection_size = HalfReflectionSize(*passes, settings);
    } else if (effect == "full_resolution_water") {
        passes->low_res_water = true;
    }
}

// True when `chosen` still has `effect` (a name of PlanCandidate::drops) that `full` has, both
// rendered with `settings`.
bool Keeps(const RenderConfiguration& chosen, const RenderConfiguration& full,
           const std::string& effect, const RenderSettings& settings) {
    using enum ShaderFeature;
    if (effect == "refraction") {
        return chosen.Has(kRefraction);
    }
    if (effect == "fresnel") {
        return chosen.Has(kFresnel);
    }
    if (effect == "distortion") {
        return chosen.Has(kDistortion);
    }
    if (effect == "distortion_scaling") {
        return chosen.Has(kScaleDistortion);
    }
    if (effect == "fog") {
        return chosen.Has(kFog);
    }
    if (effect == "planar_reflection") {
        return UsesPlanarReflection(chosen);
    }
    if (effect == "reflection_resolution") {
        return ReflectionSize(chosen.passes, settings.width, settings.height) >=
               ReflectionSize(full.passes, settings.width, settings.height);
    }
    if (effect == "full_resolution_water") {
        return !chosen.passes.low_res_water;
    }
    return true;
}

// "+2.5" or "\u22122.5" (the minus sign the report writes), to one decimal; a value that rounds
// to zero reads "+0.0".
std::string SignedText(double value) {
    const double rounded = std::round(value * 10.0) / 10.0;
    return fmt::format("{}{:.1f}", rounded < 0 ? "\u2212" : "+", std::fabs(rounded));
}

// A candidate's frame-time change vs full as a plan's reasons quote it: the estimate with its 95%
// interval and the pairs behind them, so that a coarse figure (a candidate that misses the
// target is timed for the fewest pairs, CandidateRule) reads as coarse, and a change its
// interval does not separate from none is not read as a saving.
std::string TimeChangeText(const PlanCandidate& c) {
    return fmt::format("{}% [{}, {}] over {} pairs", SignedText(c.time_change_percent),
                       SignedText(c.time_change_low), SignedText(c.time_change_high), c.pairs);
}

}  // namespace

std::vector<PlanCandidate> ProposeCandidates(const VariantConfig& config,
                                             const SceneDescription& scene,
                                             const std::string& full_preset,
                                             const RenderSettings& settings,
                                             std::vector<Diagnostic>* diagnostics) {
    std::vector<PlanCandidate> candidates;
    const Preset* full = config.FindPreset(full_preset);
    if (full == nullptr || full->program != kWaterProgram) {
        diagnostics->push_back(MakeError(
                config.path, 0, 0,
                fmt::format("the full-effect preset '{}' is missing or not a `water` preset; the "
                            "planner measures every candidate against it",
                            full_preset)));
        return candidates;
    }
    const ProgramConfig* water = config.FindProgram(kWaterProgram);
    std::set<std::string> seen;
    auto add = [&](std::vector<std::string> defines, PassOptions passes, std::string because,
                   std::string drops) {
        // One place is left for the combination PlanScene measures after these.
        if (candidates.size() + 1 >= kMaxCandidates || water == nullptr) {
            return;
        }
        PlanCandidate c;
        if (!MakeCandidate(*water, scene, std::move(defines), passes, &c) ||
            !seen.insert(c.configuration.id).second) {
            return;
        }
        c.proposed_because = std::move(because);
        c.drops = std::move(drops);
        candidates.push_back(std::move(c));
    };
    // The scene's reference: every effect of the preset the description does not turn off;
    // mirror-calm water (waves 0) has no distortion to show, and its bump normals would only
    // add Fresnel sparkle the scene does not have.
    using enum ShaderFeature;
    std::vector<std::string> f = full->defines;
    if (scene.wave_strength <= 0.0F) {
        f = WithoutDistortion(f);
    }
    const PassOptions p = full->passes;
    PassOptions refl128 = p;
    refl128.reflection_size = HalfReflectionSize(p, settings);
    PassOptions low_res = p;
    low_res.low_res_water = true;

    add(f, p,
        fmt::format("the full effect (preset {}{}): the reference", full_preset,
                    scene.wave_strength <= 0.0F ? " without distortion: the water is calm" : ""),
        "");
    // Each effect dropped alone, so every drop in the plan has its own measurement.
    const bool below = BelowVisible(scene);
    add(With(WithoutRefraction(f), {kWaterColour}), p,
        below ? "refraction replaced by the water colour (the rules expect it to show)"
              : "refraction replaced by the water colour: nothing below the water is in sight",
        "refraction");
    add(WithoutFresnel(f), p, "a constant reflection/refraction mix instead of Fresnel", "fresnel");
    add(WithoutDistortion(f), p,
        scene.wave_strength <= kCalmWaves ? "flat water: the waves are calm"
                                          : "flat water (the rules expect the waves to show)",
        "distortion");
    add(Without(f, {kScaleDistortion}), p, "distortion not scaled by distance",
        "distortion_scaling");
    add(Without(f, {kFog}), p, "no distance fog", "fog");
    const bool only_sky_above = !scene.above_terrain && !scene.above_objects;
    add(With(f, {kReflectionCubemap}), p,
        only_sky_above ? "the sky cube map instead of a reflection pass: only sky is above"
                       : "the sky cube map instead of a reflection pass (the rules expect the "
                         "island and objects to show in the reflection)",
        "planar_reflection");
    add(f, refl128, "a reflection texture of half the size", "reflection_resolution");
    add(f, low_res, "the water rendered at low resolution", "full_resolution_water");

    // Combinations the scene's properties suggest.
    const std::vector<std::string> colour = With(WithoutRefraction(f), {kWaterColour});
    if (!below) {
        add(colour, refl128, "no refraction and a half-size reflection: nothing below shows", "");
    }
    if (scene.wave_strength <= kCalmWaves) {
        add(WithoutDistortion(colour), p, "no refraction, flat water", "");
        add(WithoutDistortion(f), refl128, "flat water with a half-size reflection", "");
    }
    if (scene.camera.height >= kHighCamera) {
        add(WithoutDistortion(WithoutFresnel(f)), p,
            "seen from high up: constant mix, waves too small to see", "");
    }
    if (only_sky_above && !below) {
        add(With(colour, {kReflectionCubemap}), p,
            "only sky above and nothing below: the sky cube map, no refraction", "");
    }
    if (!scene.above_terrain) {
        add(colour, refl128, "only sky above: the reflection is the smooth sky", "");
        add(WithoutDistortion(colour), refl128, "only sky above, flat water", "");
    }
    if (!below) {
        add(With(WithoutRefraction(f), {kAlphaBlend}), p,
            "the scene below blended instead of a refraction pass", "");
    }
    add(Without(WithoutFresnel(f), {kScaleDistortion}), refl128,
        "constant mix, unscaled distortion, half-size reflection", "");
    return candidates;
}

base::StoppingRule CandidateRule(const base::StoppingRule& rule, bool misses_target) {
    base::StoppingRule out = rule;
    if (misses_target) {
        out.max_pairs = std::min(rule.max_pairs, rule.min_pairs);
        out.contended_share = 0;
    }
    return out;
}

CandidateChoice ChooseCandidate(const std::vector<CandidateMeasure>& candidates,
                                bool quality_bounds, std::optional<double> frame_budget_ms,
                                double tie_points) {
    CandidateChoice choice;
    auto at = [&](int i) -> const CandidateMeasure& {
        return candidates[static_cast<std::size_t>(i)];
    };
    const int count = static_cast<int>(candidates.size());
    if (quality_bounds) {
        // Faster than full beyond the interval: its whole interval lies below no change by
        // the report's direction margin, so a shift that load alone causes never decides.
        const auto clearly_faster = [](const CandidateMeasure& c) {
            return c.time_change_high < -base::kDirectionMarginPoints;
        };
        int fastest = -1;
        for (int i = 1; i < count; ++i) {
            const CandidateMeasure& c = at(i);
            if (c.valid && c.meets_quality && clearly_faster(c) &&
                (fastest < 0 || c.time_change_percent < at(fastest).time_change_percent)) {
                fastest = i;
            }
        }
        if (fastest < 0) {
            if (count > 0 && at(0).valid && at(0).meets_quality &&
                (!frame_budget_ms || at(0).time_ms <= *frame_budget_ms)) {
                choice.index = 0;
                choice.reason = fmt::format(
                        "no candidate that meets the target is faster than the full effect by "
                        "more than {:.1f} points beyond its 95% interval, so the full effect is "
                        "kept",
                        base::kDirectionMarginPoints);
                return choice;
            }
        } else {
            // Among the qualifying candidates indistinguishable from the fastest in time, the
            // most accurate. Indistinguishable: the intervals overlap, or the two changes differ
            // by less than the planner's resolution. Two intervals that barely miss each other
            // still leave a difference of a point or two, which another run on another load may
            // turn round (murky_pond's two water-colour candidates, 1 to 2 points apart, swapped
            // between a quiet and a loaded run).
            int kept = fastest;
            for (int i = 1; i < count; ++i) {
                const CandidateMeasure& c = at(i);
                const bool overlaps = c.time_change_low <= at(fastest).time_change_high &&
                                      at(fastest).time_change_low <= c.time_change_high;
                const bool within_resolution =
                        c.time_change_percent - at(fastest).time_change_percent < tie_points;
                if (i != fastest && c.valid && c.meets_quality && clearly_faster(c) &&
                    (overlaps || within_resolution) && c.psnr_db > at(kept).psnr_db) {
                    kept = i;
                }
            }
            choice.index = kept;
            choice.reason =
                    kept == fastest
                            ? fmt::format(
                                      "the fastest candidate that meets the target: "
                                      "{:+.1f}% [{:+.1f}, {:+.1f}] frame time vs full",
                                      at(kept).time_change_percent, at(kept).time_change_low,
                                      at(kept).time_change_high)
                            : fmt::format(
                                      "the fastest qualifying candidate ({:+.1f}%) and this "
                                      "one ({:+.1f}%) differ by less than their 95% "
                                      "intervals or the planner's {:.1f}-point resolution, "
                                      "so the more accurate one is kept "
                                      "({:.1f} dB against {:.1f} dB)",
                                      at(fastest).time_change_percent, at(kept).time_change_percent,
                                      tie_points, at(kept).psnr_db, at(fastest).psnr_db);
            if (!frame_budget_ms || at(kept).time_ms <= *frame_budget_ms) {
                return choice;
            }
        }
    } else if (frame_budget_ms) {
        for (int i = 0; i < count; ++i) {
            const CandidateMeasure& c = at(i);
            if (c.valid && c.time_ms <= *frame_budget_ms &&
                (choice.index < 0 || c.psnr_db > at(choice.index).psnr_db ||
                 (c.psnr_db == at(choice.index).psnr_db && c.time_ms < at(choice.index).time_ms))) {
                choice.index = i;
            }
        }
        if (choice.index >= 0) {
            choice.reason = "the most accurate candidate within the frame budget";
            return choice;
        }
    }
    choice.index = -1;
    for (int i = 0; i < count; ++i) {
        if (at(i).valid && (choice.index < 0 || at(i).time_ms < at(choice.index).time_ms)) {
            choice.index = i;
        }
    }
    choice.reason = "nothing meets the target; the fastest candidate is reported as not met";
    return choice;
}

ImageError MeasureImageError(const base::RgbaImage& reference, const base::RgbaImage& candidate) {
    ImageError error;
    error.psnr_db = base::Psnr(reference, candidate);
    error.ssim = base::Ssim(reference, candidate);
    error.share_visible =
            base::ShareAboveThreshold(reference, candidate, base::kVisibleDifferenceThreshold);
    return error;
}

ScenePlan PlanScene(GlContext& context, const VariantConfig& config, const SceneDescription& scene,
                    const PlanOptions& options) {
    ScenePlan plan;
    plan.scene = scene;
    if (FloorVisible(scene)) {
        plan.needed.push_back(
                fmt::format("refraction: the floor {} deep is within the fog depth "
                            "{}",
                            scene.water_depth, scene.fog_depth));
    } else if (scene.below_objects) {
        plan.needed.push_back("refraction: objects lie below the water");
    }
    if (scene.wave_strength > kCalmWaves) {
        plan.needed.push_back(fmt::format("distortion: wave strength {}", scene.wave_strength));
    }
    if (scene.above_terrain || scene.above_objects) {
        plan.needed.push_back("reflection of the island and objects above the water");
    } else {
        plan.needed.push_back("reflection of the sky only");
    }
    plan.candidates = ProposeCandidates(config, scene, options.full_preset, options.settings,
                                        &plan.diagnostics);
    if (plan.candidates.empty()) {
        return plan;
    }

    // glslang first: an invalid variant is skipped before it reaches the driver.
    std::vector<Variant> variants;
    for (const PlanCandidate& c : plan.candidates) {
        variants.push_back(c.configuration.variant);
    }
    ValidationOptions validation;
    validation.targets = {GlslTarget::kEs100};
    const ValidationReport no_verdicts;
    const ValidationReport& validated =
            options.validated != nullptr ? *options.validated : no_verdicts;
    const ValidationReport report = ValidateVariants(config, variants, validation, validated);
    for (std::size_t i = 0; i < plan.candidates.size(); ++i) {
        PlanCandidate& c = plan.candidates[i];
        const VariantVerdict* verdict = nullptr;
        for (const VariantVerdict& v : report.verdicts) {
            if (v.variant == c.configuration.variant && v.target == GlslTarget::kEs100) {
                verdict = &v;
            }
        }
        c.valid = verdict != nullptr && verdict->valid;
        if (verdict != nullptr) {
            c.diagnostics = verdict->diagnostics;
        }
        if (!c.valid && c.diagnostics.empty()) {
            c.diagnostics.push_back(MakeError(config.path, 0, 0,
                                              "glslang gave no verdict for " + c.configuration.id));
        }
    }
    if (!plan.candidates.front().valid) {
        plan.diagnostics.push_back(MakeError(
                config.path, 0, 0,
                fmt::format("the full-effect configuration {} fails validation; there is no "
                            "reference to measure against",
                            plan.candidates.front().configuration.id)));
        for (const Diagnostic& d : plan.candidates.front().diagnostics) {
            plan.diagnostics.push_back(d);
        }
        return plan;
    }

    const RenderSettings settings = SceneSettings(scene, options.settings);
    const Scene built = BuildSceneFromDescription(scene);
    std::string error;
    std::unique_ptr<WaterRenderer> renderer =
            WaterRenderer::Create(context, config, settings, &error, &built);
    if (!renderer) {
        plan.diagnostics.push_back(MakeError("", 0, 0, error));
        return plan;
    }
    const CameraView view = SceneCameraView(scene);
    auto use_settings = [&](const PlanCandidate& c) {
        RenderSettings candidate = settings;
        if (c.water_colour_alpha >= 0.0F) {
            candidate.water_colour.a = c.water_colour_alpha;
        }
        renderer->UpdateFrameSettings(candidate);
    };

    // The driver's verdict, one frame's counts and the image of every valid candidate.
    std::vector<base::RgbaImage> images(plan.candidates.size());
    auto render_image = [&](std::size_t i) {
        PlanCandidate& c = plan.candidates[i];
        if (!c.valid) {
            return;
        }
        use_settings(c);
        const DriverVerdict verdict = renderer->Prepare(c.configuration);
        if (!verdict.valid) {
            c.valid = false;
            c.diagnostics = verdict.diagnostics;
            return;
        }
        for (int f = 0; f < options.warmup_frames; ++f) {
            renderer->RenderFrame(c.configuration, view);
        }
        c.frame = renderer->RenderFrame(c.configuration, view);
        renderer->Finish();
        if (!c.frame.gl_error.empty()) {
            c.valid = false;
            c.diagnostics.push_back(MakeError("", 0, 0, c.frame.gl_error));
            return;
        }
        images[i] = renderer->ReadImage();
        if (!options.out_dir.empty()) {
            const std::string name = fmt::format("images/{}-{}.png", scene.name,
                                                 SanitiseFileName(c.configuration.id));
            const std::string write_error =
                    base::WritePngAtomically(options.out_dir / name, images[i]);
            if (write_error.empty()) {
                c.image_path = name;
            } else {
                plan.diagnostics.push_back(MakeError("", 0, 0, write_error));
            }
        }
    };
    for (std::size_t i = 0; i < plan.candidates.size(); ++i) {
        render_image(i);
    }
    if (!plan.candidates.front().valid) {
        plan.diagnostics.push_back(
                MakeError("", 0, 0,
                          fmt::format("the full-effect configuration {} failed in the GL driver",
                                      plan.candidates.front().configuration.id)));
        return plan;
    }
    const base::RgbaImage reference = images.front();
    auto measure_candidate = [&](std::size_t i) {
        PlanCandidate& c = plan.candidates[i];
        if (c.valid) {
            c.error = i == 0 ? ImageError{} : MeasureImageError(reference, images[i]);
            c.error.psnr_db = std::min(c.error.psnr_db, kIdenticalPsnrDb);
            c.meets_quality = MeetsQuality(scene.target, c.error);
        }
    };
    for (std::size_t i = 0; i < plan.candidates.size(); ++i) {
        measure_candidate(i);
    }

    // Second stage, from the measurements: every drop that met the target alone, together.
    std::vector<std::string> passing;
    for (const PlanCandidate& c : plan.candidates) {
        if (c.valid && c.meets_quality && !c.drops.empty()) {
            passing.push_back(c.drops);
        }
    }
    const ProgramConfig* water = config.FindProgram(kWaterProgram);
    if (passing.size() >= 2 && water != nullptr) {
        std::vector<std::string> defines = plan.candidates.front().configuration.variant.defines;
        PassOptions passes = plan.candidates.front().configuration.passes;
        for (const std::string& effect : passing) {
            ApplyDrop(effect, options.settings, &defines, &passes);
        }
        PlanCandidate combined;
        const bool known = [&] {
            for (const PlanCandidate& c : plan.candidates) {
                if (c.configuration.id ==
                    ConfigurationId(MakeVariant(std::string(kWaterProgram), defines), passes)) {
                    return true;
                }
            }
            return false;
        }();
        if (!known && MakeCandidate(*water, scene, defines, passes, &combined)) {
            combined.proposed_because = fmt::format("every drop that met the target alone: {}",
                                                    fmt::join(passing, ", "));
            const ValidationReport combined_report = ValidateVariants(
                    config, {combined.configuration.variant}, validation, validated);
            combined.valid =
                    combined_report.InvalidCount() == 0 && !combined_report.verdicts.empty();
            for (const VariantVerdict& v : combined_report.verdicts) {
                for (const Diagnostic& d : v.diagnostics) {
                    combined.diagnostics.push_back(d);
                }
            }
            plan.candidates.push_back(std::move(combined));
            images.emplace_back();
            render_image(plan.candidates.size() - 1);
            measure_candidate(plan.candidates.size() - 1);
        }
    }

    // Every valid candidate against the full configuration, pair by pair, through the timing
    // engine on the clock the renderer calls for.
    const QualityTarget& target = scene.target;
    const bool quality_bounds = target.min_psnr_db || target.max_share_visible;
    // With image bounds and no frame budget, a candidate whose image misses them is never chosen
    // (the full effect meets them); with a budget, the fastest of all may be, when nothing that
    // meets the bounds fits it.
    const bool time_misses_coarsely = quality_bounds && !target.frame_budget_ms;
    FrameTimer timer(*renderer, options.clock);
    PlanCandidate& full_candidate = plan.candidates.front();
    std::vector<double> full_samples;
    for (std::size_t i = 1; i < plan.candidates.size(); ++i) {
        PlanCandidate& c = plan.candidates[i];
        if (!c.valid) {
            continue;
        }
        const ComparisonTiming timing = TimeComparison(
                [&](bool candidate) {
                    const PlanCandidate& side = candidate ? c : full_candidate;
                    use_settings(side);
                    return timer.Time(side.configuration, view);
                },
                CandidateRule(options.rule, time_misses_coarsely && !c.meets_quality));
        const base::PairedEstimate& e = timing.stated;
        c.time_ms = base::Median(timing.samples.candidate_ms);
        c.time_change_percent = (e.ratio - 1.0) * 100.0;
        c.time_change_low = (e.ratio_low - 1.0) * 100.0;
        c.time_change_high = (e.ratio_high - 1.0) * 100.0;
        c.pairs = e.pairs;
        full_samples.insert(full_samples.end(), timing.samples.baseline_ms.begin(),
                            timing.samples.baseline_ms.end());
    }
    if (full_samples.empty()) {
        for (int f = 0; f < options.rule.min_pairs; ++f) {
            use_settings(full_candidate);
            full_samples.push_back(timer.Time(full_candidate.configuration, view).ms);
        }
    }
    full_candidate.time_ms = base::Median(full_samples);

    // The choice, on the measurements only.
    plan.full = 0;
    std::vector<CandidateMeasure> measures;
    for (const PlanCandidate& c : plan.candidates) {
        measures.push_back({c.valid, c.meets_quality, c.time_ms, c.time_change_low,
                            c.time_change_high, c.time_change_percent, c.error.psnr_db});
    }
    const CandidateChoice choice = ChooseCandidate(measures, quality_bounds, target.frame_budget_ms,
                                                   options.rule.resolution_points);
    const int best = choice.index;
    plan.choice_reason = choice.reason;
    plan.chosen = best;
    const PlanCandidate& chosen = plan.candidates[static_cast<std::size_t>(best)];
    const PlanCandidate& full = plan.candidates.front();
    plan.met = (!quality_bounds || chosen.meets_quality) &&
               (!target.frame_budget_ms || chosen.time_ms <= *target.frame_budget_ms);
    plan.passes_saved = full.frame.passes - chosen.frame.passes;
    plan.draws_saved = full.frame.draw_calls - chosen.frame.draw_calls;
    long long full_pixels = 0;
    long long chosen_pixels = 0;
    for (long long p : full.frame.pass_pixels) {
        full_pixels += p;
    }
    for (long long p : chosen.frame.pass_pixels) {
        chosen_pixels += p;
    }
    plan.pixels_saved = full_pixels - chosen_pixels;

    // Every effect of the full configuration the chosen one lacks, with its measurement.
    const RenderConfiguration& cc = chosen.configuration;
    const RenderConfiguration& fc = full.configuration;
    std::vector<std::pair<std::string, std::string>> drops;  // effect, scene property
    using enum ShaderFeature;
    if (fc.Has(kRefraction) && !cc.Has(kRefraction)) {
        drops.emplace_back(
                "refraction",
                FloorVisible(scene)
                        ? fmt::format("the floor {} deep shows through fog depth {}, "
                                      "but not enough to break the target",
                                      scene.water_depth, scene.fog_depth)
                        : fmt::format("fog depth {} hides the floor {} deep{}; the "
                                      "water colour stands in for it{}",
                                      scene.fog_depth, scene.water_depth,
                                      scene.below_objects ? ""
                                                          : " and nothing else "
                                                            "lies below",
                                      fc.Has(kFresnel) ? " and the Fresnel mix goes with it" : ""));
    }
    if (fc.Has(kFresnel) && !cc.Has(kFresnel) && cc.Has(kRefraction)) {
        drops.emplace_back("fresnel", fmt::format("camera {} above the water: the mix barely "
                                                  "varies over the visible water",
                                                  scene.camera.height));
    }
    if (fc.Has(kDistortion) && !cc.Has(kDistortion)) {
        drops.emplace_back(
                "distortion",
                fmt::format("wave strength {} shifts the image by {:.0f} px per unit of wave slope",
                            scene.wave_strength,
                            options.settings.wave_distortion * scene.wave_strength));
    }
    if (fc.Has(kScaleDistortion) && !cc.Has(kScaleDistortion) && cc.Has(kDistortion)) {
        drops.emplace_back("distortion_scaling",
                           fmt::format("view range {}", scene.camera.view_range));
    }
    if (fc.Has(kFog) && !cc.Has(kFog)) {
        drops.emplace_back("fog", fmt::format("view range {}: little water lies far enough away "
                                              "to fog",
                                              scene.camera.view_range));
    }
    if (ReflectionSize(cc.passes, options.settings.width, options.settings.height) <
        ReflectionSize(fc.passes, options.settings.width, options.settings.height)) {
        drops.emplace_back("reflection_resolution",
                           scene.above_terrain ? "the reflection is soft enough at half size"
                                               : "only the smooth sky is reflected");
    }
    if (cc.passes.low_res_water && !fc.passes.low_res_water) {
        drops.emplace_back("full_resolution_water",
                           "the water's detail survives a low-"
                           "resolution pass");
    }
    for (const auto& [effect, property] : drops) {
        DroppedEffect d;
        d.effect = effect;
        const PlanCandidate* alone = nullptr;
        for (const PlanCandidate& c : plan.candidates) {
            if (c.drops == effect && c.valid) {
                alone = &c;
            }
        }
        const PlanCandidate& measured = alone != nullptr ? *alone : chosen;
        d.psnr_change_db = measured.error.psnr_db;
        d.time_change_percent = measured.time_change_percent;
        d.reason =
                fmt::format("{} dropped: {}; {}: {:.1f} dB PSNR vs full, time {}", effect, property,
                            alone != nullptr ? "dropped alone"
                                             : "in the chosen "
                                               "configuration",
                            measured.error.psnr_db, TimeChangeText(measured));
        plan.dropped.push_back(std::move(d));
    }
    for (const PlanCandidate& c : plan.candidates) {
        if (c.drops.empty() || !c.valid || c.meets_quality ||
            !Keeps(cc, fc, c.drops, options.settings)) {
            continue;
        }
        DroppedEffect k;
        k.effect = c.drops;
        k.psnr_change_db = c.error.psnr_db;
        k.time_change_percent = c.time_change_percent;
        k.reason = fmt::format(
                "{} kept: dropping it alone gives {:.1f} dB PSNR and {:.1f}% "
                "visibly different pixels vs full (time {}), outside the target",
                c.drops, c.error.psnr_db, 100.0 * c.error.share_visible, TimeChangeText(c));
        plan.kept.push_back(std::move(k));
    }
    return plan;
}

stagefiles::PlansFile PlansFileFor(const std::vector<ScenePlan>& plans,
                                   const PlanOptions& options) {
    stagefiles::PlansFile file;
    file.size = {options.settings.width, options.settings.height};
    file.timing = {options.rule.resolution_points, options.rule.min_pairs, options.rule.max_pairs,
                   CandidateRule(options.rule, true).max_pairs, options.rule.contended_share};
    auto configuration = [&options](const PlanCandidate& c) {
        stagefiles::PlanConfiguration out;
        out.id = c.configuration.id;
        out.variant = c.configuration.variant.Id();
        out.passes = c.frame.pass_names;
        out.pass_draw_calls = c.frame.pass_draw_calls;
        out.pass_options = {ReflectionSize(c.configuration.passes, options.settings.width,
                                           options.settings.height),
                            c.configuration.passes.low_res_water};
        out.draw_calls = c.frame.draw_calls;
        out.image = c.image_path;
        for (long long p : c.frame.pass_pixels) {
            out.pixels_shaded_estimate += p;
        }
        return out;
    };
    auto error = [](const ImageError& e) {
        return stagefiles::PlanImageError{e.psnr_db, e.ssim, e.share_visible};
    };
    auto effects = [](const std::vector<DroppedEffect>& list) {
        std::vector<stagefiles::PlanEffect> out;
        out.reserve(list.size());
        for (const DroppedEffect& d : list) {
            out.push_back({d.effect, d.reason, d.psnr_change_db, d.time_change_percent});
        }
        return out;
    };
    auto messages = [](const std::vector<Diagnostic>& diagnostics) {
        std::vector<std::string> out;
        out.reserve(diagnostics.size());
        for (const Diagnostic& d : diagnostics) {
            out.push_back(FormatDiagnostic(d));
        }
        return out;
    };
    for (const ScenePlan& plan : plans) {
        stagefiles::PlannedScene& p = file.plans.emplace_back();
        p.scene = plan.scene.name;
        p.description = plan.scene.description;
        p.target = {plan.scene.target.frame_budget_ms, plan.scene.target.max_share_visible,
                    plan.scene.target.min_psnr_db};
        p.needed = plan.needed;
        p.errors = messages(plan.diagnostics);
        if (plan.chosen < 0 || plan.full < 0) {
            continue;  // failed: no choice, not met
        }
        const PlanCandidate& chosen = plan.candidates[static_cast<std::size_t>(plan.chosen)];
        const PlanCandidate& full = plan.candidates[static_cast<std::size_t>(plan.full)];
        p.met = plan.met;
        stagefiles::PlanChoice& choice = p.choice.emplace();
        choice.chosen = configuration(chosen);
        choice.full = configuration(full);
        choice.time_ms_chosen = chosen.time_ms;
        choice.time_ms_full = full.time_ms;
        choice.time_change_percent = chosen.time_change_percent;
        choice.time_change_interval = {chosen.time_change_low, chosen.time_change_high};
        choice.choice_reason = plan.choice_reason;
        choice.error = error(chosen.error);
        choice.dropped = effects(plan.dropped);
        choice.kept = effects(plan.kept);
        choice.passes_saved = plan.passes_saved;
        choice.draws_saved = plan.draws_saved;
        choice.pixels_saved = plan.pixels_saved;
        for (const PlanCandidate& c : plan.candidates) {
            stagefiles::PlanCandidate& j = choice.candidates.emplace_back();
            j.configuration = configuration(c);
            j.proposed_because = c.proposed_because;
            if (c.water_colour_alpha >= 0.0F) {
                j.water_colour_alpha = c.water_colour_alpha;
            }
            j.valid = c.valid;
            if (c.valid) {
                j.measurement = {error(c.error),
                                 c.time_ms,
                                 c.time_change_percent,
                                 {c.time_change_low, c.time_change_high},
                                 c.pairs,
                                 c.meets_quality};
            } else {
                j.diagnostics = messages(c.diagnostics);
            }
        }
    }
    return file;
}

}  // namespace tidepool::lab
