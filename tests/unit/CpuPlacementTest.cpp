#include "tidepool/base/CpuPlacement.h"
#include "tidepool/base/WorkerProcessPool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include <pthread.h>
#include <sched.h>

namespace tidepool::base {
namespace {

cpu_set_t AllowedCpus() {
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    EXPECT_EQ(sched_getaffinity(0, sizeof cpus, &cpus), 0);
    return cpus;
}

TEST(CpuPlacementTest, ANewThreadStartsOnOneOtherCpuAndThenMayRunOnAll) {
    const cpu_set_t allowed = AllowedCpus();
    if (CPU_COUNT(&allowed) < 2) {
        GTEST_SKIP() << "a single CPU: nowhere else to start";
    }
    const CpuPlacement placement;
    std::atomic<bool> placed{false};
    int cpus_before = 0;
    bool all_after = false;
    std::thread thread([&] {
        while (!placed) {
            std::this_thread::yield();
        }
        cpu_set_t mine;
        pthread_getaffinity_np(pthread_self(), sizeof mine, &mine);
        cpus_before = CPU_COUNT(&mine);
        placement.AllowAll();
        pthread_getaffinity_np(pthread_self(), sizeof mine, &mine);
        all_after = CPU_EQUAL(&mine, &allowed) != 0;
    });
    placement.StartThreadAway(thread.native_handle(), 0);
    placed = true;
    thread.join();
    EXPECT_EQ(cpus_before, 1);
    EXPECT_TRUE(all_after);
}

TEST(CpuPlacementTest, WorkerProcessesRunTheirItemsOnEveryAllowedCpu) {
    const cpu_set_t allowed = AllowedCpus();
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(4, 2, WorkerLimits{}, [](std::size_t, const ProgressNote&) {
                cpu_set_t mine;
                CPU_ZERO(&mine);
                sched_getaffinity(0, sizeof mine, &mine);
                return std::to_string(CPU_COUNT(&mine));
            });
    for (const WorkerItemResult& result : results) {
        EXPECT_EQ(result.payload, std::to_string(CPU_COUNT(&allowed)));
    }
}

}  // namespace
}  // namespace tidepool::base
