// The scene planner: from a scene description, propose a short list of water configurations by
// rule (which effects the scene may not need), then render and time every one against the
// scene's full-effect configuration and pick the cheapest that meets the description's target,
// explaining each dropped effect with the measurement behind it.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/PairedEstimate.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/stagefiles/PlansFile.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tidepool::lab {

// The lab's experiments are built on the renderer: its types are used here unqualified.
using namespace tidepool::runner;  // NOLINT(google-build-using-namespace)

/// PSNR reported for identical images, since JSON has no infinity; above any finite PSNR of
/// 8-bit images (one code value off in one pixel of a 640x480 image is about 103 dB, but a
/// render that differs that little is identical for every purpose here).
inline constexpr double kIdenticalPsnrDb = 99.0;

/// How far a candidate's image is from the full-effect image.
struct ImageError {
    double psnr_db = kIdenticalPsnrDb;  // over RGB, capped at kIdenticalPsnrDb
    double ssim = 1.0;
    double share_visible = 0.0;  // share of pixels that differ visibly
};

/// A candidate image's error against the reference with the report's metrics (base/
/// ImageMetrics.h: PSNR uncapped, SSIM, share of visibly different pixels), so plans and the
/// report measure alike. Never fails (NaN metrics for unequal sizes).
ImageError MeasureImageError(const base::RgbaImage& reference, const base::RgbaImage& candidate);

/// How a plan renders and times.
struct PlanOptions {
    RenderSettings settings;  // size and the defaults the description does not move
    int warmup_frames = 1;    // untimed frames per candidate before its image
    // Each candidate is timed against the full configuration pair by pair until its interval
    // is this narrow (the timing engine, FrameTimer.h); 3 points is plenty to rank candidates
    // that differ by tens of percent, and the choice rule never picks one qualifying candidate
    // over a more accurate one on a smaller difference (against the full effect, the 1.5-point
    // direction margin beyond the interval decides). Pairs are timed as the machine runs and,
    // at least half as many, with the core shared (the defaults `run` passes too), so that a plan
    // reached on a quiet machine holds on a busy one (base::AcrossHostStates).
    base::StoppingRule rule{.resolution_points = 3.0, .contended_share = 0.5};
    // The clock frames are timed on: ChooseFrameClock for the context (the caller knows
    // LP_NUM_THREADS; the library reads no environment).
    FrameClock clock = FrameClock::kWall;
    std::string full_preset = "full";  // the full-effect configuration every error is against
    // glslang's verdicts already found (a run's validation, which wrote its manifest):
    // candidates found there are not validated again. Not owned; none: all are validated.
    const ValidationReport* validated = nullptr;
    // When set, every candidate's image is written to out_dir/images/SCENE-ID.png (ids
    // sanitised), named relative to out_dir, where plans.json goes, so the report can show what
    // each drop looks like.
    std::filesystem::path out_dir;
};

/// One configuration the planner rendered and timed (or skipped as invalid).
struct PlanCandidate {
    RenderConfiguration configuration;
    std::string proposed_because;  // the rule that put it on the list
    std::string drops;             // the effect it drops alone ("" for the full and combinations)
    // ENABLE_WATER_COLOUR's mix factor (WaterColour.a), or negative for the renderer's default:
    // a candidate that replaces refraction with the water colour mixes it in as much as the
    // refraction would show, 1 - Fresnel reflectance at the centre of the view.
    float water_colour_alpha = -1.0F;
    bool valid = false;                   // passed glslang and Mesa; never chosen otherwise
    std::vector<Diagnostic> diagnostics;  // why it is invalid
    ImageError error;
    std::string image_path;  // relative to PlanOptions::out_dir; "" when not written
    double time_ms = 0;      // median frame time on the timing clock
    // Frame time vs the full configuration in percent (+ = slower), paired frame by frame, with
    // its 95% interval; 0 and [0, 0] for the full configuration itself.
    double time_change_percent = 0;
    double time_change_low = 0;
    double time_change_high = 0;
    int pairs = 0;               // pairs of frames behind the figure
    FrameReport frame;           // passes, draws and pixels of one frame
    bool meets_quality = false;  // the image-error bounds of the target hold
};

/// Why one effect of the full configuration is not in the chosen one.
struct DroppedEffect {
    std::string effect;              // "refraction", "fresnel", "distortion", ...
    std::string reason;              // the scene's property and the measurement, one sentence
    double psnr_change_db = 0;       // PSNR vs full of dropping this effect alone
    double time_change_percent = 0;  // frame time change of dropping it alone
};

/// A plan for one scene.
struct ScenePlan {
    SceneDescription scene;
    std::vector<std::string> needed;  // effects the rules say the scene shows, with why
    std::vector<PlanCandidate> candidates;
    int full = -1;  // index into candidates; -1 when the plan failed
    int chosen = -1;
    std::string choice_reason;  // ChooseCandidate's reason
    bool met = false;           // the chosen candidate meets every bound of the target
    std::vector<DroppedEffect> dropped;
    // Effects the rules offered to drop but the measurement kept, with the same fields: the
    // error dropping each alone causes breaks the target.
    std::vector<DroppedEffect> kept;
    int passes_saved = 0;
    int draws_saved = 0;
    long long pixels_saved = 0;
    std::vector<Diagnostic> diagnostics;  // errors end the plan (full invalid, GL failures)
};

/// What the choice rule reads of a candidate.
struct CandidateMeasure {
    bool valid = false;
    bool meets_quality = false;
    double time_ms = 0;
    double time_change_low = 0;   // interval of the frame-time change vs full, percent
    double time_change_high = 0;  // (+ = slower)
    double time_change_percent = 0;
    double psnr_db = 0;
};

/// The planner's choice and why.
struct CandidateChoice {
    int index = -1;
    std::string reason;
};

/// The stopping rule a candidate is timed against the full configuration by: `rule`, or, for a
/// candidate whose image misses the quality bounds of a scene with no frame budget
/// (`misses_target`), `rule` stopped at its fewest pairs, as the machine runs only (no contended
/// pairs), with the interval they give.
/// ChooseCandidate then never prefers such a candidate (the full configuration always meets the
/// bounds), so its time only says what keeping the effect costs (ScenePlan::kept); on the
/// default scenes those candidates had taken 68% of the planner's pairs (2,369 of 3,484 beside
/// two `yes`, 2026-11-28), up to the cap of 400 for a change near no change. With a frame
/// budget, the fastest of all candidates may be chosen when none that meets the bounds fits it,
/// so every candidate is timed to the resolution.
base::StoppingRule CandidateRule(const base::StoppingRule& rule, bool misses_target);

/// Chooses among measured candidates (index 0 is the full configuration). With quality bounds:
/// the fastest candidate that meets them and is faster than full beyond its interval and the
/// direction margin; but a more accurate one that also qualifies is kept instead whenever the
/// two intervals overlap or their changes differ by less than `tie_points` (the planner's
/// resolution), since then the time difference is within what the timing resolves (and it
/// says so). Full is kept when no candidate is faster beyond its interval. With only a budget:
/// the most accurate within it. When nothing qualifies: the fastest, which misses the target.
/// Never fails; -1 when no candidate is valid.
CandidateChoice ChooseCandidate(const std::vector<CandidateMeasure>& candidates,
                                bool quality_bounds, std::optional<double> frame_budget_ms,
                                double tie_points);

/// The candidate list the rules propose for `scene` (at most 11, the full configuration first,
/// then every effect dropped alone, then combinations the scene suggests),
/// each a variant of program `water` with its pass options; a candidate whose defines break a
/// rule of `config` is left out. Sizes that follow the window (the half-size reflection) are
/// taken from `settings`. Fails through diagnostics when `full_preset` does not exist.
std::vector<PlanCandidate> ProposeCandidates(const VariantConfig& config,
                                             const SceneDescription& scene,
                                             const std::string& full_preset,
                                             const RenderSettings& settings,
                                             std::vector<Diagnostic>* diagnostics);

/// Plans `scene`: validates the candidates with glslang (invalid ones are skipped, never
/// chosen), renders the scene built from the description with each and measures its error
/// (MeasureImageError), adds one candidate that combines every drop that met the target alone (at
/// most 12 in all), times them all in paired rounds, and picks the cheapest that meets the target.
/// Fails through ScenePlan::diagnostics when the full configuration is invalid or the renderer
/// cannot be created.
ScenePlan PlanScene(GlContext& context, const VariantConfig& config, const SceneDescription& scene,
                    const PlanOptions& options);

/// The plans as plans.json holds them (stagefiles/PlansFile.h, docs/SCENES.md). Never fails.
stagefiles::PlansFile PlansFileFor(const std::vector<ScenePlan>& plans, const PlanOptions& options);

}  // namespace tidepool::lab
