#include "tidepool/report/ReportInputs.h"

#include "tidepool/base/SampleStatistics.h"
#include "tidepool/report/StageFileShapes.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

namespace tidepool::report {
namespace {

// The results schema version the report reads: version 1 only ever gains keys (RESULTS.md).
constexpr int kResultsVersion = 1;
constexpr int kManifestVersion = 1;

double NumberOr(const nlohmann::json& object, const char* key, double fallback) {
    auto it = object.find(key);
    return it != object.end() && it->is_number() ? it->get<double>() : fallback;
}

std::vector<std::string> StringList(const nlohmann::json& object, const char* key) {
    std::vector<std::string> list;
    auto it = object.find(key);
    if (it != object.end() && it->is_array()) {
        for (const nlohmann::json& item : *it) {
            if (item.is_string()) {
                list.push_back(item.get<std::string>());
            }
        }
    }
    return list;
}

// Reads an optional boolean `key` of `object` into `out` (left as it is when absent); returns
// "" or an error naming `where` and the field when it is present with another type.
std::string ReadBool(const nlohmann::json& object, const char* key, const std::string& where,
                     bool* out) {
    auto it = object.find(key);
    if (it == object.end()) {
        return "";
    }
    if (!it->is_boolean()) {
        return fmt::format("{}: '{}' must be true or false, not {}", where, key, it->dump());
    }
    *out = it->get<bool>();
    return "";
}

std::string StringOr(const nlohmann::json& object, const char* key, std::string fallback = {}) {
    auto it = object.find(key);
    return it != object.end() && it->is_string() ? it->get<std::string>() : fallback;
}

// Checks the schema name and version of `document`; returns "" or what is wrong.
std::string CheckSchema(const nlohmann::json& document, std::string_view schema,
                        const char* version_key, int version) {
    if (!document.is_object()) {
        return "not a JSON object";
    }
    const std::string found = StringOr(document, "schema");
    if (found != schema) {
        return fmt::format("schema is '{}', expected '{}'", found, schema);
    }
    auto it = document.find(version_key);
    if (it == document.end() || !it->is_number_integer() || it->get<int>() != version) {
        return fmt::format("{} must be {}", version_key, version);
    }
    return {};
}

// Reads `key` (an array of rounds, each an array of numbers) into `rounds`; returns "" or the
// problem. An absent key leaves `rounds` empty: older results files have no cpu_samples_ms.
std::string ParseRounds(const nlohmann::json& entry, const char* key, const std::string& id,
                        std::vector<std::vector<double>>* rounds) {
    auto samples = entry.find(key);
    if (samples == entry.end()) {
        return {};
    }
    if (!samples->is_array()) {
        return fmt::format("configuration '{}': {} is not an array of rounds", id, key);
    }
    for (const nlohmann::json& round : *samples) {
        if (!round.is_array()) {
            return fmt::format("configuration '{}': a round of {} is not an array", id, key);
        }
        std::vector<double> frames;
        for (const nlohmann::json& sample : round) {
            if (!sample.is_number()) {
                return fmt::format("configuration '{}': a sample of {} is not a number", id, key);
            }
            frames.push_back(sample.get<double>());
        }
        rounds->push_back(std::move(frames));
    }
    return {};
}

// Reads the median and its interval from the statistics object `key`, when it counted samples.
void ParseStatistics(const nlohmann::json& entry, const char* key, double* median, double* low,
                     double* high) {
    auto stats = entry.find(key);
    if (stats == entry.end() || !stats->is_object() || NumberOr(*stats, "count", 0) <= 0) {
        return;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    *median = NumberOr(*stats, "median_ms", nan);
    *low = NumberOr(*stats, "ci_low_ms", nan);
    *high = NumberOr(*stats, "ci_high_ms", nan);
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

// A stage file's schema and version, then the type of every field it holds; "" or the problem.
std::string CheckStageFile(const nlohmann::json& document, std::string_view schema,
                           const char* version_key, int version, StageFile kind) {
    if (std::string problem = CheckSchema(document, schema, version_key, version);
        !problem.empty()) {
        return problem;
    }
    return CheckStageFileShape(kind, document);
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

// Parses one entry of results.json `configurations`; returns "" or the problem.
std::string ParseConfiguration(const nlohmann::json& entry, const std::filesystem::path& folder,
                               MeasuredConfiguration* out) {
    if (!entry.is_object() || !entry.contains("id") || !entry["id"].is_string()) {
        return "a configuration has no string 'id'";
    }
    MeasuredConfiguration& c = *out;
    c.id = entry["id"].get<std::string>();
    c.variant = StringOr(entry, "variant", c.id);
    c.program = StringOr(entry, "program");
    c.defines = StringList(entry, "defines");
    c.effects = StringList(entry, "effects");
    c.presets = StringList(entry, "presets");
    const std::string where = fmt::format("configuration '{}'", c.id);
    if (std::string e = ReadBool(entry, "uniform_bools", where, &c.uniform_bools); !e.empty()) {
        return e;
    }
    if (auto passes = entry.find("passes"); passes != entry.end() && passes->is_object()) {
        c.reflection_size = static_cast<int>(NumberOr(*passes, "reflection_size", 256));
        // Results from before the option existed: the refraction shared the reflection's size.
        c.refraction_size =
                static_cast<int>(NumberOr(*passes, "refraction_size", c.reflection_size));
        c.clip = StringOr(*passes, "clip", "oblique");
        for (const auto& [key, field] :
             {std::pair{"low_res_water", &c.low_res_water}, std::pair{"culling", &c.culling},
              std::pair{"depth_fog", &c.depth_fog}}) {
            if (std::string e = ReadBool(*passes, key, where + " passes", field); !e.empty()) {
                return e;
            }
        }
    }
    if (!entry.contains("ok") || !entry["ok"].is_boolean()) {
        return fmt::format("configuration '{}' has no boolean 'ok'", c.id);
    }
    c.ok = entry["ok"].get<bool>();
    c.gl_error = StringOr(entry, "gl_error");
    if (auto driver = entry.find("driver"); driver != entry.end() && driver->is_object()) {
        if (std::string e = ReadBool(*driver, "valid", where + " driver", &c.driver_valid);
            !e.empty()) {
            return e;
        }
        if (auto d = driver->find("diagnostics"); d != driver->end() && d->is_array()) {
            for (const nlohmann::json& diagnostic : *d) {
                c.driver_messages.push_back(
                        diagnostic.is_object()
                                ? StringOr(diagnostic, "text", StringOr(diagnostic, "message"))
                                : diagnostic.dump());
            }
        }
    }
    if (auto g = entry.find("glslang_valid"); g != entry.end() && g->is_boolean()) {
        c.glslang_valid = g->get<bool>();
    }
    if (auto views = entry.find("views"); views != entry.end() && views->is_array()) {
        for (const nlohmann::json& v : *views) {
            if (!v.is_object()) {
                return fmt::format("configuration '{}': a view is not an object", c.id);
            }
            ViewImage image{StringOr(v, "view"),
                            {},
                            StringList(v, "pass_names"),
                            std::nullopt,
                            std::nullopt};
            const std::string relative = StringOr(v, "image");
            if (!relative.empty()) {
                // Images are read and embedded in the page: only files inside the results
                // folder, as `render` writes them, never a path a crafted file points elsewhere.
                const std::filesystem::path path(relative);
                bool escapes = path.is_absolute() || path.has_root_name();
                for (const std::filesystem::path& part : path) {
                    escapes = escapes || part == "..";
                }
                if (escapes) {
                    return fmt::format(
                            "configuration '{}', view '{}': 'image' must be a path "
                            "inside the results folder, not '{}'",
                            c.id, image.view, relative);
                }
                image.image = folder / relative;
            }
            if (auto draws = v.find("draw_calls"); draws != v.end() && draws->is_number()) {
                image.draw_calls = static_cast<int>(draws->get<double>());
            }
            if (auto a = v.find("accuracy"); a != v.end() && a->is_object()) {
                const double inf = std::numeric_limits<double>::infinity();
                const double nan = std::numeric_limits<double>::quiet_NaN();
                image.accuracy =
                        base::ImageAccuracy{NumberOr(*a, "psnr_db", inf), NumberOr(*a, "ssim", nan),
                                            NumberOr(*a, "share_visible", nan)};
            }
            c.views.push_back(std::move(image));
        }
    }
    if (std::string problem = ParseRounds(entry, "samples_ms", c.id, &c.samples_ms);
        !problem.empty()) {
        return problem;
    }
    if (std::string problem = ParseRounds(entry, "cpu_samples_ms", c.id, &c.cpu_samples_ms);
        !problem.empty()) {
        return problem;
    }
    ParseStatistics(entry, "statistics", &c.median_ms, &c.ci_low_ms, &c.ci_high_ms);
    ParseStatistics(entry, "cpu_statistics", &c.cpu_median_ms, &c.cpu_ci_low_ms, &c.cpu_ci_high_ms);
    if (std::isnan(c.cpu_median_ms) && !c.cpu_samples_ms.empty()) {
        // Older writers of cpu samples without statistics: the median of every frame, as the
        // runner's statistics define it.
        std::vector<double> all;
        for (const std::vector<double>& round : c.cpu_samples_ms) {
            all.insert(all.end(), round.begin(), round.end());
        }
        c.cpu_median_ms = base::Median(all);
    }
    c.frame_passes = static_cast<int>(NumberOr(entry, "frame_passes", 0));
    c.frame_draw_calls = static_cast<int>(NumberOr(entry, "frame_draw_calls", 0));
    if (auto passes = entry.find("pass_ms"); passes != entry.end()) {
        if (!passes->is_object()) {
            return fmt::format("configuration {}: 'pass_ms' is not an object of numbers", c.id);
        }
        for (const auto& [pass, ms] : passes->items()) {
            if (!ms.is_number()) {
                return fmt::format("configuration {}: 'pass_ms.{}' is not a number", c.id, pass);
            }
            c.pass_ms[pass] = ms.get<double>();
        }
    }
    if (auto frame = entry.find("instrumented_frame_ms");
        frame != entry.end() && frame->is_number() && frame->get<double>() > 0) {
        c.instrumented_frame_ms = frame->get<double>();
    }
    return {};
}

// Reads one `comparisons` entry; returns "" or what is wrong with it, naming the field.
std::string ParseComparison(const nlohmann::json& entry, std::size_t index, MeasuredComparison* c) {
    if (!entry.is_object()) {
        return fmt::format("comparisons[{}] is not an object", index);
    }
    for (const char* key : {"label", "baseline", "candidate"}) {
        if (!entry.contains(key) || !entry[key].is_string()) {
            return fmt::format("comparisons[{}].{} is not a string", index, key);
        }
    }
    c->label = entry["label"].get<std::string>();
    c->baseline = entry["baseline"].get<std::string>();
    c->candidate = entry["candidate"].get<std::string>();
    c->decision = StringOr(entry, "decision");
    c->error = StringOr(entry, "error");
    // The times on the run's clock are required; the same frames on the wall clock optional.
    struct Times {
        const char* key;
        std::vector<double>* out;
        bool required;
    };
    for (const Times& t : {Times{"baseline_ms", &c->baseline_ms, true},
                           Times{"candidate_ms", &c->candidate_ms, true},
                           Times{"baseline_wall_ms", &c->baseline_wall_ms, false},
                           Times{"candidate_wall_ms", &c->candidate_wall_ms, false}}) {
        auto samples = entry.find(t.key);
        if (samples == entry.end() && !t.required) {
            continue;
        }
        if (samples == entry.end() || !samples->is_array()) {
            return fmt::format("comparisons[{}].{} is not an array of times", index, t.key);
        }
        for (const nlohmann::json& v : *samples) {
            if (!v.is_number()) {
                return fmt::format("comparisons[{}].{} holds a value that is not a number", index,
                                   t.key);
            }
            t.out->push_back(v.get<double>());
        }
    }
    if (c->baseline_ms.size() != c->candidate_ms.size()) {
        return fmt::format("comparisons[{}]: baseline_ms and candidate_ms differ in length", index);
    }
    return "";
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

namespace {

// The fields of each manifest variant the report reads, checked once here so the model can
// rely on them: "" or what is wrong, naming the entry and field.
std::string CheckManifestVariants(const nlohmann::json& variants) {
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const nlohmann::json& v = variants[i];
        if (!v.is_object()) {
            return fmt::format("'variants[{}]' is not an object", i);
        }
        for (const char* key : {"id", "program"}) {
            if (!v.contains(key) || !v[key].is_string() || v[key].get<std::string>().empty()) {
                return fmt::format("'variants[{}].{}' is not a non-empty string", i, key);
            }
        }
        for (const auto& [key, valid] :
             {std::pair{"defines", !v.contains("defines") || v["defines"].is_array()},
              std::pair{"valid", !v.contains("valid") || v["valid"].is_boolean()},
              std::pair{"stages", !v.contains("stages") || v["stages"].is_object()},
              std::pair{"target", !v.contains("target") || v["target"].is_string()}}) {
            if (!valid) {
                return fmt::format("'variants[{}].{}' has the wrong type", i, key);
            }
        }
    }
    return {};
}

}  // namespace

ReportInputsResult LoadReportInputs(const std::filesystem::path& manifest_path,
                                    const std::filesystem::path& results_path) {
    ReportInputsResult out;
    ReportInputs inputs;
    inputs.manifest_path = manifest_path;
    inputs.results_path = results_path;

    std::optional<nlohmann::json> manifest = stagefiles::ReadJsonFile(manifest_path, &out.error);
    if (!manifest) {
        return out;
    }
    if (std::string problem = CheckStageFile(*manifest, kManifestSchemaName, "version",
                                             kManifestVersion, StageFile::kManifest);
        !problem.empty()) {
        out.error = fmt::format("{}: {}", manifest_path.string(), problem);
        return out;
    }
    if (!manifest->contains("variants") || !(*manifest)["variants"].is_array() ||
        !manifest->contains("counts") || !(*manifest)["counts"].is_object()) {
        out.error = fmt::format(
                "{}: lacks 'variants' or 'counts' (write it with `tidepool "
                "validate --out DIR`)",
                manifest_path.string());
        return out;
    }
    if (std::string problem = CheckManifestVariants((*manifest)["variants"]); !problem.empty()) {
        out.error = fmt::format("{}: {}", manifest_path.string(), problem);
        return out;
    }
    inputs.manifest = std::move(*manifest);

    std::optional<nlohmann::json> results = stagefiles::ReadJsonFile(results_path, &out.error);
    if (!results) {
        return out;
    }
    // Results written before every stage file carried its version under one key say
    // "schema_version"; they still report.
    const char* version_key = results->is_object() && !results->contains(stagefiles::kVersionKey) &&
                                              results->contains("schema_version")
                                      ? "schema_version"
                                      : stagefiles::kVersionKey;
    if (std::string problem = CheckStageFile(*results, kResultsSchemaName, version_key,
                                             kResultsVersion, StageFile::kResults);
        !problem.empty()) {
        out.error = fmt::format("{}: {}", results_path.string(), problem);
        return out;
    }
    if (!results->contains("configurations") || !(*results)["configurations"].is_array()) {
        out.error = fmt::format("{}: lacks the 'configurations' array", results_path.string());
        return out;
    }
    if ((*results)["configurations"].empty()) {
        // A render always measures at least one configuration; an empty list would replace a
        // good report with an empty one.
        out.error = fmt::format("{}: 'configurations' is empty (render at least one)",
                                results_path.string());
        return out;
    }
    const std::filesystem::path folder = results_path.parent_path();
    std::set<std::string> ids;
    for (const nlohmann::json& entry : (*results)["configurations"]) {
        MeasuredConfiguration c;
        if (std::string problem = ParseConfiguration(entry, folder, &c); !problem.empty()) {
            out.error = fmt::format("{}: {}", results_path.string(), problem);
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
    if (auto settings = results->find("settings");
        settings != results->end() && settings->is_object()) {
        inputs.timing_view = StringOr(*settings, "timing_view");
        inputs.width = static_cast<int>(NumberOr(*settings, "width", inputs.width));
        inputs.height = static_cast<int>(NumberOr(*settings, "height", inputs.height));
        if (auto views = settings->find("views"); views != settings->end() && views->is_array()) {
            for (const nlohmann::json& v : *views) {
                if (v.is_object()) {
                    inputs.view_names.push_back(StringOr(v, "name"));
                }
            }
        }
    }
    if (inputs.view_names.empty() && !inputs.configurations.empty()) {
        for (const ViewImage& v : inputs.configurations.front().views) {
            inputs.view_names.push_back(v.view);
        }
    }
    if (inputs.timing_view.empty() && !inputs.view_names.empty()) {
        inputs.timing_view = inputs.view_names.front();
    }
    if (auto comparisons = results->find("comparisons"); comparisons != results->end()) {
        if (!comparisons->is_array()) {
            out.error = fmt::format("{}: 'comparisons' is not an array", results_path.string());
            return out;
        }
        for (std::size_t i = 0; i < comparisons->size(); ++i) {
            MeasuredComparison c;
            if (std::string problem = ParseComparison((*comparisons)[i], i, &c); !problem.empty()) {
                out.error = fmt::format("{}: {}", results_path.string(), problem);
                return out;
            }
            inputs.comparisons.push_back(std::move(c));
        }
    }
    inputs.results = std::move(*results);

    ChooseClock(&inputs);
    if (auto timing = inputs.results.find("timing");
        timing != inputs.results.end() && timing->is_object()) {
        inputs.clock_name = StringOr(*timing, "clock");
        inputs.resolution_points = NumberOr(*timing, "resolution_points", inputs.resolution_points);
        if (!inputs.clock_name.empty() && inputs.clock == TimingClock::kCpu) {
            inputs.clock_reason = fmt::format("{} ({}): {}",
                                              inputs.clock_name == "thread_cpu"
                                                      ? "the rendering thread's CPU time"
                                                      : "the run's clock",
                                              inputs.clock_name, StringOr(*timing, "clock_reason"));
        }
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
