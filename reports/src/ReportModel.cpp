#include "tidepool/report/ReportModel.h"

#include "tidepool/VariantConfig.h"
#include "tidepool/base/FileKind.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/ParallelFor.h"
#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <iterator>
#include <map>
#include <memory>
#include <numeric>
#include <thread>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

using base::DifferenceHeatMap;
using base::kHeatMapFullScale;
using base::kVisibleDifferenceThreshold;
using base::Psnr;
using base::RgbaImage;
using base::ShareAboveThreshold;
using base::Ssim;
using base::SsimReference;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A configuration rendered with the default pass options (reflection and refraction of the
// window's demo size, oblique clip, no low-resolution water, culling, depth fog): only these
// share the pass work, so their static counts are comparable with their times.
bool HasDefaultPasses(const MeasuredConfiguration& c, const ReportInputs& inputs) {
    const int size = DemoTargetSize(inputs.width, inputs.height);
    return c.reflection_size == size && c.refraction_size == size && c.clip == "oblique" &&
           !c.low_res_water && c.culling && c.depth_fog;
}

// Image error of one configuration against the reference over every view both have.
struct ViewErrors {
    double mse_sum = 0;
    double ssim_sum = 0;
    double share_sum = 0;
    int views = 0;
    std::string error;  // an unreadable image, naming the file
};

// The mean squared error behind a PSNR figure (PSNR = 10 log10(255^2 / MSE)).
double MseFromPsnr(double psnr_db) {
    return std::isinf(psnr_db) ? 0.0 : 255.0 * 255.0 / std::pow(10.0, psnr_db / 10.0);
}

double PsnrFromMse(double mse) {
    return mse <= 0 ? std::numeric_limits<double>::infinity()
                    : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// An image others are compared with, and its SSIM moments, computed once.
struct ReferenceImage {
    RgbaImage image;
    std::shared_ptr<const SsimReference> ssim;

    explicit ReferenceImage(RgbaImage from)
        : image(std::move(from)), ssim(std::make_shared<SsimReference>(image)) {}
};

using ImageCache = std::map<std::string, ReferenceImage>;

// Reads `path`, or returns the error naming it.
std::optional<RgbaImage> LoadImage(const std::filesystem::path& path, std::string* error) {
    base::ImageResult read = base::ReadPng(path);
    if (!read.image) {
        *error = read.error.empty() ? path.string() + ": cannot read image" : read.error;
        return std::nullopt;
    }
    return std::move(*read.image);
}

// Compares every image of `c` with the image of `reference` at the same view; `whose` names
// the other side in a size-mismatch error ("the reference's"). Fills `per_view` when not null.
// With `recorded` (`reference` holds the reference configuration's images), a view the render
// already compared with the reference while it was in memory is taken from the results.
ViewErrors CompareWithReference(const MeasuredConfiguration& c, const ImageCache& reference,
                                std::string_view whose = "the reference's",
                                std::vector<ViewError>* per_view = nullptr, bool recorded = false) {
    ViewErrors errors;
    for (const ViewImage& v : c.views) {
        auto ref = reference.find(v.view);
        if (v.image.empty() || ref == reference.end()) {
            continue;
        }
        ViewError view;
        if (recorded && v.accuracy) {
            // The figures come from the results; the file they describe must still be there.
            if (const std::string why = base::WhyNotARegularFile(v.image); !why.empty()) {
                errors.error = fmt::format("{}: cannot read image: {}", v.image.string(), why);
                return errors;
            }
            view = {v.view, v.accuracy->psnr_db, v.accuracy->ssim, v.accuracy->share_visible};
        } else {
            std::optional<RgbaImage> image = LoadImage(v.image, &errors.error);
            if (!image) {
                return errors;
            }
            const RgbaImage& r = ref->second.image;
            if (image->width != r.width || image->height != r.height) {
                errors.error = fmt::format("{}: {}x{} image, but {} at view '{}' is {}x{}",
                                           v.image.string(), image->width, image->height, whose,
                                           v.view, r.width, r.height);
                return errors;
            }
            const base::ImageAccuracy measured =
                    base::MeasureAccuracy(*image, r, *ref->second.ssim);
            view = {v.view, measured.psnr_db, measured.ssim, measured.share_visible};
        }
        errors.mse_sum += MseFromPsnr(view.psnr_db);
        errors.ssim_sum += view.ssim;
        errors.share_sum += view.share_visible;
        ++errors.views;
        if (per_view != nullptr) {
            per_view->push_back(view);
        }
    }
    return errors;
}

// Reads every image of `c`, keyed by view, or sets `error` naming the unreadable file.
ImageCache LoadViewImages(const MeasuredConfiguration& c, std::string* error) {
    ImageCache images;
    for (const ViewImage& v : c.views) {
        if (v.image.empty()) {
            continue;
        }
        std::optional<RgbaImage> image = LoadImage(v.image, error);
        if (!image) {
            return {};
        }
        images.emplace(v.view, ReferenceImage(std::move(*image)));
    }
    return images;
}

// The change in percent of frame rate (+ = faster) and its interval from a frame-time ratio;
// a larger ratio is a lower frame rate, so the interval's ends swap.
void ChangeFromRatio(const PairedRatio& ratio, double* change, Interval* ci) {
    if (!std::isfinite(ratio.ratio)) {
        return;
    }
    *change = PerformanceChangePercent(ratio.ratio);
    ci->low = PerformanceChangePercent(ratio.ci.high);
    ci->high = ratio.ci.low > 0 ? PerformanceChangePercent(ratio.ci.low)
                                : std::numeric_limits<double>::infinity();
}

// The sample standard deviation of log(b[i] / a[i]); NaN with fewer than 2 usable pairs.
double LogRatioSd(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        if (a[i] > 0 && b[i] > 0) {
            d.push_back(std::log(b[i] / a[i]));
        }
    }
    return base::StandardDeviation(d);
}

// The paired frames behind a comparison of two configurations.
struct PairsOfFrames {
    std::vector<double> baseline_ms;
    std::vector<double> candidate_ms;
    std::vector<double> contended_baseline_ms;  // timed with the core shared (may be empty)
    std::vector<double> contended_candidate_ms;
    std::string source;  // where the pairs come from, for the method text
    std::string error;   // why there are none
};

// The runner's pairs when results.json records this comparison (they are on the run's clock,
// which is the CPU clock ChooseClock picks for such results); otherwise one pair per round from
// the per-round medians of `clock`'s samples, as results written before the runner recorded
// pairs allow.
PairsOfFrames PairsFor(const ReportInputs& inputs, const MeasuredConfiguration& base,
                       const MeasuredConfiguration& cand, TimingClock clock) {
    PairsOfFrames pairs;
    if (const MeasuredComparison* c = inputs.FindComparison(base.id, cand.id);
        c != nullptr && clock == TimingClock::kCpu) {
        if (!c->error.empty()) {
            pairs.error = c->error;
            return pairs;
        }
        pairs.baseline_ms = c->baseline_ms;
        pairs.candidate_ms = c->candidate_ms;
        pairs.contended_baseline_ms = c->contended_baseline_ms;
        pairs.contended_candidate_ms = c->contended_candidate_ms;
        pairs.source = c->timed_by == "second_process"
                               ? "pairs of frames rendered back to back, by the process beside "
                                 "the render"
                               : "pairs of frames rendered back to back";
        return pairs;
    }
    pairs.error = PairsFromRounds(base.SamplesOn(clock), cand.SamplesOn(clock), &pairs.baseline_ms,
                                  &pairs.candidate_ms);
    pairs.source = "one pair per timing round (results without recorded pairs)";
    return pairs;
}

// Each pass's time in both configurations and the pass whose time changed most, with its share
// of the frame it belongs to: the measured reason a row's change is what it is. The passes are
// the comparison's own instrumented frames, taken in pairs under the same load, when the results
// have them; otherwise each configuration's (results written before comparisons kept theirs).
std::string MeasuredWhy(const ReportInputs& inputs, const MeasuredConfiguration& base,
                        const MeasuredConfiguration& cand) {
    using PassTimes = std::map<std::string, double>;
    const PassTimes* base_ms = &base.pass_ms;
    const PassTimes* cand_ms = &cand.pass_ms;
    if (const MeasuredComparison* c = inputs.FindComparison(base.id, cand.id);
        c != nullptr && !c->baseline_pass_ms.empty() && !c->candidate_pass_ms.empty()) {
        base_ms = &c->baseline_pass_ms;
        cand_ms = &c->candidate_pass_ms;
    }
    if (base_ms->empty() || cand_ms->empty()) {
        return "";
    }
    // The passes in frame order (as the views list them), then any the views do not name.
    std::vector<std::string> passes;
    auto add = [&](const std::string& name) {
        if (std::find(passes.begin(), passes.end(), name) == passes.end()) {
            passes.push_back(name);
        }
    };
    for (const MeasuredConfiguration* c : {&base, &cand}) {
        for (const ViewImage& v : c->views) {
            std::for_each(v.pass_names.begin(), v.pass_names.end(), add);
        }
    }
    for (const PassTimes* times : {base_ms, cand_ms}) {
        for (const auto& [name, ms] : *times) {
            add(name);
        }
    }
    auto at = [](const PassTimes& times, const std::string& pass) {
        auto found = times.find(pass);
        return found == times.end() ? 0.0 : found->second;
    };
    auto total = [](const PassTimes& times) {
        double sum = 0;
        for (const auto& [name, ms] : times) {
            sum += ms;
        }
        return sum;
    };
    std::string list;
    std::string largest;
    double largest_change = 0;
    for (const std::string& pass : passes) {
        const double a = at(*base_ms, pass);
        const double b = at(*cand_ms, pass);
        list += fmt::format("{}{} {} -> {} ms", list.empty() ? "" : "; ", pass,
                            a > 0 ? fmt::format("{:.1f}", a) : std::string("none"),
                            b > 0 ? fmt::format("{:.1f}", b) : std::string("none"));
        if (std::fabs(b - a) > std::fabs(largest_change)) {
            largest_change = b - a;
            largest = pass;
        }
    }
    if (largest.empty()) {
        return "measured per pass: " + list;
    }
    // The share of the frame the changed pass takes on the side where it is larger.
    const PassTimes& side = largest_change > 0 ? *cand_ms : *base_ms;
    const double share = 100.0 * at(side, largest) / std::max(total(side), 1e-9);
    return fmt::format(
            "measured per pass: {}. The {} pass changes most ({:+.1f} ms); it is "
            "{:.0f}% of the {}'s frame",
            list, largest, largest_change, share, largest_change > 0 ? "candidate" : "baseline");
}

// One technique's preset pair and what it is known to miss.
struct TechniquePresets {
    TechniqueKind kind;
    const char* technique;
    const char* context;
    const char* baseline;
    const char* candidate;
};

// The reflection pairs of the issue, the reflection-only pairs first; each technique replaces
// the planar reflection pass, everything else about the frame being equal.
constexpr TechniquePresets kReflectionPresets[] = {
        {TechniqueKind::kCubemapReflection, "cube-map reflection", "reflection only",
         "reflection_only", "cubemap_reflection"},
        {TechniqueKind::kFourierReflection, "Fourier reflection", "reflection only",
         "reflection_only", "fourier_reflection"},
        {TechniqueKind::kCubemapReflection, "cube-map reflection", "full effect", "full",
         "full_cubemap_reflection"},
        {TechniqueKind::kFourierReflection, "Fourier reflection", "full effect", "full",
         "full_fourier_reflection"},
};

constexpr TechniquePresets kOpticsPresets[] = {
        {TechniqueKind::kDepthOptics, "depth optics", "full effect", "full", "full_depth_optics"},
};

// What each technique is known to miss (seeds/001, seeds/004) or to change (seeds/003).
std::string KnownLimitation(TechniqueKind kind) {
    switch (kind) {
        case TechniqueKind::kCubemapReflection:
            return "Local objects and terrain are missing from the reflection: only the sky cube "
                   "map "
                   "is reflected.";
        case TechniqueKind::kFourierReflection:
            return "Only the static terrain heightfield is captured: objects (anything that moves) "
                   "are missing, and the terrain reflects as one flat colour without detail.";
        case TechniqueKind::kDepthOptics:
            return "An addition, not a replacement: the error is how much extinction, shore foam, "
                   "soft shore and sun specular change the full effect's image.";
    }
    return {};
}

std::string PsnrLabel(double psnr_db) {
    return std::isinf(psnr_db) ? std::string("identical") : fmt::format("{:.1f} dB", psnr_db);
}

// Pass names, draw calls and median of one side at the timing view.
void FillSide(const MeasuredConfiguration* c, const std::string& timing_view, TimingClock clock,
              std::vector<std::string>* passes, std::optional<int>* draw_calls, double* median_ms) {
    if (c == nullptr || !c->ok) {
        return;
    }
    if (const ViewImage* v = c->ViewAt(timing_view); v != nullptr) {
        *passes = v->pass_names;
        *draw_calls = v->draw_calls;
    }
    if (!draw_calls->has_value() && c->frame_draw_calls > 0) {
        *draw_calls = c->frame_draw_calls;  // results without per-view draw calls
    }
    *median_ms = c->MedianOn(clock);
}

// Everything of a technique comparison but the image error.
TechniqueComparison CompareTechnique(const TechniquePresets& presets, const ReportInputs& inputs,
                                     TimingClock clock) {
    TechniqueComparison t;
    t.kind = presets.kind;
    t.technique = presets.technique;
    t.context = presets.context;
    t.baseline = {presets.baseline, inputs.FindByPreset(presets.baseline)};
    t.candidate = {presets.candidate, inputs.FindByPreset(presets.candidate)};
    const MeasuredConfiguration* base = t.baseline.configuration;
    const MeasuredConfiguration* cand = t.candidate.configuration;
    FillSide(base, inputs.timing_view, clock, &t.baseline_passes, &t.baseline_draw_calls,
             &t.baseline_median_ms);
    FillSide(cand, inputs.timing_view, clock, &t.candidate_passes, &t.candidate_draw_calls,
             &t.candidate_median_ms);
    if (!t.candidate_passes.empty()) {
        for (const std::string& pass : t.baseline_passes) {
            if (std::find(t.candidate_passes.begin(), t.candidate_passes.end(), pass) ==
                t.candidate_passes.end()) {
                t.passes_dropped.push_back(pass);
            }
        }
    }
    for (const ComparisonSide* side : {&t.baseline, &t.candidate}) {
        std::string problem;
        if (side->configuration == nullptr) {
            problem = fmt::format("no configuration in the results carries preset '{}'",
                                  side->preset);
        } else if (!side->configuration->ok) {
            problem = fmt::format("configuration {} (preset '{}') FAILED", side->configuration->id,
                                  side->preset);
        }
        if (!problem.empty()) {
            t.note += (t.note.empty() ? "" : "; ") + problem;
        }
    }
    if (t.note.empty()) {
        const PairsOfFrames pairs = PairsFor(inputs, *base, *cand, clock);
        t.ratio = pairs.error.empty()
                          ? ComparePairs(pairs.baseline_ms, pairs.candidate_ms,
                                         pairs.contended_baseline_ms, pairs.contended_candidate_ms)
                          : PairedRatio{};
        if (!pairs.error.empty() || !t.ratio.error.empty()) {
            t.note = fmt::format("no paired time on the {} clock: {}", TimingClockName(clock),
                                 pairs.error.empty() ? t.ratio.error : pairs.error);
        }
        ChangeFromRatio(t.ratio, &t.change_percent, &t.change_ci);
        if (std::isfinite(t.change_ci.low) && t.change_ci.low > kDirectionMarginPoints) {
            t.direction = +1;
        } else if (std::isfinite(t.change_ci.high) && t.change_ci.high < -kDirectionMarginPoints) {
            t.direction = -1;
        }
    }
    return t;
}

// True when both sides rendered, so their images can be compared.
bool BothRendered(const TechniqueComparison& t) {
    return t.baseline.configuration != nullptr && t.baseline.configuration->ok &&
           t.candidate.configuration != nullptr && t.candidate.configuration->ok;
}

// Sets the image error of `t` from per-view errors and names the worst view in `reading`.
void FinishError(const ViewErrors& errors, TechniqueComparison* t) {
    t->reading = KnownLimitation(t->kind);
    if (errors.views == 0) {
        if (BothRendered(*t)) {
            t->note += std::string(t->note.empty() ? "" : "; ") +
                       "no view has images of both configurations";
        }
        return;
    }
    const double n = errors.views;
    t->views_compared = errors.views;
    t->psnr_db = PsnrFromMse(errors.mse_sum / n);
    t->ssim = errors.ssim_sum / n;
    t->share_visible = errors.share_sum / n;
    if (t->per_view.size() < 2) {
        return;
    }
    const ViewError* worst = nullptr;
    for (const ViewError& v : t->per_view) {
        if (std::isfinite(v.psnr_db) && (worst == nullptr || v.psnr_db < worst->psnr_db)) {
            worst = &v;
        }
    }
    if (worst != nullptr) {
        t->worst_view = worst->view;
        t->worst_psnr_db = worst->psnr_db;
        t->reading += fmt::format(
                " {}: {} ({} against {} over all views).",
                t->kind == TechniqueKind::kDepthOptics ? "Most changed view" : "Worst view",
                worst->view, PsnrLabel(worst->psnr_db), PsnrLabel(t->psnr_db));
    }
}

// The panel of `t`'s candidate beside its baseline at `view`; `baseline_images` are the
// baseline's images by view. Sets `error` naming the file when an image cannot be read.
ImagePanel TechniquePanel(const TechniqueComparison& t, const std::string& view,
                          const ImageCache* baseline_images, std::string* error) {
    ImagePanel panel;
    panel.configuration = t.candidate.configuration;
    panel.view = view;
    panel.reference_preset = t.baseline.preset;
    panel.reference_caption = fmt::format("planar reflection ({})", t.baseline.preset);
    panel.title = fmt::format(
            "{}: {} beside planar reflection ({}); the \"reference\" side is "
            "the planar image",
            t.technique, t.candidate.preset, t.baseline.preset);
    const MeasuredConfiguration* cand = t.candidate.configuration;
    const MeasuredConfiguration* base = t.baseline.configuration;
    auto baseline_image =
            baseline_images != nullptr ? baseline_images->find(view) : ImageCache::const_iterator{};
    if (cand == nullptr) {
        panel.note =
                fmt::format("MISSING: no configuration carries preset '{}'", t.candidate.preset);
    } else if (!cand->ok) {
        panel.note = "FAILED: no image (the configuration did not compile or render)";
    } else if (cand->ImageAt(view).empty()) {
        panel.note = "no image was written at this view";
    } else if (base == nullptr || !base->ok || baseline_images == nullptr ||
               baseline_image == baseline_images->end()) {
        panel.note =
                fmt::format("no planar image ({}) at this view to compare with", t.baseline.preset);
    } else {
        std::optional<RgbaImage> image = LoadImage(cand->ImageAt(view), error);
        if (!image) {
            return panel;
        }
        const RgbaImage& planar = baseline_image->second.image;
        if (image->width != planar.width || image->height != planar.height) {
            *error = fmt::format("{}: {}x{} image, but {}'s at view '{}' is {}x{}",
                                 cand->ImageAt(view).string(), image->width, image->height,
                                 base->id, view, planar.width, planar.height);
            return panel;
        }
        panel.image = std::move(*image);
        panel.reference = planar;
        panel.heat_map = DifferenceHeatMap(panel.image, panel.reference, kHeatMapFullScale);
        panel.psnr_db = Psnr(panel.image, panel.reference);
        panel.ssim = Ssim(panel.image, panel.reference);
        panel.share_visible =
                ShareAboveThreshold(panel.image, panel.reference, kVisibleDifferenceThreshold);
    }
    return panel;
}

// Builds the technique comparisons of `presets` with their image errors, the baselines' images
// read once and the pairs compared on the cores we have. Returns "" or the error naming a file.
std::string BuildTechniques(const std::vector<TechniquePresets>& presets,
                            const ReportInputs& inputs, TimingClock clock,
                            std::map<const MeasuredConfiguration*, ImageCache>* baseline_images,
                            std::vector<TechniqueComparison>* out) {
    for (const TechniquePresets& p : presets) {
        out->push_back(CompareTechnique(p, inputs, clock));
        const MeasuredConfiguration* base = out->back().baseline.configuration;
        if (BothRendered(out->back()) && baseline_images->count(base) == 0) {
            std::string error;
            (*baseline_images)[base] = LoadViewImages(*base, &error);
            if (!error.empty()) {
                return error;
            }
        }
    }
    std::vector<std::future<ViewErrors>> jobs;
    for (TechniqueComparison& t : *out) {
        if (!BothRendered(t)) {
            jobs.push_back(std::async(std::launch::deferred, [] { return ViewErrors{}; }));
            continue;
        }
        const ImageCache& images = baseline_images->at(t.baseline.configuration);
        jobs.push_back(std::async(std::launch::async, [&t, &images] {
            return CompareWithReference(*t.candidate.configuration, images,
                                        fmt::format("{}'s", t.baseline.configuration->id),
                                        &t.per_view);
        }));
    }
    std::string error;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const ViewErrors errors = jobs[i].get();
        if (error.empty() && !errors.error.empty()) {
            error = errors.error;
        }
        FinishError(errors, &(*out)[i]);
    }
    return error;
}

std::string PresetTitle(const MeasuredConfiguration& c) {
    std::string title;
    for (const std::string& p : c.presets) {
        title += (title.empty() ? "" : ", ") + p;
    }
    return title.empty() ? c.id : title;
}

// The validation summary's rows from the manifest's `pruned_by_rule`; a manifest written before
// it (a `pruned` list of combinations) is summarised the same way, by grouping its list.
std::vector<PrunedRuleRow> PrunedRuleRows(const stagefiles::ManifestFile& manifest) {
    std::vector<PrunedRuleRow> rows;
    if (manifest.pruned_by_rule) {
        for (const stagefiles::ManifestPrunedRule& item : *manifest.pruned_by_rule) {
            rows.push_back({item.program, item.rule, item.file, item.line,
                            static_cast<std::uint64_t>(std::max(item.count, 0LL))});
        }
    } else {
        for (const stagefiles::ManifestPrunedCombination& item : manifest.pruned) {
            PrunedRuleRow row{item.program, item.rule, item.file, item.line, 1};
            auto same = std::find_if(rows.begin(), rows.end(), [&](const PrunedRuleRow& r) {
                return r.program == row.program && r.rule == row.rule && r.line == row.line;
            });
            if (same == rows.end()) {
                rows.push_back(std::move(row));
            } else {
                ++same->count;
            }
        }
    }
    return rows;
}

}  // namespace

std::vector<PresetPair> ComparedPresetPairs() {
    std::vector<PresetPair> pairs;
    for (const WhitepaperRow& row : WhitepaperRows()) {
        pairs.push_back({fmt::format("row {}", row.number), row.baseline_preset,
                         row.candidate_preset, VerdictBoundaries(row)});
    }
    auto add = [&](const TechniquePresets& t) {
        pairs.push_back(
                {fmt::format("{} ({})", t.technique, t.context), t.baseline, t.candidate, {}});
    };
    std::for_each(std::begin(kReflectionPresets), std::end(kReflectionPresets), add);
    std::for_each(std::begin(kOpticsPresets), std::end(kOpticsPresets), add);
    return pairs;
}

std::string_view TechniqueKindName(TechniqueKind kind) {
    switch (kind) {
        case TechniqueKind::kCubemapReflection:
            return "cubemap";
        case TechniqueKind::kFourierReflection:
            return "fourier";
        case TechniqueKind::kDepthOptics:
            return "depth-optics";
    }
    return "cubemap";
}

std::string_view VerdictName(Verdict verdict) {
    switch (verdict) {
        case Verdict::kSameDirectionAndMagnitude:
            return "same-direction-and-magnitude";
        case Verdict::kSameDirectionDifferentMagnitude:
            return "same-direction-different-magnitude";
        case Verdict::kSameDirectionMagnitudeAtBandEdge:
            return "same-direction-magnitude-at-band-edge";
        case Verdict::kSameDirectionOnly:
            return "same-direction-only";
        case Verdict::kNegligibleAsClaimed:
            return "negligible-as-claimed";
        case Verdict::kOpposite:
            return "opposite";
        case Verdict::kBelowResolution:
            return "below-resolution";
        case Verdict::kFailed:
            return "failed";
    }
    return "failed";
}

VerdictStanding StandingOf(Verdict verdict) {
    switch (verdict) {
        case Verdict::kSameDirectionAndMagnitude:
        case Verdict::kNegligibleAsClaimed:
            return VerdictStanding::kAgrees;
        case Verdict::kSameDirectionDifferentMagnitude:
        case Verdict::kSameDirectionMagnitudeAtBandEdge:
        case Verdict::kSameDirectionOnly:
            return VerdictStanding::kAgreesInDirection;
        case Verdict::kOpposite:
        case Verdict::kFailed:
            return VerdictStanding::kDisagrees;
        case Verdict::kBelowResolution:
            return VerdictStanding::kUndecided;
    }
    return VerdictStanding::kUndecided;
}

bool IsFirmVerdict(Verdict verdict, FigureKind kind) {
    switch (verdict) {
        case Verdict::kSameDirectionAndMagnitude:
        case Verdict::kSameDirectionDifferentMagnitude:
        case Verdict::kSameDirectionMagnitudeAtBandEdge:
        case Verdict::kNegligibleAsClaimed:
        case Verdict::kOpposite:
            return true;
        case Verdict::kSameDirectionOnly:
            return kind == FigureKind::kDirection;  // never given to other rows
        case Verdict::kBelowResolution:
        case Verdict::kFailed:
            return false;
    }
    return false;
}

Verdict GradeRow(const WhitepaperRow& row, const PairedRatio& measured, const SplitHalf* split,
                 std::string* reason) {
    if (!std::isfinite(measured.ratio) || measured.pairs == 0) {
        *reason = measured.error.empty() ? "no measurement" : measured.error;
        return Verdict::kFailed;
    }
    // A larger frame-time ratio is a lower frame rate, so the interval's ends swap.
    const double low = PerformanceChangePercent(measured.ci.high);
    const double high = PerformanceChangePercent(measured.ci.low);
    const double change = PerformanceChangePercent(measured.ratio);
    const std::string interval = fmt::format("{:+.1f}% [{:+.1f}%, {:+.1f}%], {} pairs", change, low,
                                             high, measured.pairs);
    std::string halves;
    if (split != nullptr && std::isfinite(split->odd.ratio) && std::isfinite(split->even.ratio)) {
        const double odd = PerformanceChangePercent(split->odd.ratio);
        const double even = PerformanceChangePercent(split->even.ratio);
        if (odd * even < 0) {
            halves = fmt::format(
                    "; the two halves of the pairs disagree in sign ({:+.1f}% with "
                    "the baseline first, {:+.1f}% with the candidate first)",
                    even, odd);
        }
    }
    const double bound = std::max(std::fabs(low), std::fabs(high));
    const bool near_no_change = low <= kDirectionMarginPoints && high >= -kDirectionMarginPoints;
    if (row.kind == FigureKind::kNegligible) {
        const double band = 1.0 * kMagnitudeFactor;  // the whitepaper's "<1%", times the factor
        if (bound <= band) {
            *reason =
                    fmt::format("|change| < {:.1f}%, within {:.0f}% as the whitepaper's <1%: {}{}",
                                bound, band, interval, halves);
            return Verdict::kNegligibleAsClaimed;
        }
    }
    if (near_no_change) {
        *reason = fmt::format(
                "below resolution: |change| < {:.1f}%; the interval reaches within "
                "{:.1f} points of no change, so no direction is claimed: {}{}",
                bound, kDirectionMarginPoints, interval, halves);
        return Verdict::kBelowResolution;
    }
    const int direction = low > 0.0 ? +1 : -1;
    if (direction != row.expected_sign) {
        *reason = fmt::format("{} where the whitepaper says {}: {}{}",
                              direction > 0 ? "faster" : "slower",
                              row.expected_sign > 0 ? "faster" : "slower", interval, halves);
        return Verdict::kOpposite;
    }
    if (row.kind == FigureKind::kDirection) {
        *reason = fmt::format(
                "the whitepaper's figure is qualitative, so only the direction is "
                "compared: {}{}",
                interval, halves);
        return Verdict::kSameDirectionOnly;
    }
    // The interval's magnitudes against the band [f / factor, f x factor] (for "<1%": up to
    // 1% x factor, the direction already established above).
    const double magnitude_low = std::min(std::fabs(low), std::fabs(high));
    const double magnitude_high = bound;
    const double figure =
            row.kind == FigureKind::kNegligible ? 0.0 : std::fabs(row.whitepaper_percent);
    const double band_low = figure / kMagnitudeFactor;
    const double band_high =
            row.kind == FigureKind::kNegligible ? kMagnitudeFactor : figure * kMagnitudeFactor;
    const std::string band =
            row.kind == FigureKind::kNegligible
                    ? fmt::format("the whitepaper's <1% times {:.0f}: |change| <= {:.0f}%",
                                  kMagnitudeFactor, band_high)
                    : fmt::format("half to twice the whitepaper's figure: {:.1f}% to {:.0f}%",
                                  band_low, band_high);
    if (magnitude_low >= band_low && magnitude_high <= band_high) {
        *reason = fmt::format("the whole interval lies within {}: {}{}", band, interval, halves);
        return Verdict::kSameDirectionAndMagnitude;
    }
    if (magnitude_high < band_low || magnitude_low > band_high) {
        *reason = fmt::format("the whole interval lies outside {}: {}{}", band, interval, halves);
        return Verdict::kSameDirectionDifferentMagnitude;
    }
    // The interval holds an end of the band (or both): the effect may lie on either side.
    const bool holds_low = magnitude_low < band_low;
    const bool holds_high = magnitude_high > band_high;
    const std::string held = holds_low && holds_high ? "the whole band"
                             : holds_low             ? fmt::format("its {:.1f}% end", band_low)
                                                     : fmt::format("its {:.1f}% end", band_high);
    *reason = fmt::format(
            "the same direction; the interval holds {} ({}), so the magnitude is not decided "
            "either way: {}{}",
            held, band, interval, halves);
    return Verdict::kSameDirectionMagnitudeAtBandEdge;
}

std::vector<double> VerdictBoundaries(const WhitepaperRow& row) {
    switch (row.kind) {
        case FigureKind::kPercent: {
            const double figure = std::fabs(row.whitepaper_percent);
            const double sign = row.expected_sign >= 0 ? 1.0 : -1.0;
            std::vector<double> ends;
            for (double end :
                 {sign * figure / kMagnitudeFactor, sign * figure * kMagnitudeFactor}) {
                if (std::isfinite(end) && end > -100.0) {  // a frame rate cannot fall by 100%
                    ends.push_back(end);
                }
            }
            return ends;
        }
        case FigureKind::kNegligible:  // the whitepaper's "<1%", times the factor
            return {-1.0 * kMagnitudeFactor, 1.0 * kMagnitudeFactor};
        case FigureKind::kDirection:
            return {};
    }
    return {};
}

StaticCostAnalysis AnalyseStaticCost(std::vector<StaticCostEntry> entries) {
    StaticCostAnalysis analysis;
    analysis.entries = std::move(entries);
    if (analysis.entries.size() < 3) {
        analysis.note = "fewer than 3 measured configurations with a static cost";
        return analysis;
    }
    std::vector<double> ops;
    std::vector<double> times;
    for (const StaticCostEntry& e : analysis.entries) {
        ops.push_back(static_cast<double>(e.total_ops));
        times.push_back(e.median_ms);
    }
    const std::vector<double> ops_ranks = base::AverageRanks(ops);
    const std::vector<double> time_ranks = base::AverageRanks(times);
    for (std::size_t i = 0; i < analysis.entries.size(); ++i) {
        analysis.entries[i].ops_rank = ops_ranks[i];
        analysis.entries[i].time_rank = time_ranks[i];
    }
    analysis.spearman_rho = base::SpearmanRho(ops, times);
    if (std::isnan(analysis.spearman_rho)) {
        analysis.note = "the counts or the times are all equal";
    }
    std::vector<std::size_t> order(analysis.entries.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const StaticCostEntry& x = analysis.entries[a];
        const StaticCostEntry& y = analysis.entries[b];
        return std::abs(x.ops_rank - x.time_rank) > std::abs(y.ops_rank - y.time_rank);
    });
    order.resize(std::min(order.size(), kMisleadingCount));
    analysis.misleading = order;
    return analysis;
}

namespace {
ReportModelResult BuildReportModelUnchecked(const ReportInputs& inputs,
                                            const ReportOptions& options);
}  // namespace

ReportModelResult BuildReportModel(const ReportInputs& inputs, const ReportOptions& options) {
    // LoadReportInputs checks every field the model needs; a field it does not know of that has
    // the wrong type must still be an error naming the files, never an abort.
    try {
        return BuildReportModelUnchecked(inputs, options);
    } catch (const nlohmann::json::exception& e) {
        ReportModelResult out;
        out.error =
                fmt::format("{} or {}: a field has an unexpected type: {}",
                            inputs.results_path.string(), inputs.manifest_path.string(), e.what());
        return out;
    }
}

namespace {
ReportModelResult BuildReportModelUnchecked(const ReportInputs& inputs,
                                            const ReportOptions& options) {
    ReportModelResult out;
    ReportModel model;
    model.options = options;
    model.inputs = &inputs;
    model.clock = inputs.clock;
    model.reference = inputs.FindByPreset(kReferencePreset);
    if (model.reference != nullptr && !model.reference->ok) {
        model.reference = nullptr;  // a failed reference has no images to compare with
    }

    // Reference images per view, read once.
    ImageCache reference_images;
    if (model.reference != nullptr) {
        for (const ViewImage& v : model.reference->views) {
            if (v.image.empty()) {
                continue;
            }
            std::optional<RgbaImage> image = LoadImage(v.image, &out.error);
            if (!image) {
                return out;
            }
            reference_images.emplace(v.view, ReferenceImage(std::move(*image)));
        }
    }

    // Accuracy: every configuration's error against the reference, on the cores we have.
    std::vector<ViewErrors> errors(inputs.configurations.size());
    base::ParallelFor(inputs.configurations.size(),
                      static_cast<int>(std::thread::hardware_concurrency()), [&](std::size_t i) {
                          if (inputs.configurations[i].ok) {
                              errors[i] = CompareWithReference(inputs.configurations[i],
                                                               reference_images, "the reference's",
                                                               nullptr, true);
                          }
                      });
    std::vector<double> times;
    std::vector<double> losses;
    for (std::size_t i = 0; i < inputs.configurations.size(); ++i) {
        const MeasuredConfiguration& c = inputs.configurations[i];
        if (!errors[i].error.empty()) {
            out.error = errors[i].error;
            return out;
        }
        AccuracyEntry entry;
        entry.configuration = &c;
        entry.is_reference = &c == model.reference;
        entry.median_ms = c.MedianOn(model.clock);
        if (!c.ok) {
            entry.note = "FAILED: " + (c.driver_valid ? "GL error " + c.gl_error
                                                      : std::string("Mesa compile/link failed"));
            ++model.failed_configurations;
        } else if (model.reference == nullptr) {
            entry.note = "no reference configuration (preset 'reference') rendered";
        } else if (errors[i].views == 0) {
            entry.note = "no images to compare";
        } else if (std::isnan(entry.median_ms)) {
            entry.note = fmt::format("not timed ({} clock)", TimingClockName(model.clock));
        } else {
            const double n = errors[i].views;
            entry.measured = true;
            entry.views_compared = errors[i].views;
            entry.psnr_db = PsnrFromMse(errors[i].mse_sum / n);
            entry.ssim = errors[i].ssim_sum / n;
            entry.share_visible = errors[i].share_sum / n;
        }
        times.push_back(entry.measured ? entry.median_ms : kNaN);
        losses.push_back(entry.measured ? entry.SsimLoss() : kNaN);
        model.accuracy.push_back(std::move(entry));
    }
    model.frontier = ParetoFrontier(times, losses);
    for (std::size_t i : model.frontier) {
        model.accuracy[i].on_frontier = true;
    }
    auto accuracy_of = [&](const MeasuredConfiguration* c) -> const AccuracyEntry* {
        for (const AccuracyEntry& e : model.accuracy) {
            if (e.configuration == c) {
                return &e;
            }
        }
        return nullptr;
    };

    // The whitepaper table.
    for (const WhitepaperRow& row : WhitepaperRows()) {
        RowComparison comparison;
        comparison.row = row;
        comparison.baseline = {row.baseline_preset, inputs.FindByPreset(row.baseline_preset)};
        comparison.candidate = {row.candidate_preset, inputs.FindByPreset(row.candidate_preset)};
        const MeasuredConfiguration* base = comparison.baseline.configuration;
        const MeasuredConfiguration* cand = comparison.candidate.configuration;
        if (base == nullptr || cand == nullptr) {
            comparison.verdict = Verdict::kFailed;
            comparison.verdict_reason =
                    fmt::format("no configuration in the results carries preset '{}'",
                                base == nullptr ? row.baseline_preset : row.candidate_preset);
        } else if (!base->ok || !cand->ok) {
            comparison.verdict = Verdict::kFailed;
            comparison.verdict_reason =
                    fmt::format("configuration {} failed", !base->ok ? base->id : cand->id);
        } else {
            const PairsOfFrames pairs = PairsFor(inputs, *base, *cand, model.clock);
            comparison.pairs_source = pairs.source;
            if (pairs.error.empty()) {
                comparison.ratio =
                        ComparePairs(pairs.baseline_ms, pairs.candidate_ms,
                                     pairs.contended_baseline_ms, pairs.contended_candidate_ms);
                comparison.split = CompareSplitPairs(pairs.baseline_ms, pairs.candidate_ms);
            } else {
                comparison.ratio.error = pairs.error;
            }
            comparison.verdict =
                    GradeRow(row, comparison.ratio, &comparison.split, &comparison.verdict_reason);
            ChangeFromRatio(comparison.ratio, &comparison.change_percent, &comparison.change_ci);
            comparison.resolution_points =
                    (comparison.change_ci.high - comparison.change_ci.low) / 2;
            comparison.measured_why = MeasuredWhy(inputs, *base, *cand);
            comparison.odd_change_percent = PerformanceChangePercent(comparison.split.odd.ratio);
            comparison.even_change_percent = PerformanceChangePercent(comparison.split.even.ratio);
            const double d = comparison.split.disagreement_percent_points;
            if (std::isfinite(d) && (std::isnan(model.largest_split_half_disagreement) ||
                                     d > model.largest_split_half_disagreement)) {
                model.largest_split_half_disagreement = d;
                model.largest_split_half_row = row.number;
            }
            comparison.time_change_ms = cand->MedianOn(model.clock) - base->MedianOn(model.clock);
            const AccuracyEntry* a = accuracy_of(base);
            const AccuracyEntry* b = accuracy_of(cand);
            if (a != nullptr && b != nullptr && a->measured && b->measured) {
                comparison.ssim_loss_change = b->SsimLoss() - a->SsimLoss();
                comparison.psnr_change_db = b->psnr_db - a->psnr_db;
            }
        }
        model.rows.push_back(std::move(comparison));
    }

    // What the clock buys: each recorded comparison's pair noise on both clocks.
    for (const MeasuredComparison& c : inputs.comparisons) {
        ClockNoiseRow row;
        row.label = c.label;
        row.pairs = static_cast<int>(c.baseline_ms.size());
        row.decision = c.error.empty() ? c.decision : "failed: " + c.error;
        const PairedRatio ratio = ComparePairs(c.baseline_ms, c.candidate_ms);
        if (ratio.error.empty()) {
            row.half_width_points = (PerformanceChangePercent(ratio.ci.low) -
                                     PerformanceChangePercent(ratio.ci.high)) /
                                    2;
        }
        row.pair_sd_clock_percent = 100 * LogRatioSd(c.baseline_ms, c.candidate_ms);
        row.pair_sd_wall_percent = 100 * LogRatioSd(c.baseline_wall_ms, c.candidate_wall_ms);
        model.clock_noise.push_back(row);
    }

    // Static cost versus time.
    std::map<std::string, const stagefiles::ManifestVariant*> manifest_variants;
    for (const stagefiles::ManifestVariant& v : inputs.manifest.variants) {
        manifest_variants[v.id] = &v;
    }
    std::vector<StaticCostEntry> static_entries;
    for (const MeasuredConfiguration& c : inputs.configurations) {
        if (!c.ok || !HasDefaultPasses(c, inputs) || std::isnan(c.MedianOn(model.clock))) {
            continue;
        }
        auto it = manifest_variants.find(c.variant);
        if (it == manifest_variants.end()) {
            continue;
        }
        const std::optional<stagefiles::ManifestStages>& stages = it->second->stages;
        if (!stages || !stages->vertex.cost || !stages->fragment.cost) {
            continue;
        }
        const stagefiles::StageCostEntry& vertex = *stages->vertex.cost;
        const stagefiles::StageCostEntry& fragment = *stages->fragment.cost;
        StaticCostEntry entry;
        entry.configuration = &c;
        entry.vertex_ops = vertex.total_ops;
        entry.fragment_ops = fragment.total_ops;
        entry.total_ops = entry.vertex_ops + entry.fragment_ops;
        entry.median_ms = c.MedianOn(model.clock);
        static_entries.push_back(entry);
    }
    model.static_cost = AnalyseStaticCost(std::move(static_entries));

    // Validation.
    ValidationSummary& validation = model.validation;
    validation.counts = inputs.manifest.counts;
    for (const stagefiles::ManifestVariant& v : inputs.manifest.variants) {
        if (!v.valid.value_or(true)) {
            validation.glslang_invalid.push_back(v.id);
        }
    }
    validation.pruned_by_rule = PrunedRuleRows(inputs.manifest);
    validation.configurations = static_cast<int>(inputs.configurations.size());
    for (const MeasuredConfiguration& c : inputs.configurations) {
        if (!c.ok) {
            validation.failed.push_back(&c);
        }
    }
    for (const stagefiles::ResultsDisagreement& d : inputs.results.disagreements) {
        validation.disagreements.push_back({d.variant, d.glslang_valid, d.mesa_valid});
    }
    for (const stagefiles::DiagnosticEntry& d : inputs.results.diagnostics) {
        validation.run_diagnostics.push_back(d.text.value_or(d.message));
    }

    // Image panels: every whitepaper preset's configuration, once, at the chosen views.
    std::vector<std::string> views = options.panel_views;
    if (views.empty() && !inputs.timing_view.empty()) {
        views.push_back(inputs.timing_view);
    }
    std::vector<const MeasuredConfiguration*> shown;
    for (const WhitepaperRow& row : WhitepaperRows()) {
        for (const std::string& preset : {row.baseline_preset, row.candidate_preset}) {
            const MeasuredConfiguration* c = inputs.FindByPreset(preset);
            if (c != nullptr && c != model.reference &&
                std::find(shown.begin(), shown.end(), c) == shown.end()) {
                shown.push_back(c);
            }
        }
    }
    for (const std::string& view : views) {
        auto ref = reference_images.find(view);
        for (const MeasuredConfiguration* c : shown) {
            ImagePanel panel;
            panel.title = PresetTitle(*c);
            panel.configuration = c;
            panel.view = view;
            const std::filesystem::path path = c->ImageAt(view);
            if (!c->ok) {
                panel.note = "FAILED: no image (the configuration did not compile or render)";
            } else if (path.empty()) {
                panel.note = "no image was written at this view";
            } else if (ref == reference_images.end()) {
                panel.note = "no reference image at this view";
            } else {
                std::optional<RgbaImage> image = LoadImage(path, &out.error);
                if (!image) {
                    return out;
                }
                // Images of one view have one size; another size is a corrupt input, and a heat
                // map of two sizes would be empty (the report then failed writing it, exit 3).
                const RgbaImage& reference = ref->second.image;
                if (image->width != reference.width || image->height != reference.height) {
                    out.error = fmt::format(
                            "{}: {}x{} image, but the reference configuration's at view '{}' is "
                            "{}x{}; render the run again",
                            path.string(), image->width, image->height, view, reference.width,
                            reference.height);
                    return out;
                }
                panel.image = std::move(*image);
                panel.reference = reference;
                panel.heat_map = DifferenceHeatMap(panel.image, panel.reference, kHeatMapFullScale);
                panel.psnr_db = Psnr(panel.image, panel.reference);
                panel.ssim = Ssim(panel.image, panel.reference);
                panel.share_visible = ShareAboveThreshold(panel.image, panel.reference,
                                                          kVisibleDifferenceThreshold);
            }
            model.panels.push_back(std::move(panel));
        }
    }

    // Reflection techniques against planar reflection, and the depth optics against full.
    std::map<const MeasuredConfiguration*, ImageCache> baseline_images;
    out.error = BuildTechniques({std::begin(kReflectionPresets), std::end(kReflectionPresets)},
                                inputs, model.clock, &baseline_images, &model.reflections);
    if (out.error.empty()) {
        out.error = BuildTechniques({std::begin(kOpticsPresets), std::end(kOpticsPresets)}, inputs,
                                    model.clock, &baseline_images, &model.optics);
    }
    if (!out.error.empty()) {
        return out;
    }
    // One view keeps the section short: the first panel view, where the image panels look.
    const std::string panel_view = views.empty() ? std::string() : views.front();
    for (const TechniqueComparison& t : model.reflections) {
        if (t.context != "full effect" || panel_view.empty()) {
            continue;
        }
        auto images = baseline_images.find(t.baseline.configuration);
        model.reflection_panels.push_back(TechniquePanel(
                t, panel_view, images == baseline_images.end() ? nullptr : &images->second,
                &out.error));
        if (!out.error.empty()) {
            return out;
        }
    }
    out.model = std::move(model);
    return out;
}

}  // namespace

}  // namespace tidepool::report
