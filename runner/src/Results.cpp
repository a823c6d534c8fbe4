// The render run: compile, images, warm-up, interleaved timing rounds, results.json.
#include "tidepool/runner/Results.h"

#include "tidepool/GlslValidator.h"
#include "tidepool/Manifest.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/ImageMetrics.h"
#include "tidepool/base/RgbaImage.h"
#include "tidepool/base/SampleStatistics.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "ConfigurationImages.h"
#include "RenderProgress.h"
#include "SharedUnits.h"
#include <fmt/format.h>

namespace tidepool::runner {
namespace {

using base::EstimatePaired;
using base::PairedEstimate;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration duration) {
    return std::chrono::duration<double>(duration).count();
}

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace

bool RunResults::AllOk() const {
    return std::all_of(configurations.begin(), configurations.end(),
                       [](const ConfigurationResult& c) { return c.Ok(); });
}

int RunResults::SharedComparisons() const {
    return static_cast<int>(
            std::count_if(comparisons.begin(), comparisons.end(),
                          [](const ComparisonResult& c) { return c.timed_by_second_process; }));
}

namespace {

constexpr long kInitialPairGuess = 60;  // until a comparison's first look says otherwise

}  // namespace

RunResults RunRender(GlContext& context, const VariantConfig& config, const RunOptions& options,
                     const ProgressCallback& progress) {
    RunResults results;
    results.gl = context.Environment();
    results.host = options.host;
    results.options = options;
    results.started_utc = UtcNow();
    results.clock = ChooseFrameClock(results.gl.renderer, options.host.lp_num_threads,
                                     results.gl.timer_query);
    const Clock::time_point start = Clock::now();

    for (const RenderConfiguration& configuration : options.configurations) {
        ConfigurationResult result;
        result.configuration = configuration;
        results.configurations.push_back(std::move(result));
    }
    for (const TimedComparison& c : options.comparisons) {
        ComparisonResult r;
        r.comparison = c;
        if (c.baseline >= options.configurations.size() ||
            c.candidate >= options.configurations.size()) {
            r.error = "the comparison names a configuration the run does not have";
        }
        results.comparisons.push_back(std::move(r));
    }

    // glslang's verdict on the same variants, to list where the two compilers disagree.
    std::map<std::string, bool> glslang;
    if (options.compare_with_glslang) {
        std::vector<Variant> variants;
        std::set<std::string> seen;
        for (const ConfigurationResult& r : results.configurations) {
            if (seen.insert(r.configuration.variant.Id()).second) {
                variants.push_back(r.configuration.variant);
            }
        }
        const ValidationReport report = ValidateVariants(
                config, variants, ValidationOptions{},
                options.validated != nullptr ? *options.validated : ValidationReport{});
        for (const VariantVerdict& v : report.verdicts) {
            glslang[v.variant.Id()] = v.valid;
        }
    }

    ProgressMeter meter(progress, start);
    const long per_configuration = FramesPerConfiguration(options);
    meter.AddExpected(ProgressMeter::kImage,
                      per_configuration * static_cast<long>(options.configurations.size()));
    // Frames of a comparison with `pairs` as-run pairs: both sides of those and of the contended
    // pairs taken beside them (0 for none).
    auto pair_frames = [&](long pairs) -> long {
        if (pairs <= 0) {
            return 0;
        }
        const int contended =
                base::ContendedPairsBeforeNextLook(static_cast<int>(pairs), 0, options.rule);
        return 2 * (pairs + contended);
    };
    // What a comparison renders besides its pairs, expected before it starts: both sides'
    // warm-up again when it goes on from its probe, and its per-pass pairs after its last look
    // (TimeComparisonUnit). About a fifth of a comparison that stops at the fewest pairs; left
    // uncounted, the calibration had to learn them. (The warm-up frames a worker renders the
    // first time it uses a configuration, often in a probe, are not counted.)
    const long warmup_frames = ProbesComparisons(options) ? 2L * options.warmup_frames : 0;
    const long per_pass_frames = 2L * options.pass_frames;
    auto frames_at = [&](long pairs) -> long {
        return pairs <= 0 ? 0 : pair_frames(pairs) + warmup_frames + per_pass_frames;
    };
    meter.AddComparisons(results.comparisons.size(), frames_at(kInitialPairGuess));
    meter.ComparisonCostPrior(ContendedFramesCost(options.rule.contended_share));
    for (std::size_t k = 0; k < results.comparisons.size(); ++k) {
        const TimedComparison& c = results.comparisons[k].comparison;
        meter.ComparisonConfigurations(k, c.baseline, c.candidate);
    }

    // The reference configuration renders first, so that every later image is compared with
    // it while in memory.
    ReferenceImages references;
    const std::vector<WorkUnit> units = RunWorkOrder(options);
    std::atomic<std::size_t> next_unit{0};
    std::mutex results_mutex;  // diagnostics and write errors, appended from every thread
    std::vector<std::atomic<bool>> pass_timed(results.configurations.size());

    // A configuration in several comparisons keeps the per-pass times of the first of them to
    // finish (each comparison keeps its own pair in its ComparisonTiming).
    auto keep_passes = [&](std::size_t i, const PassMedians& passes) {
        if (!pass_timed[i].exchange(true)) {
            results.configurations[i].pass_ms = passes.pass_ms;
            results.configurations[i].instrumented_frame_ms = passes.frame_ms;
        }
    };

    base::SharedClaims* claims = options.shared.claims;
    std::atomic<bool> collected{false};
    std::atomic<int> threads_started{0};
    std::atomic<int> threads_done{0};
    if (claims != nullptr) {
        meter.ShareUnits(claims, per_configuration, results.configurations.size());
    }
    const ImageUnitContext image_context{options, references, &meter, results_mutex,
                                         results.write_errors};
    auto run_configuration = [&](RenderWorker& w, std::size_t i) {
        RenderConfigurationUnit(w, image_context, i, results.configurations[i]);
    };

    // Times a part of comparison k (ComparisonPart), counting its frames in the meter as they
    // are taken; `stepped[k]` holds how many it has counted so far.
    std::vector<long> stepped(results.comparisons.size(), 0);
    // The spreads of the probes so far, by which a disturbed probe is known
    // (base::UndisturbedProbe).
    base::ProbeSpreads probe_spreads;
    std::mutex probe_spreads_mutex;
    auto time_comparison = [&](RenderWorker& w, std::size_t k, ComparisonPart part) {
        ComparisonResult& out = results.comparisons[k];
        const TimedComparison& c = out.comparison;
        const base::StoppingRule rule = ComparisonRule(options, c);
        // The rest of a comparison that goes on from its probe warms both sides again before its
        // first pair (TimeComparisonUnit): counted with its first look's frames.
        const long warmed = part == ComparisonPart::kRest && !out.timing.samples.baseline_ms.empty()
                                    ? 2L * options.warmup_frames
                                    : 0;
        auto after_look = [&](const ComparisonTiming& so_far) {
            // Frames taken so far, and a new guess of the pairs the interval needs.
            const long frames = 2L * static_cast<long>(so_far.samples.baseline_ms.size() +
                                                       so_far.contended.baseline_ms.size()) +
                                warmed;
            meter.StepComparison(k, c.label, frames - stepped[k]);
            stepped[k] = frames;
            // A probe's guesses take its pairs with a disturbed state's pulled in; a later look's
            // take them as they are.
            base::ProbeCandidates probe;
            if (part == ComparisonPart::kProbe) {
                std::lock_guard<std::mutex> lock(probe_spreads_mutex);
                probe = base::UndisturbedProbe(
                        so_far.samples.baseline_ms, so_far.samples.candidate_ms,
                        so_far.contended.baseline_ms, so_far.contended.candidate_ms, probe_spreads);
            }
            const bool probed = part == ComparisonPart::kProbe;
            const std::vector<double>& candidate_ms =
                    probed ? probe.as_run : so_far.samples.candidate_ms;
            const std::vector<double>& contended_candidate_ms =
                    probed ? probe.contended : so_far.contended.candidate_ms;
            const base::ExpectedPairs expected = base::PairsExpectedAcrossStates(
                    so_far.samples.baseline_ms, candidate_ms, so_far.contended.baseline_ms,
                    contended_candidate_ms, so_far.estimate, so_far.contended_estimate, rule,
                    kInitialPairGuess);
            const long expected_frames =
                    2L * (expected.as_run + expected.contended) + warmup_frames + per_pass_frames;
            // After the last look, the per-pass frames are still to come.
            const bool finished = so_far.decision != base::StopDecision::kContinue;
            meter.ComparisonExpects(k, finished ? frames + per_pass_frames : expected_frames,
                                    false);
        };
        TimeComparisonUnit(w, options, out, after_look, part);
        if (!out.error.empty()) {
            meter.ComparisonExpects(k, 0, true);
            return;
        }
        if (part == ComparisonPart::kProbe) {
            // The probe's frames are what the rest of this comparison's frames will cost, and
            // what its contended frames will cost on top depends on how much of its core the
            // render thread has now: its frames' time on the run's clock over their wall time.
            const PairSamples& probe = out.timing.samples;
            meter.ConfigurationCost(c.baseline, base::Median(probe.baseline_wall_ms) / 1000.0);
            meter.ConfigurationCost(c.candidate, base::Median(probe.candidate_wall_ms) / 1000.0);
            std::vector<double> clock_ms = probe.baseline_ms;
            clock_ms.insert(clock_ms.end(), probe.candidate_ms.begin(), probe.candidate_ms.end());
            std::vector<double> wall_ms = probe.baseline_wall_ms;
            wall_ms.insert(wall_ms.end(), probe.candidate_wall_ms.begin(),
                           probe.candidate_wall_ms.end());
            if (!clock_ms.empty() && !wall_ms.empty() && base::Median(wall_ms) > 0) {
                meter.ComparisonCostPrior(ContendedFramesCost(
                        options.rule.contended_share,
                        std::min(1.0, base::Median(clock_ms) / base::Median(wall_ms))));
            }
            return;
        }
        keep_passes(c.baseline, out.timing.baseline_passes);
        keep_passes(c.candidate, out.timing.candidate_passes);
        meter.StepComparison(k, c.label, per_pass_frames);
        stepped[k] += per_pass_frames;
        meter.ComparisonExpects(k, stepped[k], true);
    };

    // Comparison k's unit: its probe (`probe`) or the rest of it. Each comparison is timed by one
    // thread at a time, and its units may come in any order between threads: a rest unit taken
    // before the probe times the whole comparison, and the probe then has nothing to do.
    enum class Timed { kNotYet, kProbed, kDone };
    std::vector<Timed> timed(results.comparisons.size(), Timed::kNotYet);
    std::vector<std::mutex> comparison_mutex(results.comparisons.size());
    auto run_comparison = [&](RenderWorker& w, std::size_t k, bool probe) {
        std::lock_guard<std::mutex> lock(comparison_mutex[k]);
        if (timed[k] == Timed::kDone || (probe && timed[k] == Timed::kProbed)) {
            return;
        }
        time_comparison(w, k, probe ? ComparisonPart::kProbe : ComparisonPart::kRest);
        timed[k] = probe && results.comparisons[k].error.empty() ? Timed::kProbed : Timed::kDone;
    };

    // Whether this process does claim-table unit `unit` (it does all but the second process's).
    auto owner_takes = [&](std::size_t unit) {
        return claims == nullptr || unit >= claims->Size() || claims->ClaimForOwner(unit);
    };
    // Whether the second process has claimed `unit`.
    auto helper_has = [&](std::size_t unit) {
        return claims != nullptr && claims->HelperHas(unit);
    };

    // A rendering thread: its own context (but the calling thread's), renderer and timer; takes
    // units from the queue until it is empty.
    auto run_worker = [&](RenderWorker& w, GlContext& gl_context) {
        std::string error;
        w.renderer = WaterRenderer::Create(gl_context, config, options.settings, &error);
        if (!w.renderer) {
            std::lock_guard<std::mutex> lock(results_mutex);
            results.diagnostics.push_back(
                    MakeError("", 0, 0, "cannot set up the renderer: " + error));
            return;
        }
        w.timer = std::make_unique<FrameTimer>(*w.renderer, results.clock.clock);
        ++threads_started;
        for (std::size_t u = next_unit++; u < units.size(); u = next_unit++) {
            const std::size_t index = units[u].index;
            if (units[u].comparison) {
                // A probe leaves its comparison unclaimed: a second process that runs out of
                // images takes the comparisons the render has not gone on with, whole (its
                // results replace the probe's), instead of waiting for the render to finish them.
                const std::size_t unit = SharedComparisonUnit(options, index);
                if (units[u].probe ? !helper_has(unit) : owner_takes(unit)) {
                    run_comparison(w, index, units[u].probe);
                }
            } else if (owner_takes(index)) {
                run_configuration(w, index);
            }
        }
        // The units a second process took, collected by the last thread out: no other thread
        // is then writing a configuration's per-pass times.
        if (claims != nullptr && ++threads_done == threads_started.load() &&
            !collected.exchange(true)) {
            const CollectedUnits shared = CollectSharedUnits(
                    w, image_context, results, [&](std::size_t k) { run_comparison(w, k, false); });
            results.shared_configurations = shared.configurations;
        }
    };

    std::atomic<bool> rendered{false};
    results.workers =
            RunOnRenderingThreads(context, options.make_context, std::max(1, options.workers),
                                  [&](GlContext& gl_context) {
                                      RenderWorker w;
                                      run_worker(w, gl_context);
                                      if (w.renderer) {
                                          rendered = true;
                                      }
                                  });
    if (!rendered) {
        return results;  // the diagnostics say why
    }

    for (ConfigurationResult& r : results.configurations) {
        for (const Diagnostic& d : r.verdict.diagnostics) {
            results.diagnostics.push_back(d);
        }
        std::vector<double> all;
        for (const std::vector<double>& round : r.samples_ms) {
            all.insert(all.end(), round.begin(), round.end());
        }
        r.statistics = base::ComputeSampleStatistics(all);
        std::vector<double> all_clock;
        for (const std::vector<double>& round : r.cpu_samples_ms) {
            all_clock.insert(all_clock.end(), round.begin(), round.end());
        }
        r.cpu_statistics = base::ComputeSampleStatistics(all_clock);
        const std::string id = r.configuration.variant.Id();
        if (auto found = glslang.find(id); found != glslang.end()) {
            r.glslang_valid = found->second;
            // Only the variant's own program counts: a helper program's failure is not its fault.
            const bool mesa_valid = r.verdict.linked;
            const bool listed =
                    std::any_of(results.disagreements.begin(), results.disagreements.end(),
                                [&](const VerdictDisagreement& d) { return d.variant == id; });
            if (found->second != mesa_valid && !listed) {
                results.disagreements.push_back(VerdictDisagreement{id, found->second, mesa_valid});
            }
        }
        if (!r.gl_error.empty()) {
            results.diagnostics.push_back(Diagnostic{Severity::kError, "", 0, 0,
                                                     "GL error while rendering: " + r.gl_error,
                                                     r.configuration.id});
        }
    }
    results.wall_seconds = Seconds(Clock::now() - start);
    return results;
}

namespace {

std::array<double, 2> Array(const glm::vec2& v) {
    return {v.x, v.y};
}

std::array<double, 3> Array(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

// A diagnostic with its GCC-form text beside its fields.
stagefiles::DiagnosticEntry ResultsDiagnostic(const Diagnostic& d) {
    return {std::string(SeverityName(d.severity)),
            d.file,
            d.line,
            d.column,
            d.message,
            d.variant,
            FormatDiagnostic(d)};
}

std::vector<stagefiles::DiagnosticEntry> ToEntries(const std::vector<Diagnostic>& diagnostics) {
    std::vector<stagefiles::DiagnosticEntry> entries;
    entries.reserve(diagnostics.size());
    for (const Diagnostic& d : diagnostics) {
        entries.push_back(ResultsDiagnostic(d));
    }
    return entries;
}

stagefiles::ResultsStatistics ToEntry(const base::SampleStatistics& s) {
    return {s.count,   s.min,         s.max,
            s.mean,    s.median,      s.q1,
            s.q3,      s.iqr,         s.ci_low,
            s.ci_high, s.ci_coverage, "order statistics of the median, binomial(n, 0.5) coverage"};
}

stagefiles::ResultsSettings ToSettings(const RunResults& results) {
    const RunOptions& o = results.options;
    const RenderSettings& s = o.settings;
    stagefiles::ResultsSettings out;
    out.config = o.config_path;
    out.width = s.width;
    out.height = s.height;
    for (const CameraView& v : o.views) {
        out.views.push_back({v.name, Array(v.eye), Array(v.target), v.fov_y_radians, v.near_plane,
                             v.far_plane});
    }
    out.timing_view =
            o.timing_view.empty() && !o.views.empty() ? o.views.front().name : o.timing_view;
    out.warmup_frames = o.warmup_frames;
    out.coarse_frames = o.coarse_frames;
    out.pass_frames = o.pass_frames;
    out.workers = results.workers;
    out.timing_method =
            "every frame timed on `timing.clock` around submission + glFinish (wall clock beside "
            "it); each configuration gets coarse_frames frames on its own; each comparison is "
            "timed in pairs of frames rendered back to back on one thread, the side going first "
            "alternating, as the machine runs and (at least timing.contended_share of them, more "
            "while they narrow the stated interval more) with a competing thread on the "
            "rendering thread's core, until the interval spanning both "
            "states' 95% Wilcoxon intervals of the Hodges-Lehmann ratio is as narrow as "
            "timing.resolution_points or timing.max_pairs is reached";
    out.animation_time_s = s.animation_time;
    out.clip_plane_offset = s.clip_plane_offset;
    out.wave_distortion = s.wave_distortion;
    out.bump_scale = {Array(s.bump_scale0), Array(s.bump_scale1)};
    out.bump_velocity = {Array(s.bump_velocity0), Array(s.bump_velocity1)};
    out.fog_colour = Array(s.fog_colour);
    out.rcp_max_fog_distance = s.rcp_max_fog_distance;
    out.underwater_colour = Array(s.underwater_colour);
    out.rcp_max_fog_depth = s.rcp_max_fog_depth;
    out.water_colour = {s.water_colour.r, s.water_colour.g, s.water_colour.b, s.water_colour.a};
    out.low_res_water_size = s.low_res_water_size;
    out.sky_size = s.sky_size;
    out.normal_map_size = s.normal_map_size;
    out.normalisation_cube_size = s.normalisation_cube_size;
    out.max_water_depth = s.max_water_depth;
    out.extinction = {Array(s.extinction.extinction), s.extinction.visibility,
                      Array(s.extinction.surface_colour), Array(s.extinction.depth_colour)};
    out.foam_depth = Array(s.foam_depth);
    out.shore_hardness = s.shore_hardness;
    out.shininess = s.shininess;
    out.fourier = {s.fourier.coefficients,        s.fourier.directions,   s.fourier.march_distance,
                   s.fourier.integration_samples, s.fourier.grid_spacing, s.fourier.grid_margin};
    return out;
}

stagefiles::ResultsConfiguration ToEntry(const ConfigurationResult& r, const RenderSettings& s) {
    const RenderConfiguration& c = r.configuration;
    stagefiles::ResultsConfiguration out;
    out.id = c.id;
    out.variant = c.variant.Id();
    out.program = c.variant.program;
    out.defines = c.variant.defines;
    out.effects = c.effects;
    out.uniform_bools = c.UsesUniformBools();
    out.presets = c.presets;
    out.passes = {ReflectionSize(c.passes, s.width, s.height),
                  RefractionSize(c.passes, s.width, s.height),
                  c.passes.low_res_water,
                  c.passes.depth_fog,
                  c.passes.clip,
                  c.passes.culling};
    out.driver = {r.verdict.valid,
                  r.verdict.vertex_compiled,
                  r.verdict.fragment_compiled,
                  r.verdict.linked,
                  r.verdict.vertex_log,
                  r.verdict.fragment_log,
                  r.verdict.link_log,
                  ToEntries(r.verdict.diagnostics)};
    out.glslang_valid = r.glslang_valid;
    for (const ViewResult& v : r.views) {
        stagefiles::ResultsViewResult view;
        view.view = v.view;
        view.image = v.image_path;
        view.passes = v.frame.passes;
        view.pass_names = v.frame.pass_names;
        view.draw_calls = v.frame.draw_calls;
        view.oblique_fallback = v.frame.oblique_fallback;
        view.gl_error = v.frame.gl_error;
        if (v.accuracy) {
            // An identical image's PSNR is infinite, which JSON writes as null.
            view.accuracy = {v.accuracy->psnr_db, v.accuracy->ssim, v.accuracy->share_visible};
        }
        out.views.push_back(std::move(view));
    }
    out.frame_passes = r.passes;
    out.frame_draw_calls = r.draw_calls;
    out.samples_ms = r.samples_ms;
    out.statistics = ToEntry(r.statistics);
    out.cpu_samples_ms = r.cpu_samples_ms;
    out.cpu_statistics = ToEntry(r.cpu_statistics);
    out.plan_ms_median = r.plan_ms_median;
    out.pass_ms.insert(r.pass_ms.begin(), r.pass_ms.end());
    out.instrumented_frame_ms = r.instrumented_frame_ms;
    out.gl_error = r.gl_error;
    out.ok = r.Ok();
    return out;
}

}  // namespace

stagefiles::ResultsFile ToResultsFile(const RunResults& results) {
    const RunOptions& o = results.options;
    stagefiles::ResultsFile file;
    file.started_utc = results.started_utc;
    file.wall_seconds = results.wall_seconds;
    file.environment = {results.gl.backend,
                        results.gl.context_api,
                        results.gl.renderer,
                        results.gl.version,
                        results.gl.shading_language,
                        results.gl.mesa_version,
                        results.gl.float_render_target,
                        results.gl.timer_query,
                        results.host.cpu_model,
                        results.host.lp_num_threads,
                        results.host.build_type,
                        results.host.git_revision,
                        results.host.command};
    file.settings = ToSettings(results);
    for (const ConfigurationResult& r : results.configurations) {
        file.configurations.push_back(ToEntry(r, o.settings));
    }
    file.timing = {std::string(FrameClockName(results.clock.clock)),
                   results.clock.reason,
                   o.rule.resolution_points,
                   o.rule.min_pairs,
                   o.rule.max_pairs,
                   o.rule.batch_pairs,
                   o.rule.contended_share,
                   base::kConfidenceLevel,
                   "Hodges-Lehmann median of Walsh averages of per-pair log "
                   "ratios; Wilcoxon signed-rank interval",
                   o.rule.boundary_pairs,
                   o.rule.boundary_standard_errors};
    for (const ComparisonResult& c : results.comparisons) {
        const base::PairedEstimate& e = c.timing.estimate;
        const bool indices_ok = c.comparison.baseline < results.configurations.size() &&
                                c.comparison.candidate < results.configurations.size();
        stagefiles::ResultsComparison out;
        out.label = c.comparison.label;
        if (indices_ok) {
            out.baseline = results.configurations[c.comparison.baseline].configuration.id;
            out.candidate = results.configurations[c.comparison.candidate].configuration.id;
        }
        out.error = c.error;
        out.pairs = e.pairs;
        out.decision = std::string(base::StopDecisionName(c.timing.decision));
        // JSON has no infinity or NaN: both are written as null.
        out.ratio = e.ratio;
        out.ratio_low = e.ratio_low;
        out.ratio_high = e.ratio_high;
        out.change_percent = e.change_percent;
        out.change_low = e.change_low;
        out.change_high = e.change_high;
        out.baseline_ms = c.timing.samples.baseline_ms;
        out.candidate_ms = c.timing.samples.candidate_ms;
        out.baseline_wall_ms = c.timing.samples.baseline_wall_ms;
        out.candidate_wall_ms = c.timing.samples.candidate_wall_ms;
        out.contended_baseline_ms = c.timing.contended.baseline_ms;
        out.contended_candidate_ms = c.timing.contended.candidate_ms;
        out.stated_change_low = c.timing.stated.change_low;
        out.stated_change_high = c.timing.stated.change_high;
        out.baseline_pass_ms.insert(c.timing.baseline_passes.pass_ms.begin(),
                                    c.timing.baseline_passes.pass_ms.end());
        out.candidate_pass_ms.insert(c.timing.candidate_passes.pass_ms.begin(),
                                     c.timing.candidate_passes.pass_ms.end());
        out.baseline_instrumented_frame_ms = c.timing.baseline_passes.frame_ms;
        out.candidate_instrumented_frame_ms = c.timing.candidate_passes.frame_ms;
        out.timed_by = c.timed_by_second_process ? "second_process" : "render";
        file.comparisons.push_back(std::move(out));
    }
    for (const VerdictDisagreement& d : results.disagreements) {
        file.disagreements.push_back({d.variant, d.glslang_valid, d.mesa_valid});
    }
    file.diagnostics = ToEntries(results.diagnostics);
    file.ok = results.AllOk();
    return file;
}

nlohmann::json ResultsToJson(const RunResults& results) {
    return stagefiles::ToJson(ToResultsFile(results));
}

}  // namespace tidepool::runner
