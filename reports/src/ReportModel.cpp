#include "tidepool/report/ReportModel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>
#include <iterator>
#include <map>
#include <numeric>
#include <thread>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A configuration rendered with the default pass options (256 reflection and refraction,
// oblique clip, no low-resolution water, culling, depth fog): only these share the pass work, so
// their static counts are comparable with their times.
bool HasDefaultPasses(const MeasuredConfiguration& c) {
    return c.reflection_size == 256 && c.refraction_size == 256 && c.clip == "oblique" &&
           !c.low_res_water && c.culling && c.depth_fog;
}

// Ranks 1..n, ties getting the average of their ranks.
std::vector<double> Ranks(const std::vector<double>& values) {
    std::vector<std::size_t> order(values.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    std::vector<double> ranks(values.size());
    std::size_t i = 0;
    while (i < order.size()) {
        std::size_t j = i;
        while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) {
            ++j;
        }
        const double rank = (static_cast<double>(i) + static_cast<double>(j)) / 2.0 + 1.0;
        for (std::size_t k = i; k <= j; ++k) {
            ranks[order[k]] = rank;
        }
        i = j + 1;
    }
    return ranks;
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

using ImageCache = std::map<std::string, RgbaImage>;

// Reads `path`, or returns the error naming it.
std::optional<RgbaImage> LoadImage(const std::filesystem::path& path, std::string* error) {
    ImageResult read = ReadPng(path);
    if (!read.image) {
        *error = read.error.empty() ? path.string() + ": cannot read image" : read.error;
        return std::nullopt;
    }
    return std::move(*read.image);
}

// Compares every image of `c` with the image of `reference` at the same view; `whose` names
// the other side in a size-mismatch error ("the reference's"). Fills `per_view` when not null.
ViewErrors CompareWithReference(const MeasuredConfiguration& c, const ImageCache& reference,
                                std::string_view whose = "the reference's",
                                std::vector<ViewError>* per_view = nullptr) {
    ViewErrors errors;
    for (const ViewImage& v : c.views) {
        auto ref = reference.find(v.view);
        if (v.image.empty() || ref == reference.end()) {
            continue;
        }
        std::optional<RgbaImage> image = LoadImage(v.image, &errors.error);
        if (!image) {
            return errors;
        }
        const RgbaImage& r = ref->second;
        if (image->width != r.width || image->height != r.height) {
            errors.error = fmt::format("{}: {}x{} image, but {} at view '{}' is {}x{}",
                                       v.image.string(), image->width, image->height, whose,
                                       v.view, r.width, r.height);
            return errors;
        }
        const ViewError view{v.view, Psnr(*image, r), Ssim(*image, r),
                             ShareAboveThreshold(*image, r, kVisibleDifferenceThreshold)};
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
        images[v.view] = std::move(*image);
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
        return "Local objects and terrain are missing from the reflection: only the sky cube map "
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

std::string PsnrText(double psnr_db) {
    return std::isinf(psnr_db) ? std::string("identical") : fmt::format("{:.1f} dB", psnr_db);
}

// Pass names, draw calls and median of one side at the timing view.
void FillSide(const MeasuredConfiguration* c, const std::string& timing_view, TimingClock clock,
              std::vector<std::string>* passes, std::optional<int>* draw_calls,
              double* median_ms) {
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
                                     const ReportOptions& options, TimingClock clock) {
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
            problem = fmt::format("configuration {} (preset '{}') FAILED",
                                  side->configuration->id, side->preset);
        }
        if (!problem.empty()) {
            t.note += (t.note.empty() ? "" : "; ") + problem;
        }
    }
    if (t.note.empty()) {
        t.ratio = ComparePaired(base->SamplesOn(clock), cand->SamplesOn(clock), options.seed);
        if (!t.ratio.error.empty()) {
            t.note = fmt::format("no paired time on the {} clock: {}", TimingClockName(clock),
                                 t.ratio.error);
        }
        ChangeFromRatio(t.ratio, &t.change_percent, &t.change_ci);
        const double floor = std::isnan(options.noise_floor_percent)
                                     ? 0.0
                                     : std::max(0.0, options.noise_floor_percent);
        if (std::isfinite(t.change_ci.low) && t.change_ci.low > floor) {
            t.direction = +1;
        } else if (std::isfinite(t.change_ci.high) && t.change_ci.high < -floor) {
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
        t->reading += fmt::format(" {}: {} ({} against {} over all views).",
                                  t->kind == TechniqueKind::kDepthOptics ? "Most changed view"
                                                                         : "Worst view",
                                  worst->view, PsnrText(worst->psnr_db), PsnrText(t->psnr_db));
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
    panel.title = fmt::format("{}: {} beside planar reflection ({}); the \"reference\" side is "
                              "the planar image",
                              t.technique, t.candidate.preset, t.baseline.preset);
    const MeasuredConfiguration* cand = t.candidate.configuration;
    const MeasuredConfiguration* base = t.baseline.configuration;
    auto baseline_image = baseline_images != nullptr ? baseline_images->find(view)
                                                     : ImageCache::const_iterator{};
    if (cand == nullptr) {
        panel.note = fmt::format("MISSING: no configuration carries preset '{}'",
                                 t.candidate.preset);
    } else if (!cand->ok) {
        panel.note = "FAILED: no image (the configuration did not compile or render)";
    } else if (cand->ImageAt(view).empty()) {
        panel.note = "no image was written at this view";
    } else if (base == nullptr || !base->ok || baseline_images == nullptr ||
               baseline_image == baseline_images->end()) {
        panel.note = fmt::format("no planar image ({}) at this view to compare with",
                                 t.baseline.preset);
    } else {
        std::optional<RgbaImage> image = LoadImage(cand->ImageAt(view), error);
        if (!image) {
            return panel;
        }
        const RgbaImage& planar = baseline_image->second;
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
                            const ReportInputs& inputs, const ReportOptions& options,
                            TimingClock clock,
                            std::map<const MeasuredConfiguration*, ImageCache>* baseline_images,
                            std::vector<TechniqueComparison>* out) {
    for (const TechniquePresets& p : presets) {
        out->push_back(CompareTechnique(p, inputs, options, clock));
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

}  // namespace

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
    case Verdict::kSameDirectionOnly:
        return "same-direction-only";
    case Verdict::kOpposite:
        return "opposite";
    case Verdict::kInconclusive:
        return "inconclusive";
    case Verdict::kFailed:
        return "failed";
    }
    return "failed";
}

Verdict GradeRow(const WhitepaperRow& row, const PairedRatio& measured, const SplitHalf* split,
                 double magnitude_tolerance_percent_points, double noise_floor_percent,
                 std::string* reason) {
    const double tolerance = std::isnan(magnitude_tolerance_percent_points)
                                     ? 0.0
                                     : std::max(0.0, magnitude_tolerance_percent_points);
    const double floor =
            std::isnan(noise_floor_percent) ? 0.0 : std::max(0.0, noise_floor_percent);
    if (!std::isfinite(measured.ratio) || measured.rounds == 0) {
        *reason = measured.error.empty() ? "no measurement" : measured.error;
        return Verdict::kFailed;
    }
    const double change = PerformanceChangePercent(measured.ratio);
    // A larger frame-time ratio is a lower frame rate, so the interval's ends swap.
    const double low = PerformanceChangePercent(measured.ci.high);
    const double high = std::isfinite(measured.ci.low) && measured.ci.low > 0
                                ? PerformanceChangePercent(measured.ci.low)
                                : std::numeric_limits<double>::infinity();
    if (!std::isfinite(low) || !std::isfinite(high)) {
        *reason = "the interval is unbounded (too few rounds)";
        return Verdict::kInconclusive;
    }
    const std::string interval = fmt::format("[{:+.1f}%, {:+.1f}%]", low, high);
    // The category comes from the estimate; how firmly the run supports it is said beside it
    // (the interval, and whether the odd and even rounds agree), never by changing category:
    // between consecutive runs the estimate of one comparison moves by several points, more
    // than its within-run interval shows, so interval-based categories flipped from run to run.
    std::string evidence;
    if (low <= 0.0 && high >= 0.0) {
        evidence = fmt::format("; weakly supported: the interval {} includes no change", interval);
    } else {
        evidence = fmt::format("; interval {}", interval);
    }
    if (split != nullptr) {
        const double odd = PerformanceChangePercent(split->odd.ratio);
        const double even = PerformanceChangePercent(split->even.ratio);
        if (std::isfinite(odd) && std::isfinite(even) && odd * even < 0) {
            evidence += fmt::format("; the odd rounds say {:+.1f}%, the even {:+.1f}%", odd, even);
        }
    }
    if (row.kind == FigureKind::kNegligible && std::fabs(change) <= tolerance) {
        *reason = fmt::format("{:+.1f}% lies within {:.0f} points of no change, as the "
                              "whitepaper's <1%{}",
                              change, tolerance, evidence);
        return Verdict::kSameDirectionAndMagnitude;
    }
    if (std::fabs(change) < floor) {
        *reason = fmt::format("{:+.1f}% is below the {:.0f}% floor: no direction to compare{}",
                              change, floor, evidence);
        return Verdict::kInconclusive;
    }
    const int direction = change > 0 ? +1 : -1;
    if (direction != row.expected_sign) {
        *reason = fmt::format("{:+.1f}% is {} where the whitepaper says {}{}", change,
                              direction > 0 ? "faster" : "slower",
                              row.expected_sign > 0 ? "faster" : "slower", evidence);
        return Verdict::kOpposite;
    }
    if (row.kind == FigureKind::kDirection) {
        *reason = fmt::format("the whitepaper's figure is qualitative: direction only{}",
                              evidence);
        return Verdict::kSameDirectionOnly;
    }
    const double figure = row.kind == FigureKind::kNegligible ? 0.0 : row.whitepaper_percent;
    if (std::fabs(change - figure) <= tolerance) {
        *reason = fmt::format("{:+.1f}% lies within {:.0f} points of the whitepaper's {:+.1f}%{}",
                              change, tolerance, figure, evidence);
        return Verdict::kSameDirectionAndMagnitude;
    }
    *reason = fmt::format("{:+.1f}% is not within {:.0f} points of the whitepaper's {}{}", change,
                          tolerance,
                          row.kind == FigureKind::kNegligible ? std::string("<1%")
                                                              : fmt::format("{:+.1f}%", figure),
                          evidence);
    return Verdict::kSameDirectionOnly;
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
    const std::vector<double> ops_ranks = Ranks(ops);
    const std::vector<double> time_ranks = Ranks(times);
    for (std::size_t i = 0; i < analysis.entries.size(); ++i) {
        analysis.entries[i].ops_rank = ops_ranks[i];
        analysis.entries[i].time_rank = time_ranks[i];
    }
    analysis.spearman_rho = SpearmanRho(ops, times);
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

ReportModelResult BuildReportModel(const ReportInputs& inputs, const ReportOptions& options) {
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
            reference_images[v.view] = std::move(*image);
        }
    }

    // Accuracy: every configuration's error against the reference, on the cores we have.
    std::vector<ViewErrors> errors(inputs.configurations.size());
    {
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::future<void>> workers;
        std::atomic<std::size_t> next{0};
        for (unsigned w = 0; w < cores; ++w) {
            workers.push_back(std::async(std::launch::async, [&] {
                for (std::size_t i = next++; i < inputs.configurations.size(); i = next++) {
                    if (inputs.configurations[i].ok) {
                        errors[i] = CompareWithReference(inputs.configurations[i],
                                                         reference_images);
                    }
                }
            }));
        }
        for (auto& w : workers) {
            w.get();
        }
    }
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
            comparison.verdict_reason = fmt::format(
                    "no configuration in the results carries preset '{}'",
                    base == nullptr ? row.baseline_preset : row.candidate_preset);
        } else if (!base->ok || !cand->ok) {
            comparison.verdict = Verdict::kFailed;
            comparison.verdict_reason = fmt::format("configuration {} failed",
                                                    !base->ok ? base->id : cand->id);
        } else {
            comparison.ratio = ComparePaired(base->SamplesOn(model.clock),
                                             cand->SamplesOn(model.clock), options.seed);
            comparison.split = CompareSplitHalves(base->SamplesOn(model.clock),
                                                  cand->SamplesOn(model.clock), options.seed);
            comparison.verdict = GradeRow(row, comparison.ratio, &comparison.split,
                                          options.magnitude_tolerance_percent_points,
                                          options.noise_floor_percent,
                                          &comparison.verdict_reason);
            ChangeFromRatio(comparison.ratio, &comparison.change_percent, &comparison.change_ci);
            comparison.odd_change_percent = PerformanceChangePercent(comparison.split.odd.ratio);
            comparison.even_change_percent =
                    PerformanceChangePercent(comparison.split.even.ratio);
            const double d = comparison.split.disagreement_percent_points;
            if (std::isfinite(d) && (std::isnan(model.largest_split_half_disagreement) ||
                                     d > model.largest_split_half_disagreement)) {
                model.largest_split_half_disagreement = d;
                model.largest_split_half_row = row.number;
            }
            comparison.time_change_ms =
                    cand->MedianOn(model.clock) - base->MedianOn(model.clock);
            const AccuracyEntry* a = accuracy_of(base);
            const AccuracyEntry* b = accuracy_of(cand);
            if (a != nullptr && b != nullptr && a->measured && b->measured) {
                comparison.ssim_loss_change = b->SsimLoss() - a->SsimLoss();
                comparison.psnr_change_db = b->psnr_db - a->psnr_db;
            }
        }
        model.rows.push_back(std::move(comparison));
    }

    // Static cost versus time.
    std::map<std::string, const nlohmann::json*> manifest_variants;
    for (const nlohmann::json& v : inputs.manifest["variants"]) {
        if (v.is_object() && v.contains("id") && v["id"].is_string()) {
            manifest_variants[v["id"].get<std::string>()] = &v;
        }
    }
    std::vector<StaticCostEntry> static_entries;
    for (const MeasuredConfiguration& c : inputs.configurations) {
        if (!c.ok || !HasDefaultPasses(c) || std::isnan(c.MedianOn(model.clock))) {
            continue;
        }
        auto it = manifest_variants.find(c.variant);
        if (it == manifest_variants.end()) {
            continue;
        }
        const nlohmann::json& stages = it->second->value("stages", nlohmann::json::object());
        const nlohmann::json vertex = stages.value("vertex", nlohmann::json::object())
                                              .value("cost", nlohmann::json::object());
        const nlohmann::json fragment = stages.value("fragment", nlohmann::json::object())
                                                .value("cost", nlohmann::json::object());
        if (!vertex.contains("total_ops") || !fragment.contains("total_ops")) {
            continue;
        }
        StaticCostEntry entry;
        entry.configuration = &c;
        entry.vertex_ops = vertex.value("total_ops", 0);
        entry.fragment_ops = fragment.value("total_ops", 0);
        entry.total_ops = entry.vertex_ops + entry.fragment_ops;
        entry.median_ms = c.MedianOn(model.clock);
        static_entries.push_back(entry);
    }
    model.static_cost = AnalyseStaticCost(std::move(static_entries));

    // Validation.
    ValidationSummary& validation = model.validation;
    validation.counts = inputs.manifest["counts"];
    for (const nlohmann::json& v : inputs.manifest["variants"]) {
        if (v.is_object() && !v.value("valid", true)) {
            validation.glslang_invalid.push_back(v.value("id", std::string("?")));
        }
    }
    if (auto pruned = inputs.manifest.find("pruned");
        pruned != inputs.manifest.end() && pruned->is_array()) {
        for (const nlohmann::json& p : *pruned) {
            if (p.is_object()) {
                validation.pruned.emplace_back(p.value("id", std::string()),
                                               p.value("rule", std::string()));
            }
        }
    }
    validation.configurations = static_cast<int>(inputs.configurations.size());
    for (const MeasuredConfiguration& c : inputs.configurations) {
        if (!c.ok) {
            validation.failed.push_back(&c);
        }
    }
    if (auto d = inputs.results.find("disagreements");
        d != inputs.results.end() && d->is_array()) {
        for (const nlohmann::json& item : *d) {
            if (item.is_object()) {
                validation.disagreements.push_back({item.value("variant", std::string()),
                                                    item.value("glslang_valid", false),
                                                    item.value("mesa_valid", false)});
            }
        }
    }
    if (auto d = inputs.results.find("diagnostics");
        d != inputs.results.end() && d->is_array()) {
        for (const nlohmann::json& item : *d) {
            validation.run_diagnostics.push_back(
                    item.is_object() ? item.value("text", item.value("message", std::string()))
                                     : item.dump());
        }
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
                panel.image = std::move(*image);
                panel.reference = ref->second;
                panel.heat_map = DifferenceHeatMap(panel.image, panel.reference, kHeatMapFullScale);
                panel.psnr_db = Psnr(panel.image, panel.reference);
                panel.ssim = Ssim(panel.image, panel.reference);
                panel.share_visible =
                        ShareAboveThreshold(panel.image, panel.reference, kVisibleDifferenceThreshold);
            }
            model.panels.push_back(std::move(panel));
        }
    }

    // Reflection techniques against planar reflection, and the depth optics against full.
    std::map<const MeasuredConfiguration*, ImageCache> baseline_images;
    out.error = BuildTechniques({std::begin(kReflectionPresets), std::end(kReflectionPresets)},
                                inputs, options, model.clock, &baseline_images,
                                &model.reflections);
    if (out.error.empty()) {
        out.error = BuildTechniques({std::begin(kOpticsPresets), std::end(kOpticsPresets)},
                                    inputs, options, model.clock, &baseline_images,
                                    &model.optics);
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

}  // namespace tidepool::report
