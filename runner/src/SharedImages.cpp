// Configurations' units shared with a second process (Results.h, SharedImages.h).
#include "SharedImages.h"

#include "tidepool/Diagnostic.h"
#include "tidepool/base/AtomicFile.h"
#include "tidepool/base/SharedClaims.h"

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include "RenderProgress.h"
#include <fmt/format.h>

namespace tidepool::runner {
namespace {

// How long the second process may go without finishing or claiming a unit before the render
// takes its unfinished units back. One unit is one configuration's four images and three frames:
// about half a second here, and a few seconds on the slowest Fourier variant with two other
// processes competing; a minute is far beyond any of them.
constexpr std::chrono::seconds kHelperStall{60};
constexpr std::chrono::milliseconds kPoll{20};

Diagnostic FromEntry(const stagefiles::DiagnosticEntry& e) {
    return Diagnostic{SeverityFromName(e.severity).value_or(Severity::kError),
                      e.file,
                      e.line,
                      e.column,
                      e.message,
                      e.variant};
}

// Reads unit `i`'s file into `r`; false when it is missing, unreadable or not this configuration.
bool ReadSharedUnit(const SharedImageUnits& shared, std::size_t i, ConfigurationResult& r) {
    const stagefiles::ReadResult<stagefiles::ResultsFile> read =
            stagefiles::ReadResultsFile(SharedUnitPath(shared, i));
    if (!read.value || read.value->configurations.size() != 1 ||
        read.value->configurations.front().id != r.configuration.id) {
        return false;
    }
    // The per-pass times are the render process's own: compared configurations are timed there.
    std::map<std::string, double> pass_ms = std::move(r.pass_ms);
    const double instrumented_frame_ms = r.instrumented_frame_ms;
    FromResultsEntry(read.value->configurations.front(), r);
    r.pass_ms = std::move(pass_ms);
    r.instrumented_frame_ms = instrumented_frame_ms;
    return true;
}

}  // namespace

std::filesystem::path SharedUnitPath(const SharedImageUnits& shared, std::size_t i) {
    return shared.folder / fmt::format("{}.json", i);
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

int CollectSharedUnits(RenderWorker& w, const ImageUnitContext& context,
                       std::vector<ConfigurationResult>& configurations) {
    const SharedImageUnits& shared = context.options.shared;
    base::SharedClaims& claims = *shared.claims;
    for (std::size_t i : claims.AwaitHelper(kHelperStall, kPoll)) {
        RenderConfigurationUnit(w, context, i, configurations[i]);
    }
    int collected = 0;
    for (std::size_t i = 0; i < configurations.size() && i < claims.Size(); ++i) {
        if (claims.StateOf(i) != base::SharedClaims::State::kHelperDone) {
            continue;
        }
        if (ReadSharedUnit(shared, i, configurations[i])) {
            ++collected;
        } else {
            RenderConfigurationUnit(w, context, i, configurations[i]);
        }
    }
    return collected;
}

SharedImagesDone RenderSharedImages(GlContext& context, const VariantConfig& config,
                                    const RunOptions& options) {
    SharedImagesDone done;
    base::SharedClaims* claims = options.shared.claims;
    if (claims == nullptr) {
        return done;
    }
    RenderWorker w;
    w.renderer = WaterRenderer::Create(context, config, options.settings, &done.error);
    if (!w.renderer) {
        done.error = "cannot set up the renderer: " + done.error;
        return done;
    }
    // Each unit's file is a results file of one configuration, written by the one writer.
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
    const std::vector<WorkUnit> order =
            RenderWorkOrder(options.comparisons.size(), options.configurations.size(), reference);
    claims->SetHelperTaking(true);
    for (auto unit = order.rbegin(); unit != order.rend(); ++unit) {
        if (unit->comparison || unit->index == reference || unit->index >= claims->Size() ||
            !claims->ClaimForHelper(unit->index)) {
            continue;
        }
        ConfigurationResult r;
        r.configuration = options.configurations[unit->index];
        RenderConfigurationUnit(w, unit_context, unit->index, r);
        frame.configurations = {std::move(r)};
        // A file that cannot be written is rendered again by the render process.
        base::WriteFileAtomically(SharedUnitPath(options.shared, unit->index),
                                  stagefiles::ResultsFileText(ToResultsFile(frame)),
                                  base::Durability::kUnsynced);
        done.configurations += claims->FinishForHelper(unit->index) ? 1 : 0;
    }
    claims->SetHelperTaking(false);
    return done;
}

}  // namespace tidepool::runner
