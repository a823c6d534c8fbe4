#include "GlCliSupport.h"

#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

namespace tidepool::cli {

bool ParseBackendOption(const std::string& text, runner::BackendKind* backend) {
    if (runner::ParseBackendKind(text, backend)) {
        return true;
    }
    std::fprintf(stderr, "error: --backend must be auto, egl or osmesa, not '%s'\n", text.c_str());
    return false;
}

void AddFourierOptions(CLI::App* command, runner::FourierSettings* settings) {
    command->add_option("--fourier-coefficients", settings->coefficients,
                        "REFLECTION_FOURIER: Fourier terms kept per water vertex, 1..8 "
                        "(a0, a1, b1, a2, b2, a3, b3, a4)")
            ->capture_default_str();
    command->add_option(
                   "--fourier-directions", settings->directions,
                   "REFLECTION_FOURIER: directions the terrain is marched in per vertex (>= 3)")
            ->capture_default_str();
}

bool CheckFourierOptions(const runner::FourierSettings& settings) {
    const std::string error = runner::CheckFourierSettings(settings);
    if (!error.empty()) {
        std::fprintf(stderr,
                     "error: %s (set --fourier-coefficients 1..8 and --fourier-directions >= 3)\n",
                     error.c_str());
        return false;
    }
    return true;
}

void AddTimingFlags(CLI::App* command, TimingFlags* flags) {
    command->add_option("--resolution", flags->resolution,
                        "stop timing a comparison when its 95% interval is this narrow "
                        "(half-width, percent points of frame rate)")
            ->capture_default_str();
    command->add_option("--min-pairs", flags->min_pairs, "pairs of frames per comparison, at least")
            ->capture_default_str();
    command->add_option("--max-pairs", flags->max_pairs,
                        "pairs of frames per comparison, at most (the resolution reached is "
                        "reported)")
            ->capture_default_str();
    command->add_option("--contended-share", flags->contended_share,
                        "pairs of frames timed with a competing thread on the rendering thread's "
                        "core, per pair timed as the machine runs; each comparison's interval "
                        "spans both (0: none)")
            ->capture_default_str();
    command->add_option("--coarse-frames", flags->coarse_frames,
                        "timed frames of each configuration on its own (the accuracy chart)")
            ->capture_default_str();
    command->add_option("--warmup", flags->warmup,
                        "untimed frames before a compared configuration is timed, per thread")
            ->capture_default_str();
    command->add_option("--workers", flags->workers,
                        "rendering threads, each with its own GL context (0: one per core; "
                        "llvmpipe's contexts in one process share one rasteriser lock, so more "
                        "than one rarely renders faster)")
            ->capture_default_str();
    command->add_option("--threads", flags->threads,
                        "llvmpipe threads (LP_NUM_THREADS; 0 renders on each worker's thread, "
                        "timed on that thread's CPU clock)")
            ->capture_default_str();
}

bool CheckTimingFlags(const TimingFlags& flags) {
    if (!(flags.resolution > 0 && flags.resolution <= 50)) {
        std::fprintf(stderr,
                     "error: --resolution must be above 0 and at most 50 percent points, "
                     "not %g\n",
                     flags.resolution);
        return false;
    }
    if (flags.min_pairs < base::kMinimumPairs || flags.max_pairs < flags.min_pairs ||
        flags.max_pairs > 100000) {
        std::fprintf(stderr,
                     "error: --min-pairs must be at least %d and --max-pairs between "
                     "--min-pairs and 100000, not %d and %d\n",
                     base::kMinimumPairs, flags.min_pairs, flags.max_pairs);
        return false;
    }
    if (!(flags.contended_share >= 0 && flags.contended_share <= 4)) {
        std::fprintf(stderr, "error: --contended-share must be between 0 and 4, not %g\n",
                     flags.contended_share);
        return false;
    }
    // A frame takes tens of milliseconds: 1000 of them are most of a minute per configuration,
    // and 2000000000 were accepted and began a render that would never end.
    if (flags.coarse_frames < 1 || flags.coarse_frames > kMaxFramesPerStep || flags.warmup < 0 ||
        flags.warmup > kMaxFramesPerStep || flags.workers < 0 || flags.workers > 64 ||
        flags.threads < 0 || flags.threads > 64) {
        std::fprintf(stderr,
                     "error: --coarse-frames must be between 1 and %d, --warmup between 0 and "
                     "%d, --workers and --threads between 0 and 64, not %d, %d, %d and %d\n",
                     kMaxFramesPerStep, kMaxFramesPerStep, flags.coarse_frames, flags.warmup,
                     flags.workers, flags.threads);
        return false;
    }
    return true;
}

std::string FormatDuration(double seconds) {
    const long total = static_cast<long>(seconds + 0.5);
    return total >= 60 ? fmt::format("{}m{:02}s", total / 60, total % 60)
                       : fmt::format("{}s", total);
}

runner::ProgressCallback MakeProgressPrinter() {
    return MakeProgressPrinter(stderr, isatty(fileno(stderr)) != 0);
}

runner::ProgressCallback MakeProgressPrinter(std::FILE* out, bool terminal) {
    struct State {
        std::string last_stage;
        double last_print = -1e9;
        bool printed_complete = false;  // the last line printed said the run is complete
    };
    auto state = std::make_shared<State>();
    return [state, out, terminal](const runner::RunProgress& p) {
        if (terminal) {
            std::fprintf(out, "\r\033[K[%3.0f%%] %-11s %s  ETA %s", p.percent, p.stage.c_str(),
                         p.configuration.c_str(), FormatDuration(p.eta_seconds).c_str());
            std::fflush(out);
        } else if (const bool complete = p.done == p.total && p.eta_seconds <= 0;
                   p.stage != state->last_stage || p.elapsed_seconds - state->last_print >= 10.0 ||
                   (complete && !state->printed_complete)) {
            // The complete line once: a render waiting for a second process's last units has
            // done all of its own frames for seconds before, and says so every 10 s.
            state->printed_complete = complete;
            std::fprintf(out, "[%3.0f%%] %s %s (elapsed %s, ETA %s)\n", p.percent, p.stage.c_str(),
                         p.configuration.c_str(), FormatDuration(p.elapsed_seconds).c_str(),
                         FormatDuration(p.eta_seconds).c_str());
            state->last_print = p.elapsed_seconds;
        }
        state->last_stage = p.stage;
    };
}

void AddProgressLogFlag(CLI::App* command, std::string* path) {
    command->add_option("--progress-log", *path,
                        "write every progress state, with the figures its ETA is worked out "
                        "from, to this file as JSON lines");
}

void FinishProgress() {
    if (isatty(fileno(stderr)) != 0) {
        std::fprintf(stderr, "\n");
    }
}

}  // namespace tidepool::cli
