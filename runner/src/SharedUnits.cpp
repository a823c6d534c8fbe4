// Units shared with a second process (Results.h, SharedUnits.h).
#include "SharedUnits.h"

#include "tidepool/Diagnostic.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/SharedClaims.h"

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "RenderProgress.h"
#include <fmt/format.h>

namespace tidepool::runner {
namespace {

// How long the second process may go without finishing or claiming a unit before the render
// takes its unfinished units back. A configuration's unit (four images and three frames) takes
// about half a second here, and a few seconds on the slowest Fourier variant with two other
// processes competing; a comparison's unit beats at every look at its interval, a few seconds
// apart. A minute is far beyond any of them.
constexpr std::chrono::seconds kHelperStall{60};
constexpr std::chrono::milliseconds kPoll{20};
constexpr std::chrono::milliseconds kWaitingLineEvery{500};

Diagnostic FromEntry(const stagefiles::DiagnosticEntry& e) {
    return Diagnostic{SeverityFromName(e.severity).value_or(Severity::kError),
                      e.file,
                      e.line,
                      e.column,
                      e.message,
                      e.variant};
}

// Reads configuration `i`'s unit file into `r`; false when it is missing, unreadable or not this
// configuration.
bool ReadSharedConfiguration(const SharedUnits& shared, std::size_t i, ConfigurationResult& r) {
    const stagefiles::ReadResult<stagefiles::ResultsFile> read =
            stagefiles::ReadResultsFile(SharedUnitPath(shared, i));
    if (!read.value || read.value->configurations.size() != 1 ||
        read.value->configurations.front().id != r.configuration.id) {
        return false;
    }
    // A configuration's per-pass times are the ones its comparison's process measured: kept here,
    // and filled from a shared comparison's unit when this process timed none.
    std::map<std::string, double> pass_ms = std::move(r.pass_ms);
    const double instrumented_frame_ms = r.instrumented_frame_ms;
    FromResultsEntry(read.value->configurations.front(), r);
    r.pass_ms = std::move(pass_ms);
    r.instrumented_frame_ms = instrumented_frame_ms;
    return true;
}

// Reads comparison `k`'s unit file into `out`, and its configurations' per-pass times into those
// of `configurations` that have none; false when it is missing, unreadable or not this comparison.
bool ReadSharedComparison(const RunOptions& options, std::size_t k, ComparisonResult& out,
                          std::vector<ConfigurationResult>& configurations) {
    const stagefiles::ReadResult<stagefiles::ResultsFile> read = stagefiles::ReadResultsFile(
            SharedUnitPath(options.shared, SharedComparisonUnit(options, k)));
    const TimedComparison& c = out.comparison;
    if (!read.value || read.value->comparisons.size() != 1 ||
        read.value->configurations.size() != 2 || c.baseline >= configurations.size() ||
        c.candidate >= configurations.size()) {
        return false;
    }
    const stagefiles::ResultsComparison& entry = read.value->comparisons.front();
    if (entry.label != c.label || entry.baseline != configurations[c.baseline].configuration.id ||
        entry.candidate != configurations[c.candidate].configuration.id ||
        !FromResultsEntry(entry, out)) {
        return false;
    }
    out.timed_by_second_process = true;
    for (const stagefiles::ResultsConfiguration& timed : read.value->configurations) {
        for (std::size_t i : {c.baseline, c.candidate}) {
            ConfigurationResult& r = configurations[i];
            if (timed.id == r.configuration.id && r.pass_ms.empty()) {
                r.pass_ms = {timed.pass_ms.begin(), timed.pass_ms.end()};
                r.instrumented_frame_ms = timed.instrumented_frame_ms;
            }
        }
    }
    return true;
}

// Whether comparison `k` names two configurations of the run (one that does not is the render's
// to report).
bool ComparesTwoConfigurations(const RunOptions& options, std::size_t k) {
    const TimedComparison& c = options.comparisons[k];
    return c.baseline < options.configurations.size() &&
           c.candidate < options.configurations.size();
}

// Times comparison `k` on `w` into `frame` as a unit's results: the comparison between frame's
// configurations 0 (the baseline) and 1 (the candidate), each with its per-pass times.
void TimeSharedComparison(RenderWorker& w, const RunOptions& options, std::size_t k,
                          base::SharedClaims& claims, RunResults& frame) {
    ComparisonResult out;
    out.comparison = options.comparisons[k];
    // A comparison under load may take longer than the render waits for a silent helper.
    TimeComparisonUnit(w, options, out, [&](const ComparisonTiming&) { claims.Beat(); });
    frame.configurations.clear();
    for (const bool candidate : {false, true}) {
        ConfigurationResult r;
        r.configuration = options.configurations[candidate ? out.comparison.candidate
                                                           : out.comparison.baseline];
        const PassMedians& passes =
                candidate ? out.timing.candidate_passes : out.timing.baseline_passes;
        r.pass_ms = passes.pass_ms;
        r.instrumented_frame_ms = passes.frame_ms;
        frame.configurations.push_back(std::move(r));
    }
    out.comparison.baseline = 0;
    out.comparison.candidate = 1;
    frame.comparisons = {std::move(out)};
}

}  // namespace

std::filesystem::path SharedUnitPath(const SharedUnits& shared, std::size_t unit) {
    return shared.folder / fmt::format("{}.json", unit);
}

std::size_t SharedComparisonUnit(const RunOptions& options, std::size_t k) {
    return options.configurations.size() + k;
}

void FromResultsEntry(const stagefiles::ResultsConfiguration& entry, ConfigurationResult& r) {
    const stagefiles::ResultsDriver& d = entry.driver;
    r.verdict = {d.valid,      d.vertex_compiled, d.fragment_compiled, d.linked,
                 d.vertex_log, d.fragment_log,    d.link_log,          {}};
    for (const stagefiles::DiagnosticEntry& e : d.diagnostics) {
        r.verdict.diagnostics.push_back(FromEntry(e));
    }
    r.glslang_valid = entry.glslang_valid;
    r.views.clear();
    for (const stagefiles::ResultsViewResult& v : entry.views) {
        ViewResult view;
        view.view = v.view;
        view.image_path = v.image;
        view.frame.passes = v.passes;
        view.frame.pass_names = v.pass_names;
        view.frame.draw_calls = v.draw_calls.value_or(0);
        view.frame.oblique_fallback = v.oblique_fallback;
        view.frame.gl_error = v.gl_error;
        if (v.accuracy) {
            // The file keeps an identical image's infinite PSNR as null, read back as NaN.
            const double psnr = std::isnan(v.accuracy->psnr_db) ? INFINITY : v.accuracy->psnr_db;
            view.accuracy = base::ImageAccuracy{psnr, v.accuracy->ssim, v.accuracy->share_visible};
        }
        r.views.push_back(std::move(view));
    }
    r.passes = entry.frame_passes;
    r.draw_calls = entry.frame_draw_calls;
    r.samples_ms = entry.samples_ms;
    r.cpu_samples_ms = entry.cpu_samples_ms;
    r.plan_ms_median = entry.plan_ms_median;
    r.pass_ms = {entry.pass_ms.begin(), entry.pass_ms.end()};
    r.instrumented_frame_ms = entry.instrumented_frame_ms;
    r.gl_error = entry.gl_error;
}

bool FromResultsEntry(const stagefiles::ResultsComparison& entry, ComparisonResult& out) {
    const std::optional<base::StopDecision> decision = base::StopDecisionFromName(entry.decision);
    if (!decision) {
        return false;
    }
    out.error = entry.error;
    out.timing.samples = {entry.baseline_ms, entry.candidate_ms, entry.baseline_wall_ms,
                          entry.candidate_wall_ms};
    out.timing.decision = *decision;
    out.timing.baseline_passes = {{entry.baseline_pass_ms.begin(), entry.baseline_pass_ms.end()},
                                  entry.baseline_instrumented_frame_ms};
    out.timing.candidate_passes = {{entry.candidate_pass_ms.begin(), entry.candidate_pass_ms.end()},
                                   entry.candidate_instrumented_frame_ms};
    out.timing.contended = {entry.contended_baseline_ms, entry.contended_candidate_ms, {}, {}};
    if (out.error.empty()) {
        out.timing.estimate = base::EstimatePaired(entry.baseline_ms, entry.candidate_ms);
        out.timing.contended_estimate =
                base::EstimatePaired(entry.contended_baseline_ms, entry.contended_candidate_ms);
        out.timing.stated =
                base::AcrossHostStates(out.timing.estimate, out.timing.contended_estimate);
    }
    return true;
}

CollectedUnits CollectSharedUnits(RenderWorker& w, const ImageUnitContext& context,
                                  RunResults& results,
                                  const std::function<void(std::size_t k)>& time_comparison) {
    const RunOptions& options = context.options;
    base::SharedClaims& claims = *options.shared.claims;
    std::vector<ConfigurationResult>& configurations = results.configurations;
    auto redo = [&](std::size_t unit) {
        if (unit < configurations.size()) {
            RenderConfigurationUnit(w, context, unit, configurations[unit]);
        } else if (unit - configurations.size() < results.comparisons.size()) {
            time_comparison(unit - configurations.size());
        }
    };
    // While the second process finishes its units, the progress line says so, with their ETA.
    ProgressMeter::Clock::time_point told{};
    const auto tell = [&] {
        const ProgressMeter::Clock::time_point now = ProgressMeter::Clock::now();
        if (context.meter != nullptr && now - told >= kWaitingLineEvery) {
            context.meter->Waiting("the second process's units", now);
            told = now;
        }
    };
    const std::vector<std::size_t> taken_back = claims.AwaitHelper(kHelperStall, kPoll, tell);
    for (std::size_t unit : taken_back) {
        redo(unit);  // its steps publish the line from here on
    }
    if (context.meter != nullptr && taken_back.empty() &&
        told != ProgressMeter::Clock::time_point{}) {
        context.meter->Waiting("the second process's units", ProgressMeter::Clock::now());
    }
    // Configurations first: their units keep the per-pass times already here, which a shared
    // comparison's unit then fills where there are none.
    CollectedUnits collected;
    for (std::size_t i = 0; i < configurations.size() && i < claims.Size(); ++i) {
        if (claims.StateOf(i) != base::SharedClaims::State::kHelperDone) {
            continue;
        }
        if (ReadSharedConfiguration(options.shared, i, configurations[i])) {
            ++collected.configurations;
        } else {
            redo(i);
        }
    }
    for (std::size_t k = 0; k < results.comparisons.size(); ++k) {
        const std::size_t unit = SharedComparisonUnit(options, k);
        if (unit >= claims.Size() ||
            claims.StateOf(unit) != base::SharedClaims::State::kHelperDone) {
            continue;
        }
        if (!ReadSharedComparison(options, k, results.comparisons[k], configurations)) {
            redo(unit);
        }
    }
    return collected;
}

SharedUnitsDone RenderSharedUnits(GlContext& context, const VariantConfig& config,
                                  const RunOptions& options) {
    SharedUnitsDone done;
    base::SharedClaims* claims = options.shared.claims;
    if (claims == nullptr) {
        return done;
    }
    RenderWorker w;
    w.renderer = WaterRenderer::Create(context, config, options.settings, &done.error);
    if (!w.renderer) {
        done.error = "cannot set up the renderer: " + done.error;
        claims->SetHelperTaking(false);  // the render must not count on it
        return done;
    }
    // Each unit's file is a results file of one configuration or comparison, written by the one
    // writer.
    RunResults frame;
    frame.gl = context.Environment();
    frame.host = options.host;
    frame.options = options;
    frame.clock =
            ChooseFrameClock(frame.gl.renderer, options.host.lp_num_threads, frame.gl.timer_query);
    w.timer = std::make_unique<FrameTimer>(*w.renderer, frame.clock.clock);
    ReferenceImages references;
    std::mutex errors_mutex;
    const std::optional<std::size_t> reference = ReferenceConfiguration(options);
    if (reference) {
        // The reference's views, rendered here as the render process renders them (the same
        // scene, settings and driver give the same pixels), kept in memory only.
        RunOptions views_only = options;
        views_only.write_images = false;
        views_only.coarse_frames = 0;
        std::vector<std::string> unused;
        ConfigurationResult scratch;
        scratch.configuration = options.configurations[*reference];
        RenderConfigurationUnit(w, {views_only, references, nullptr, errors_mutex, unused},
                                *reference, scratch);
    }
    const ImageUnitContext unit_context{options, references, nullptr, errors_mutex,
                                        done.write_errors};
    const std::vector<WorkUnit> order = RunWorkOrder(options);
    claims->SetHelperTaking(true);
    for (auto unit = order.rbegin(); unit != order.rend(); ++unit) {
        const std::size_t claim =
                unit->comparison ? SharedComparisonUnit(options, unit->index) : unit->index;
        const bool skip = unit->comparison ? !ComparesTwoConfigurations(options, unit->index)
                                           : unit->index == reference;
        if (skip || claim >= claims->Size() || !claims->ClaimForHelper(claim)) {
            continue;
        }
        if (unit->comparison) {
            TimeSharedComparison(w, options, unit->index, *claims, frame);
        } else {
            ConfigurationResult r;
            r.configuration = options.configurations[unit->index];
            RenderConfigurationUnit(w, unit_context, unit->index, r);
            frame.configurations = {std::move(r)};
            frame.comparisons.clear();
        }
        // A file that cannot be written is done again by the render process.
        base::WriteFileAtomically(SharedUnitPath(options.shared, claim),
                                  stagefiles::ResultsFileText(ToResultsFile(frame)),
                                  base::Durability::kUnsynced);
        const int handed = claims->FinishForHelper(claim) ? 1 : 0;
        (unit->comparison ? done.comparisons : done.configurations) += handed;
    }
    claims->SetHelperTaking(false);
    return done;
}

}  // namespace tidepool::runner
