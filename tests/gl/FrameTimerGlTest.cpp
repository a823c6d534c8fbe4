// Frame timing on a real context (runner/include/tidepool/runner/FrameTimer.h): per-pass times
// against the frame's, and the GPU timer-query clock where the driver offers it.
#include "tidepool/base/SampleStatistics.h"
#include "tidepool/runner/FrameTimer.h"
#include "tidepool/runner/ProceduralScene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "SharedWaterRenderer.h"

namespace tidepool::runner {
namespace {

using test_support::WaterConfiguration;

// The per-pass times of an instrumented frame (a glFinish after each pass) add up to that
// frame's time to within 2% (they partition it; the rest is one final glFinish), and to within
// 30% of ordinary frames' time, interleaved with them. Why 30%: the suite runs llvmpipe with
// worker threads (LP_NUM_THREADS=2), and each glFinish between passes wakes them, which cost up
// to 20% extra process CPU time when the GL tests ran two at a time; rendering on the calling
// thread, as `run` does, the two agreed within 5% (printed below).
TEST(FrameTimerGlTest, PassTimesSumToTheFrameTime) {
    test_support::SharedRenderer& s = test_support::SharedWaterRenderer();
    ASSERT_TRUE(s.context) << s.error;
    s.context->MakeCurrent();
    const RenderConfiguration c = WaterConfiguration({"ENABLE_REFRACTION", "ENABLE_FOG"});
    ASSERT_TRUE(s.renderer->Prepare(c).valid);
    const CameraView view = *FindView(DefaultViews(), "three_quarter");
    FrameTimer timer(*s.renderer, FrameClock::kProcessCpu);
    std::vector<double> sums;
    std::vector<double> instrumented;
    std::vector<double> plain;
    for (int i = 0; i < 15; ++i) {
        const std::map<std::string, double> passes = timer.TimePasses(c, view);
        double sum = 0;
        for (const auto& [name, ms] : passes) {
            sum += name == "frame" ? 0.0 : ms;
        }
        EXPECT_EQ(passes.count("reflection") + passes.count("refraction") + passes.count("main"),
                  3U);
        sums.push_back(sum);
        instrumented.push_back(passes.at("frame"));
        plain.push_back(timer.Time(c, view).ms);
    }
    std::printf("pass sum %.2f ms, instrumented frame %.2f ms, plain frame %.2f ms\n",
                base::Median(sums), base::Median(instrumented), base::Median(plain));
    EXPECT_NEAR(base::Median(sums), base::Median(instrumented), 0.02 * base::Median(instrumented));
    EXPECT_NEAR(base::Median(sums), base::Median(plain), 0.30 * base::Median(plain));
}

// llvmpipe offers GL_EXT_disjoint_timer_query, so the GPU clock's path runs here too, though
// ChooseFrameClock never picks it for a software renderer.
TEST(FrameTimerGlTest, GpuTimerQueriesTimeFramesWhereTheDriverOffersThem) {
    test_support::SharedRenderer& s = test_support::SharedWaterRenderer();
    ASSERT_TRUE(s.context) << s.error;
    if (!s.context->Environment().timer_query) {
        GTEST_SKIP() << "this driver has no GL_EXT_disjoint_timer_query";
    }
    s.context->MakeCurrent();
    const RenderConfiguration c = WaterConfiguration({"ENABLE_FOG"});
    ASSERT_TRUE(s.renderer->Prepare(c).valid);
    FrameTimer timer(*s.renderer, FrameClock::kGpuTimer);
    const FrameTime t = timer.Time(c, *FindView(DefaultViews(), "three_quarter"));
    EXPECT_TRUE(std::isfinite(t.ms));
    EXPECT_GE(t.ms, 0.0);
    EXPECT_TRUE(std::isnan(s.renderer->EndGpuTimerMs()));  // no query runs: no time
}

}  // namespace
}  // namespace tidepool::runner
