// Benchmark (a): the share of each frame the harness spends outside GL (planning the frame on
// the CPU: matrices, the infinite water polygon, oblique projections, per-pass culling), next to
// the whole frame (submission + glFinish). Target: under 3%. Prints figures; never fails a build.
#include "tidepool/VariantConfig.h"
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <fmt/format.h>

using namespace tidepool;
using namespace tidepool::runner;

int main() {
    setenv("LP_NUM_THREADS", "2", 0);  // the CLI's default, unless the caller chose otherwise
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
    std::string error;
    std::unique_ptr<WaterRenderer> renderer =
            WaterRenderer::Create(*context.context, *loaded.config, RenderSettings{}, &error);
    if (!renderer) {
        fmt::print(stderr, "{}\n", error);
        return 3;
    }
    const ConfigurationSet set = BuildDefaultConfigurations(*loaded.config, {});
    const CameraView view = DefaultViews().front();
    constexpr int kWarmup = 3;
    constexpr int kFrames = 20;
    using Clock = std::chrono::steady_clock;
    fmt::print("{:<70} {:>9} {:>9} {:>9} {:>7}\n", "preset configuration", "frame ms", "plan ms",
               "submit ms", "plan %");
    double worst_share = 0;
    for (const RenderConfiguration& c : set.configurations) {
        if (!renderer->Prepare(c).valid) {
            fmt::print("{:<70} driver rejected it\n", c.id);
            continue;
        }
        for (int i = 0; i < kWarmup; ++i) {
            renderer->RenderFrame(c, view);
            renderer->Finish();
        }
        std::vector<double> frame_ms;
        std::vector<double> plan_ms;
        std::vector<double> submit_ms;
        for (int i = 0; i < kFrames; ++i) {
            const Clock::time_point start = Clock::now();
            const FrameReport report = renderer->RenderFrame(c, view);
            const Clock::time_point submitted = Clock::now();
            renderer->Finish();
            const Clock::time_point done = Clock::now();
            frame_ms.push_back(std::chrono::duration<double, std::milli>(done - start).count());
            submit_ms.push_back(
                    std::chrono::duration<double, std::milli>(submitted - start).count());
            plan_ms.push_back(report.plan_seconds * 1000.0);
        }
        // A benchmark checks what it rendered: a wrong (e.g. empty) image must not post a time.
        const base::RgbaImage image = renderer->ReadImage();
        std::set<std::uint32_t> colours;
        for (std::size_t p = 0; p + 3 < image.pixels.size(); p += 4 * 97) {
            colours.insert(static_cast<std::uint32_t>(image.pixels[p]) << 16 |
                           static_cast<std::uint32_t>(image.pixels[p + 1]) << 8 |
                           image.pixels[p + 2]);
        }
        if (colours.size() < 50) {
            fmt::print("{:<70} image looks wrong ({} colours)\n", c.id, colours.size());
            continue;
        }
        const double frame = base::Median(frame_ms);
        const double plan = base::Median(plan_ms);
        const double submit = base::Median(submit_ms);
        const double share = 100.0 * plan / frame;
        worst_share = std::max(worst_share, share);
        fmt::print("{:<70} {:>9.3f} {:>9.4f} {:>9.3f} {:>6.3f}%\n", c.id, frame, plan, submit,
                   share);
    }
    fmt::print("\nworst harness share of a frame: {:.3f}% (target < 3%) on {} via {}\n",
               worst_share, context.context->Environment().renderer,
               context.context->Environment().backend);
    fmt::print(
            "plan = CPU-only frame planning in the harness; submit = RenderFrame returning "
            "(plan + GL calls the driver queues); frame = submit + glFinish.\n");
    return 0;
}
