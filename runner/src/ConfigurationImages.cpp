// A configuration's unit of the render (ConfigurationImages.h).
#include "ConfigurationImages.h"

#include "tidepool/Manifest.h"
#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

namespace tidepool::runner {

void ReferenceImages::Keep(const std::string& view, const base::RgbaImage& image) {
    auto kept = std::make_shared<const Kept>(image);
    std::lock_guard<std::mutex> lock(mutex_);
    views_[view] = std::move(kept);
}

std::optional<base::ImageAccuracy> ReferenceImages::Compare(const std::string& view,
                                                            const base::RgbaImage& image) const {
    std::shared_ptr<const Kept> kept;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto found = views_.find(view);
        if (found == views_.end()) {
            return std::nullopt;
        }
        kept = found->second;
    }
    if (kept->image.width != image.width || kept->image.height != image.height) {
        return std::nullopt;
    }
    return base::MeasureAccuracy(image, kept->image, kept->ssim);
}

const CameraView* TimingView(const RunOptions& options) {
    for (const CameraView& view : options.views) {
        if (options.timing_view.empty() || view.name == options.timing_view) {
            return &view;
        }
    }
    return nullptr;
}

std::optional<std::size_t> ReferenceConfiguration(const RunOptions& options) {
    for (std::size_t i = 0; i < options.configurations.size(); ++i) {
        const std::vector<std::string>& presets = options.configurations[i].presets;
        if (std::find(presets.begin(), presets.end(), options.reference_preset) != presets.end()) {
            return i;
        }
    }
    return std::nullopt;
}

bool ProbesComparisons(const RunOptions& options) {
    return options.rule.min_pairs > kProbePairs && !options.comparisons.empty() &&
           options.workers <= 1;
}

std::vector<WorkUnit> RunWorkOrder(const RunOptions& options) {
    std::vector<std::size_t> compared;
    for (const TimedComparison& c : options.comparisons) {
        for (std::size_t i : {c.baseline, c.candidate}) {
            if (i < options.configurations.size() &&
                std::find(compared.begin(), compared.end(), i) == compared.end()) {
                compared.push_back(i);
            }
        }
    }
    return RenderWorkOrder(options.comparisons.size(), options.configurations.size(),
                           ReferenceConfiguration(options), compared, ProbesComparisons(options));
}

const DriverVerdict& PrepareConfiguration(RenderWorker& w, const RunOptions& options, std::size_t i,
                                          bool warm) {
    auto found = w.prepared.find(i);
    if (found != w.prepared.end()) {
        return found->second;
    }
    const RenderConfiguration& c = options.configurations[i];
    DriverVerdict verdict = w.renderer->Prepare(c);
    const CameraView* timing_view = TimingView(options);
    if (warm && verdict.valid && timing_view != nullptr) {
        for (int f = 0; f < options.warmup_frames; ++f) {
            w.renderer->RenderFrame(c, *timing_view);
            w.renderer->Finish();
        }
    }
    return w.prepared.emplace(i, std::move(verdict)).first->second;
}

long FramesPerConfiguration(const RunOptions& options) {
    return static_cast<long>(options.views.size()) + options.coarse_frames;
}

void RenderConfigurationUnit(RenderWorker& w, const ImageUnitContext& context, std::size_t i,
                             ConfigurationResult& r) {
    const RunOptions& options = context.options;
    const CameraView* timing_view = TimingView(options);
    const bool is_reference = ReferenceConfiguration(options) == i;
    auto step = [&](long frames) {
        if (context.meter != nullptr) {
            context.meter->Step(ProgressMeter::kImage, r.configuration.id, frames);
        }
    };
    // A configuration's own unit needs no warm-up: its images, every view once, come before its
    // timed frames and warm it.
    r.verdict = PrepareConfiguration(w, options, i, false);
    if (!r.verdict.valid) {
        step(FramesPerConfiguration(options));
        return;
    }
    for (const CameraView& view : options.views) {
        ViewResult view_result;
        view_result.view = view.name;
        view_result.frame = w.renderer->RenderFrame(r.configuration, view);
        w.renderer->Finish();
        if (!view_result.frame.gl_error.empty() && r.gl_error.empty()) {
            r.gl_error = fmt::format("{} (view {})", view_result.frame.gl_error, view.name);
        }
        const base::RgbaImage image = w.renderer->ReadImage();
        if (is_reference) {
            context.references.Keep(view.name, image);
        }
        view_result.accuracy = context.references.Compare(view.name, image);
        if (options.write_images) {
            const std::string name = fmt::format("images/{}-{}.png",
                                                 SanitiseFileName(r.configuration.id), view.name);
            const std::string write_error = base::WritePngAtomically(options.out_dir / name, image);
            if (write_error.empty()) {
                view_result.image_path = name;
            } else {
                std::lock_guard<std::mutex> lock(context.errors_mutex);
                context.write_errors.push_back(write_error);
            }
        }
        if (&view == timing_view) {
            r.passes = view_result.frame.passes;
            r.draw_calls = view_result.frame.draw_calls;
        }
        r.views.push_back(std::move(view_result));
        step(1);
    }
    if (timing_view == nullptr) {
        step(options.coarse_frames);
        return;
    }
    std::vector<double> plan_ms;
    for (int f = 0; f < options.coarse_frames; ++f) {
        FrameReport frame;
        const FrameTime t = w.timer->Time(r.configuration, *timing_view, &frame);
        r.samples_ms.push_back({t.wall_ms});
        r.cpu_samples_ms.push_back({t.ms});
        plan_ms.push_back(frame.plan_seconds * 1000.0);
        if (!frame.gl_error.empty() && r.gl_error.empty()) {
            r.gl_error = frame.gl_error;
        }
        step(1);
    }
    r.plan_ms_median = base::Median(plan_ms);
    std::vector<double> wall_ms;
    for (const std::vector<double>& sample : r.samples_ms) {
        wall_ms.insert(wall_ms.end(), sample.begin(), sample.end());
    }
    if (context.meter != nullptr && !wall_ms.empty()) {
        context.meter->ConfigurationCost(i, base::Median(wall_ms) / 1000.0);
    }
}

base::StoppingRule ComparisonRule(const RunOptions& options, const TimedComparison& comparison) {
    base::StoppingRule rule = options.rule;
    rule.boundaries_points = comparison.boundaries_points;
    return rule;
}

void TimeComparisonUnit(RenderWorker& w, const RunOptions& options, ComparisonResult& out,
                        const std::function<void(const ComparisonTiming& so_far)>& after_look,
                        ComparisonPart part) {
    const TimedComparison& c = out.comparison;
    const CameraView* timing_view = TimingView(options);
    if (out.error.empty() && timing_view == nullptr) {
        out.error = "no timing view";
    }
    if (out.error.empty()) {
        for (std::size_t i : {c.baseline, c.candidate}) {
            if (!PrepareConfiguration(w, options, i, true).valid) {
                out.error = fmt::format("configuration {} did not compile in Mesa",
                                        options.configurations[i].id);
                break;
            }
        }
    }
    if (!out.error.empty()) {
        return;
    }
    const RenderConfiguration& baseline = options.configurations[c.baseline];
    const RenderConfiguration& candidate = options.configurations[c.candidate];
    const TimeSide time_side = [&](bool is_candidate) {
        return w.timer->Time(is_candidate ? candidate : baseline, *timing_view);
    };
    if (part == ComparisonPart::kProbe) {
        out.timing = ProbeComparison(time_side, kProbePairs, ComparisonRule(options, c));
        if (after_look) {
            after_look(out.timing);
        }
        return;
    }
    if (!out.timing.samples.baseline_ms.empty()) {
        // On from a probe taken seconds or minutes ago: other units have run on this thread
        // since, so both sides are warmed again before their next timed frame.
        for (int f = 0; f < options.warmup_frames; ++f) {
            for (const RenderConfiguration* side : {&baseline, &candidate}) {
                w.renderer->RenderFrame(*side, *timing_view);
                w.renderer->Finish();
            }
        }
    }
    out.timing = TimeComparison(time_side, ComparisonRule(options, c), after_look,
                                std::move(out.timing));
    TimePassesInPairs(
            [&](bool is_candidate) {
                return w.timer->TimePasses(is_candidate ? candidate : baseline, *timing_view);
            },
            options.pass_frames, out.timing);
}

}  // namespace tidepool::runner
