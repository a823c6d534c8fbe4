// The competitor tidepool's contended timing runs beside the render thread
// (base/include/tidepool/base/CoreCompetitor.h).
#include "tidepool/base/CoreCompetitor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <iterator>
#include <thread>

#include <pthread.h>
#include <sched.h>

namespace tidepool::base {
namespace {

// Threads of this process now, from /proc.
long ThreadsOfThisProcess() {
    return std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                         std::filesystem::directory_iterator{});
}

// How many cores the calling thread may run on.
int CoresOfThisThread() {
    cpu_set_t set;
    CPU_ZERO(&set);
    pthread_getaffinity_np(pthread_self(), sizeof set, &set);
    return CPU_COUNT(&set);
}

TEST(CoreCompetitorTest, ACompetitorSharesTheCallersCoreWhileItLivesAndThenGoes) {
    const long threads_before = ThreadsOfThisProcess();
    const int cores_before = CoresOfThisThread();
    {
        const CoreCompetitor competitor;
        ASSERT_TRUE(competitor.Running());
        EXPECT_EQ(ThreadsOfThisProcess(), threads_before + 1);
        if (competitor.Pinned()) {
            EXPECT_EQ(CoresOfThisThread(), 1);
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (competitor.Passes() < 6 && std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        EXPECT_GE(competitor.Passes(), 6);  // it walks its buffer
    }
    EXPECT_EQ(ThreadsOfThisProcess(), threads_before);
    EXPECT_EQ(CoresOfThisThread(), cores_before);  // the caller has its own cores back
}

// On a machine that lets threads choose their cores (any Linux without a restricting cpuset
// that forbids it), both threads are pinned.
TEST(CoreCompetitorTest, BothThreadsArePinnedWhereTheSystemAllows) {
    const CoreCompetitor competitor;
    EXPECT_TRUE(competitor.Pinned());
}

}  // namespace
}  // namespace tidepool::base
