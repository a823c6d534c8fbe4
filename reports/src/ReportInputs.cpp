#include "tidepool/report/ReportInputs.h"

#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

// The statistics' median and its interval, when they counted samples.
void ReadStatistics(const std::optional<stagefiles::ResultsStatistics>& stats, double* median,
                    double* low, double* high) {
    if (!stats || !(stats->count > 0)) {
        return;
    }
    *median = stats->median_ms;
    *low = stats->ci_low_ms;
    *high = stats->ci_high_ms;
}

// Chooses the comparison clock: CPU time only when every timed configuration has CPU samples
// of the same shape as its wall samples, so no comparison mixes the two clocks.
void ChooseClock(ReportInputs* inputs) {
    int timed = 0;
    std::vector<std::string> without;
    for (const MeasuredConfiguration& c : inputs->configurations) {
        if (!c.ok || c.samples_ms.empty()) {
            continue;
        }
        ++timed;
        bool same_shape = c.cpu_samples_ms.size() == c.samples_ms.size();
        for (std::size_t r = 0; same_shape && r < c.samples_ms.size(); ++r) {
            same_shape = c.cpu_samples_ms[r].size() == c.samples_ms[r].size();
        }
        if (!same_shape || std::isnan(c.cpu_median_ms)) {
            without.push_back(c.id);
        }
    }
    if (timed > 0 && without.empty()) {
        inputs->clock = TimingClock::kCpu;
        inputs->clock_reason = fmt::format(
                "process CPU time (CLOCK_PROCESS_CPUTIME_ID, every llvmpipe thread), because all "
                "{} timed configurations carry it: it measures the work a frame costs, while "
                "wall-clock samples on a shared 2-core machine are disturbed by other processes "
                "so much that two consecutive runs did not give the same verdicts",
                timed);
    } else if (timed == 0) {
        inputs->clock = TimingClock::kWall;
        inputs->clock_reason = "wall-clock time: no configuration was timed";
    } else {
        inputs->clock = TimingClock::kWall;
        inputs->clock_reason = fmt::format(
                "wall-clock time, because {} of {} timed configurations (first: {}) have no "
                "cpu_samples_ms of the same shape (results written before the runner recorded "
                "CPU time); comparisons never mix the two clocks",
                without.size(), timed, without.front());
    }
}

// Reads a stage file beside the results with `read`: absent leaves both outputs untouched; one
// that is unreadable, not tidepool's or incomplete is left out with `error` saying why (it may be
// anything a user left there). One that claims the schema but has a wrongly typed field is a
// damaged stage file, an error like a damaged manifest or results file: returns false.
template <typename T>
bool LoadSibling(const std::filesystem::path& path,
                 stagefiles::ReadResult<T> (*read)(const std::filesystem::path&),
                 std::optional<T>* value, std::string* error) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        return true;
    }
    stagefiles::ReadResult<T> result = read(path);
    *value = std::move(result.value);
    *error = std::move(result.error);
    return result.failure != stagefiles::ReadFailure::kWrongType;
}

// Views name the report's image files (images/<preset>-<view>.png): a name that is a path
// would write outside the report's folder.
constexpr const char* kViewNameRule =
        "must be a plain name of at most 64 characters (letters, digits, '_' and '-'), as render "
        "writes them";

bool IsViewName(const std::string& name) {
    return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
    });
}

// One entry of results.json `configurations` as the report uses it; returns "" or the problem.
std::string ParseConfiguration(const stagefiles::ResultsConfiguration& entry,
                               const std::filesystem::path& folder, MeasuredConfiguration* out) {
    MeasuredConfiguration& c = *out;
    c.id = entry.id;
    c.variant = entry.variant.value_or(c.id);
    c.program = entry.program;
    c.defines = entry.defines;
    c.effects = entry.effects;
    c.presets = entry.presets;
    c.uniform_bools = entry.uniform_bools;
    c.reflection_size = entry.passes.reflection_size;
    // Results from before the option existed: the refraction shared the reflection's size.
    c.refraction_size = entry.passes.refraction_size.value_or(c.reflection_size);
    c.clip = entry.passes.clip;
    c.low_res_water = entry.passes.low_res_water;
    c.culling = entry.passes.culling;
    c.depth_fog = entry.passes.depth_fog;
    c.ok = entry.ok;
    c.gl_error = entry.gl_error;
    c.driver_valid = entry.driver.valid;
    for (const stagefiles::DiagnosticEntry& diagnostic : entry.driver.diagnostics) {
        c.driver_messages.push_back(diagnostic.text.value_or(diagnostic.message));
    }
    c.glslang_valid = entry.glslang_valid;
    std::set<std::string> views;
    for (const stagefiles::ResultsViewResult& v : entry.views) {
        if (!IsViewName(v.view)) {
            return fmt::format("configuration '{}': view name '{}' {}", c.id, v.view,
                               kViewNameRule);
        }
        if (!views.insert(v.view).second) {
            return fmt::format("configuration '{}': view '{}' appears more than once", c.id,
                               v.view);
        }
        ViewImage image{v.view, {}, v.pass_names, v.draw_calls, std::nullopt};
        if (!v.image.empty()) {
            // Images are read and embedded in the page: only files inside the results
            // folder, as `render` writes them, never a path a crafted file points elsewhere.
            const std::filesystem::path path(v.image);
            bool escapes = path.is_absolute() || path.has_root_name();
            for (const std::filesystem::path& part : path) {
                escapes = escapes || part == "..";
            }
            if (escapes) {
                return fmt::format(
                        "configuration '{}', view '{}': 'image' must be a path "
                        "inside the results folder, not '{}'",
                        c.id, image.view, v.image);
            }
            image.image = folder / v.image;
        }
        if (v.accuracy) {
            // An identical image's PSNR is infinite, which JSON writes as null (read as NaN).
            const double psnr = v.accuracy->psnr_db;
            image.accuracy = base::ImageAccuracy{
                    std::isnan(psnr) ? std::numeric_limits<double>::infinity() : psnr,
                    v.accuracy->ssim, v.accuracy->share_visible};
        }
        c.views.push_back(std::move(image));
    }
    c.samples_ms = entry.samples_ms;
    c.cpu_samples_ms = entry.cpu_samples_ms;
    ReadStatistics(entry.statistics, &c.median_ms, &c.ci_low_ms, &c.ci_high_ms);
    ReadStatistics(entry.cpu_statistics, &c.cpu_median_ms, &c.cpu_ci_low_ms, &c.cpu_ci_high_ms);
    if (std::isnan(c.cpu_median_ms) && !c.cpu_samples_ms.empty()) {
        // Older writers of cpu samples without statistics: the median of every frame, as the
        // runner's statistics define it.
        std::vector<double> all;
        for (const std::vector<double>& round : c.cpu_samples_ms) {
            all.insert(all.end(), round.begin(), round.end());
        }
        c.cpu_median_ms = base::Median(all);
    }
    c.frame_passes = entry.frame_passes;
    c.frame_draw_calls = entry.frame_draw_calls;
    c.pass_ms.insert(entry.pass_ms.begin(), entry.pass_ms.end());
    if (entry.instrumented_frame_ms > 0) {
        c.instrumented_frame_ms = entry.instrumented_frame_ms;
    }
    return {};
}

// One `comparisons` entry as the report uses it.
MeasuredComparison ParseComparison(const stagefiles::ResultsComparison& entry) {
    return {entry.label,
            entry.baseline,
            entry.candidate,
            entry.baseline_ms,
            entry.candidate_ms,
            entry.baseline_wall_ms,
            entry.candidate_wall_ms,
            entry.contended_baseline_ms,
            entry.contended_candidate_ms,
            entry.decision,
            entry.error,
            {entry.baseline_pass_ms.begin(), entry.baseline_pass_ms.end()},
            {entry.candidate_pass_ms.begin(), entry.candidate_pass_ms.end()},
            entry.timed_by};
}

}  // namespace

bool MeasuredConfiguration::HasPreset(std::string_view preset) const {
    for (const std::string& p : presets) {
        if (p == preset) {
            return true;
        }
    }
    return false;
}

std::string MeasuredConfiguration::PassLabel() const {
    std::string label = fmt::format("reflection {0}x{0}, {1} clip", reflection_size, clip);
    if (refraction_size != reflection_size) {
        label += fmt::format(", refraction {0}x{0}", refraction_size);
    }
    if (!depth_fog) {
        label += ", no depth fog";
    }
    if (low_res_water) {
        label += ", low-res water";
    }
    if (!culling) {
        label += ", no culling";
    }
    return label;
}

const std::vector<std::vector<double>>& MeasuredConfiguration::SamplesOn(TimingClock clock) const {
    return clock == TimingClock::kCpu ? cpu_samples_ms : samples_ms;
}

const MeasuredComparison* ReportInputs::FindComparison(std::string_view baseline,
                                                       std::string_view candidate) const {
    for (const MeasuredComparison& c : comparisons) {
        if (c.baseline == baseline && c.candidate == candidate) {
            return &c;
        }
    }
    return nullptr;
}

double MeasuredConfiguration::MedianOn(TimingClock clock) const {
    return clock == TimingClock::kCpu ? cpu_median_ms : median_ms;
}

std::string_view TimingClockName(TimingClock clock) {
    return clock == TimingClock::kCpu ? "cpu" : "wall";
}

std::filesystem::path MeasuredConfiguration::ImageAt(std::string_view view) const {
    for (const ViewImage& v : views) {
        if (v.view == view) {
            return v.image;
        }
    }
    return {};
}

const ViewImage* MeasuredConfiguration::ViewAt(std::string_view view) const {
    for (const ViewImage& v : views) {
        if (v.view == view) {
            return &v;
        }
    }
    return nullptr;
}

const MeasuredConfiguration* ReportInputs::FindByPreset(std::string_view preset) const {
    for (const MeasuredConfiguration& c : configurations) {
        if (c.HasPreset(preset)) {
            return &c;
        }
    }
    return nullptr;
}

const MeasuredConfiguration* ReportInputs::FindById(std::string_view id) const {
    for (const MeasuredConfiguration& c : configurations) {
        if (c.id == id) {
            return &c;
        }
    }
    return nullptr;
}

ReportInputsResult LoadReportInputs(const std::filesystem::path& manifest_path,
                                    const std::filesystem::path& results_path) {
    ReportInputsResult out;
    ReportInputs inputs;
    inputs.manifest_path = manifest_path;
    inputs.results_path = results_path;

    stagefiles::ReadResult<stagefiles::ManifestFile> manifest =
            stagefiles::ReadManifestFile(manifest_path);
    if (!manifest.value) {
        out.error = std::move(manifest.error);
        return out;
    }
    inputs.manifest = std::move(*manifest.value);

    stagefiles::ReadResult<stagefiles::ResultsFile> results =
            stagefiles::ReadResultsFile(results_path);
    if (!results.value) {
        out.error = std::move(results.error);
        return out;
    }
    if (results.value->configurations.empty()) {
        // A render always measures at least one configuration; an empty list would replace a
        // good report with an empty one.
        out.error = fmt::format("{}: 'configurations' is empty (render at least one)",
                                results_path.string());
        return out;
    }
    const std::filesystem::path folder = results_path.parent_path();
    std::set<std::string> ids;
    std::set<std::string> variants;
    for (const stagefiles::ManifestVariant& variant : inputs.manifest.variants) {
        variants.insert(variant.id);
    }
    for (const stagefiles::ResultsConfiguration& entry : results.value->configurations) {
        MeasuredConfiguration c;
        if (std::string problem = ParseConfiguration(entry, folder, &c); !problem.empty()) {
            out.error = fmt::format("{}: {}", results_path.string(), problem);
            return out;
        }
        if (variants.count(c.variant) == 0) {
            out.error = fmt::format(
                    "{}: configuration '{}' renders variant '{}', which {} does not list: the "
                    "results come from the run of another configuration; give the manifest that "
                    "run validated",
                    results_path.string(), c.id, c.variant, manifest_path.string());
            return out;
        }
        if (!ids.insert(c.id).second) {
            out.error = fmt::format(
                    "{}: configuration id '{}' appears more than once in "
                    "'configurations'",
                    results_path.string(), c.id);
            return out;
        }
        inputs.configurations.push_back(std::move(c));
    }
    const stagefiles::ResultsSettings& settings = results.value->settings;
    inputs.timing_view = settings.timing_view;
    inputs.width = settings.width;
    inputs.height = settings.height;
    for (const stagefiles::ResultsView& v : settings.views) {
        if (!IsViewName(v.name)) {
            out.error = fmt::format("{}: settings.views: view name '{}' {}", results_path.string(),
                                    v.name, kViewNameRule);
            return out;
        }
        inputs.view_names.push_back(v.name);
    }
    if (!inputs.timing_view.empty() && !IsViewName(inputs.timing_view)) {
        out.error = fmt::format("{}: settings.timing_view '{}' {}", results_path.string(),
                                inputs.timing_view, kViewNameRule);
        return out;
    }
    if (inputs.view_names.empty() && !inputs.configurations.empty()) {
        for (const ViewImage& v : inputs.configurations.front().views) {
            inputs.view_names.push_back(v.view);
        }
    }
    if (inputs.timing_view.empty() && !inputs.view_names.empty()) {
        inputs.timing_view = inputs.view_names.front();
    }
    for (std::size_t i = 0; i < results.value->comparisons.size(); ++i) {
        MeasuredComparison c = ParseComparison(results.value->comparisons[i]);
        for (const auto& [side, id] :
             {std::pair{"baseline", &c.baseline}, std::pair{"candidate", &c.candidate}}) {
            if (ids.count(*id) == 0) {
                out.error = fmt::format(
                        "{}: comparisons[{}].{} '{}' is not the id of one of 'configurations'",
                        results_path.string(), i, side, *id);
                return out;
            }
        }
        if (c.baseline_ms.size() != c.candidate_ms.size()) {
            out.error = fmt::format(
                    "{}: comparisons[{}]: baseline_ms and candidate_ms differ in "
                    "length",
                    results_path.string(), i);
            return out;
        }
        // A pair's time is a thread's CPU time or a wall time: never 0 nor missing. The row
        // would read "failed" in a report that otherwise looks whole.
        for (const auto& [name, times] : {std::pair{"baseline_ms", &c.baseline_ms},
                                          std::pair{"candidate_ms", &c.candidate_ms}}) {
            const auto bad = std::find_if(times->begin(), times->end(),
                                          [](double t) { return !(t > 0 && std::isfinite(t)); });
            if (bad != times->end()) {
                out.error = fmt::format(
                        "{}: 'comparisons[{}].{}[{}]' is {}, which is not a pair's time (above "
                        "0 ms)",
                        results_path.string(), i, name, bad - times->begin(),
                        std::isnan(*bad) ? "null" : fmt::format("{}", *bad));
                return out;
            }
        }
        inputs.comparisons.push_back(std::move(c));
    }
    inputs.results = std::move(*results.value);

    ChooseClock(&inputs);
    const stagefiles::ResultsTiming& timing = inputs.results.timing;
    inputs.clock_name = timing.clock;
    inputs.resolution_points = timing.resolution_points.value_or(inputs.resolution_points);
    if (!inputs.clock_name.empty() && inputs.clock == TimingClock::kCpu) {
        inputs.clock_reason =
                fmt::format("{} ({}): {}",
                            inputs.clock_name == "thread_cpu" ? "the rendering thread's CPU time"
                                                              : "the run's clock",
                            inputs.clock_name, timing.clock_reason);
    }

    inputs.stability_path = folder / stagefiles::kStabilityFileName;
    if (!LoadSibling(inputs.stability_path, &stagefiles::ReadStabilityFile, &inputs.stability,
                     &inputs.stability_error)) {
        out.error = inputs.stability_error;
        return out;
    }
    inputs.plans_path = folder / stagefiles::kPlansFileName;
    if (!LoadSibling(inputs.plans_path, &stagefiles::ReadPlansFile, &inputs.plans,
                     &inputs.plans_error)) {
        out.error = inputs.plans_error;
        return out;
    }
    out.inputs = std::move(inputs);
    return out;
}

}  // namespace tidepool::report
