// Benchmark (b): the whole default matrix (every water variant plus every preset) at 640x480,
// every view, with the `tidepool render` defaults (warm-up 2, rounds 3, frames 3): compile,
// images, timing. Prints the total wall time (target: under 3 minutes on a 2-core machine).
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Results.h"

using namespace tidepool;
using namespace tidepool::runner;

int main() {
    setenv("LP_NUM_THREADS", "2", 0);  // the CLI's default, unless the caller chose otherwise
    const auto start = std::chrono::steady_clock::now();
    GlContextResult context = CreateGlContext(BackendKind::kAuto);
    if (!context.context) {
        fmt::print(stderr, "{}\n", context.error);
        return 3;
    }
    ConfigResult loaded =
        LoadVariantConfig(std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml");
    if (!loaded.config) {
        fmt::print(stderr, "variants.yaml does not load\n");
        return 2;
    }
    const ExpansionResult expansion =
        ExpandVariants(*loaded.config, ExpansionOptions{loaded.config->max_variants});
    RunOptions options;
    options.configurations = BuildDefaultConfigurations(*loaded.config, expansion.variants)
                                 .configurations;
    options.views = DefaultViews();
    options.out_dir = std::filesystem::temp_directory_path() / "tidepool-bench-matrix";
    options.host.command = "bench/render_default_matrix";
    options.host.lp_num_threads = std::getenv("LP_NUM_THREADS");
    const RunResults results = RunRender(*context.context, *loaded.config, options, nullptr);
    WriteJsonAtomically(options.out_dir / "results.json", ResultsToJson(results));
    const double total =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    int failed = 0;
    double timed_ms = 0;
    for (const ConfigurationResult& r : results.configurations) {
        failed += r.Ok() ? 0 : 1;
        for (const auto& round : r.samples_ms) {
            for (double ms : round) {
                timed_ms += ms;
            }
        }
    }
    fmt::print("configurations: {} ({} failed), views: {}, frames each: {} images + {} warm-up + "
               "{} x {} timed\n",
               results.configurations.size(), failed, options.views.size(), options.views.size(),
               options.warmup_frames, options.rounds, options.frames_per_round);
    fmt::print("timed frames: {:.1f} s; run: {:.1f} s; total wall time incl. context and "
               "compile: {:.1f} s (target < 180 s)\n",
               timed_ms / 1000.0, results.wall_seconds, total);
    fmt::print("images and results.json in {}\n", options.out_dir.string());
    return failed > 0 ? 1 : 0;
}
