#include "tidepool/base/WorkerProcessPool.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <future>
#include <memory>
#include <new>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "AddressSanitizer.h"
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace tidepool::base {
namespace {

TEST(WorkerProcessPoolTest, ResultsComeBackInItemOrderFromSeveralWorkers) {
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            20, 3, WorkerLimits{},
            [](std::size_t i, const ProgressNote&) { return std::to_string(i * i); });
    ASSERT_EQ(results.size(), 20U);
    for (std::size_t i = 0; i < results.size(); ++i) {
        EXPECT_EQ(results[i].failure, WorkerFailure::kNone);
        EXPECT_EQ(results[i].payload, std::to_string(i * i));
    }
}

// `run` plans scenes on two threads, and each plan validates its candidates in a pool of its
// own: a worker forked by one pool must not hold the other pool's sockets open, or neither
// pool's workers see their end and both wait forever.
TEST(WorkerProcessPoolTest, PoolsOnSeveralThreadsAtOnceAllFinish) {
    constexpr int kThreads = 4;
    std::vector<std::future<std::size_t>> runs;
    for (int t = 0; t < kThreads; ++t) {
        runs.push_back(std::async(std::launch::async, [] {
            std::size_t finished = 0;
            for (int round = 0; round < 5; ++round) {
                const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
                        6, 2, WorkerLimits{},
                        [](std::size_t i, const ProgressNote&) { return std::to_string(i); });
                for (const WorkerItemResult& r : results) {
                    finished += r.failure == WorkerFailure::kNone ? 1 : 0;
                }
            }
            return finished;
        }));
    }
    for (std::future<std::size_t>& run : runs) {
        ASSERT_EQ(run.wait_for(std::chrono::seconds(60)), std::future_status::ready)
                << "pools on several threads wait for each other's workers";
        EXPECT_EQ(run.get(), 30U);
    }
}

TEST(WorkerProcessPoolTest, CrashFailsOnlyItsItemAndKeepsItsNotes) {
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(4, 1, WorkerLimits{}, [](std::size_t i, const ProgressNote& note) {
                note("before");
                if (i == 1) {
                    std::raise(SIGSEGV);
                }
                return std::string("ok");
            });
    ASSERT_EQ(results.size(), 4U);
    EXPECT_EQ(results[0].payload, "ok");
    EXPECT_EQ(results[1].failure, WorkerFailure::kCrashed);
    EXPECT_EQ(results[1].notes, std::vector<std::string>{"before"});
    // "signal 11 (...)"; under AddressSanitizer the worker reports the fault and exits instead.
    EXPECT_FALSE(results[1].detail.empty());
    EXPECT_EQ(results[2].payload, "ok");  // a fresh worker took over
    EXPECT_EQ(results[3].payload, "ok");
}

// The stack size of the calling thread, as text (an item's payload); "0" when unknown.
std::string OwnStackSize() {
    std::size_t size = 0;
    pthread_attr_t attributes;
    if (::pthread_getattr_np(::pthread_self(), &attributes) == 0) {
        ::pthread_attr_getstacksize(&attributes, &size);
        ::pthread_attr_destroy(&attributes);
    }
    return std::to_string(size);
}

// A pool asked for a stack size runs its items on a stack that large: glslang's preprocessor
// recurses once for each parenthesis of an `#if`, and on the usual 8 MiB 60,000 crashed it.
TEST(WorkerProcessPoolTest, ItemsRunOnAStackOfTheSizeAsked) {
    WorkerLimits limits;
    limits.stack_bytes = std::size_t{64} << 20;
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            3, 2, limits, [](std::size_t, const ProgressNote&) { return OwnStackSize(); });
    ASSERT_EQ(results.size(), 3U);
    for (const WorkerItemResult& r : results) {
        ASSERT_EQ(r.failure, WorkerFailure::kNone) << r.detail;
        EXPECT_GE(std::stoull(r.payload), limits.stack_bytes);
    }
}

// With no descriptor left for a worker's sockets, the items run in the calling process: on the
// stack asked for too (before, on the caller's own, where a deep `#if` crashed the process).
TEST(WorkerProcessPoolTest, ItemsRunWithoutIsolationStillGetTheStackAsked) {
    WorkerLimits limits;
    limits.stack_bytes = std::size_t{64} << 20;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // Exit 0 only when every item ran here, on a stack of the size asked.
        const rlimit no_more_files{3, 3};  // stdin, stdout, stderr
        if (::setrlimit(RLIMIT_NOFILE, &no_more_files) != 0) {
            ::_exit(2);
        }
        std::vector<WorkerItemResult> results;
        try {
            results = RunInWorkerProcesses(
                    2, 2, limits, [](std::size_t, const ProgressNote&) { return OwnStackSize(); });
        } catch (...) {
            ::_exit(3);
        }
        bool right = results.size() == 2;
        for (const WorkerItemResult& r : results) {
            right = right && r.failure == WorkerFailure::kNone &&
                    r.detail.find("without isolation") != std::string::npos &&
                    std::stoull(r.payload) >= limits.stack_bytes;
        }
        ::_exit(right ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 0)
            << "1: an item ran on another stack or failed; 2: setrlimit; 3: an exception";
}

TEST(WorkerProcessPoolTest, NotesKeepTheirOrderWhateverWayTheyTravel) {
    // Short notes go without waking the parent; one that finds that way full (600 KB of notes
    // is more than a socket holds), or is too long for it (the last one), goes with the
    // records. Each item's notes come back whole and in the order sent, also when the item
    // then crashes, and with items handed ahead.
    WorkerLimits limits;
    limits.items_ahead = 2;
    auto notes_of = [](std::size_t i) {
        std::vector<std::string> notes;
        for (int n = 0; n < 600; ++n) {
            notes.push_back(std::to_string(i) + ":" + std::to_string(n) + std::string(1000, 'x'));
        }
        notes.push_back(std::string(70000, static_cast<char>('a' + i)));
        return notes;
    };
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(6, 2, limits, [&](std::size_t i, const ProgressNote& note) {
                for (const std::string& text : notes_of(i)) {
                    note(text);
                }
                if (i == 3) {
                    std::raise(SIGSEGV);
                }
                return std::string("done");
            });
    ASSERT_EQ(results.size(), 6U);
    for (std::size_t i = 0; i < results.size(); ++i) {
        EXPECT_EQ(results[i].failure, i == 3 ? WorkerFailure::kCrashed : WorkerFailure::kNone);
        EXPECT_TRUE(results[i].notes == notes_of(i))
                << "item " << i << ": " << results[i].notes.size() << " notes";
    }
}

TEST(WorkerProcessPoolTest, ItemsHandedAheadOfAFailureRunInAFreshWorker) {
    // Each worker holds two items beyond the one it runs; item 1 crashes with 2 and 3 waiting
    // behind it, item 4 hangs with 5 and 6 behind it. Every other item runs once, in a process
    // that did not fail, and reports its own notes.
    WorkerLimits limits;
    limits.seconds_per_item = 0.5;
    limits.items_ahead = 2;
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(8, 1, limits, [](std::size_t i, const ProgressNote& note) {
                note("item " + std::to_string(i));
                if (i == 1) {
                    std::raise(SIGSEGV);
                }
                if (i == 4) {
                    std::this_thread::sleep_for(std::chrono::seconds(30));
                }
                return "done " + std::to_string(i);
            });
    ASSERT_EQ(results.size(), 8U);
    EXPECT_EQ(results[1].failure, WorkerFailure::kCrashed);
    EXPECT_EQ(results[1].notes, std::vector<std::string>{"item 1"});
    EXPECT_EQ(results[4].failure, WorkerFailure::kTimedOut);
    for (const std::size_t i : {0U, 2U, 3U, 5U, 6U, 7U}) {
        EXPECT_EQ(results[i].failure, WorkerFailure::kNone) << i;
        EXPECT_EQ(results[i].payload, "done " + std::to_string(i));
        EXPECT_EQ(results[i].notes, std::vector<std::string>{"item " + std::to_string(i)});
    }
}

TEST(WorkerProcessPoolTest, ItemsAheadStillSpreadFewItemsOverTheWorkers) {
    // Two items and two workers: each worker gets one, although each may hold two.
    WorkerLimits limits;
    limits.items_ahead = 1;
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            2, 2, limits,
            [](std::size_t, const ProgressNote&) { return std::to_string(::getpid()); });
    ASSERT_EQ(results.size(), 2U);
    EXPECT_NE(results[0].payload, results[1].payload);
}

// How often the worker (the process id each item returned) changes from one item to the next.
std::size_t WorkerChanges(const std::vector<WorkerItemResult>& results) {
    std::size_t changes = 0;
    for (std::size_t i = 1; i < results.size(); ++i) {
        changes += results[i].payload != results[i - 1].payload ? 1U : 0U;
    }
    return changes;
}

TEST(WorkerProcessPoolTest, ContiguousSharesKeepNeighbouringItemsInOneWorker) {
    WorkerLimits limits;
    limits.items_ahead = 1;
    auto run = [&limits](bool contiguous) {
        limits.contiguous_shares = contiguous;
        return RunInWorkerProcesses(40, 2, limits, [](std::size_t, const ProgressNote&) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            return std::to_string(::getpid());
        });
    };
    const std::vector<WorkerItemResult> shared = run(true);
    // Each worker runs its own half in order, and the one done first then the last items of
    // the other's: the worker changes at most twice along the items.
    EXPECT_LE(WorkerChanges(shared), 2U);
    // Both ran items: each is handed the first of its share at once (under load the other may
    // then take all the rest).
    std::set<std::string> workers;
    for (const WorkerItemResult& result : shared) {
        workers.insert(result.payload);
    }
    EXPECT_EQ(workers.size(), 2U);
    // The control: handed out in plain order, the two workers take turns.
    EXPECT_GT(WorkerChanges(run(false)), 2U);
}

TEST(WorkerProcessPoolTest, AWorkerDoneWithItsShareTakesTheLastItemsOfAnother) {
    // The first half's items take 10 ms, the second half's 1 ms: the second worker finishes its
    // half first and then takes the first half's items from its end, until the two meet.
    WorkerLimits limits;
    limits.contiguous_shares = true;
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(40, 2, limits, [](std::size_t i, const ProgressNote&) {
                std::this_thread::sleep_for(std::chrono::milliseconds(i < 20 ? 10 : 1));
                return std::to_string(::getpid());
            });
    EXPECT_EQ(WorkerChanges(results), 1U);
    std::size_t meet = 1;
    while (meet < results.size() && results[meet].payload == results[0].payload) {
        ++meet;
    }
    EXPECT_LT(meet, 20U);  // the second worker ran some of the first half
    EXPECT_GT(meet, 0U);
}

TEST(WorkerProcessPoolTest, ContiguousSharesRunEveryItemOnceThroughCrashesAndSkips) {
    WorkerLimits limits;
    limits.contiguous_shares = true;
    limits.items_ahead = 2;
    std::vector<int> ended(30, 0);
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            30, 3, limits,
            [](std::size_t i, const ProgressNote& note) {
                note("item " + std::to_string(i));
                if (i == 7 || i == 18) {
                    std::raise(SIGSEGV);
                }
                return "done " + std::to_string(i);
            },
            [](std::size_t i) { return i % 5 != 0; },
            [&ended](std::size_t i, const WorkerItemResult&) { ++ended[i]; });
    for (std::size_t i = 0; i < results.size(); ++i) {
        EXPECT_EQ(ended[i], 1) << i;
        if (i % 5 == 0) {
            EXPECT_EQ(results[i].failure, WorkerFailure::kSkipped) << i;
        } else if (i == 7 || i == 18) {
            EXPECT_EQ(results[i].failure, WorkerFailure::kCrashed) << i;
        } else {
            EXPECT_EQ(results[i].payload, "done " + std::to_string(i));
            EXPECT_EQ(results[i].notes, std::vector<std::string>{"item " + std::to_string(i)});
        }
    }
}

TEST(WorkerProcessPoolTest, ItemThatTakesTooLongIsKilledAndReportedAsTimedOut) {
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            2, 1, WorkerLimits{0, 0.5}, [](std::size_t i, const ProgressNote&) {
                if (i == 0) {
                    std::this_thread::sleep_for(std::chrono::seconds(30));
                }
                return std::string("done");
            });
    EXPECT_EQ(results[0].failure, WorkerFailure::kTimedOut);
    EXPECT_EQ(results[0].detail, "took longer than 0.5 s");
    EXPECT_EQ(results[1].payload, "done");
}

// Whether process `pid` has ended: gone, or a zombie nobody has reaped yet (a container's first
// process may never reap the orphans it inherits).
bool Ended(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) {
        return true;
    }
    const std::size_t after_name = line.rfind(')');
    return after_name == std::string::npos || line.compare(after_name, 3, ") Z") == 0;
}

// Before, a worker outlived a parent killed by `timeout` or a cancelled CI job and went on with
// its item, past its time limit, which only the parent enforces.
TEST(WorkerProcessPoolTest, WorkersDieWithTheProcessThatForkedThem) {
    // The worker names itself in a file: a worker closes every descriptor but its own sockets.
    char folder[] = "/tmp/tidepool-pdeathsig.XXXXXX";
    ASSERT_NE(::mkdtemp(folder), nullptr);
    const std::string pid_file = std::string(folder) + "/worker";
    const pid_t parent = ::fork();
    ASSERT_GE(parent, 0);
    if (parent == 0) {
        RunInWorkerProcesses(1, 1, WorkerLimits{0, 60}, [&](std::size_t, const ProgressNote&) {
            std::ofstream(pid_file + ".tmp") << ::getpid() << "\n";
            std::rename((pid_file + ".tmp").c_str(), pid_file.c_str());
            std::this_thread::sleep_for(std::chrono::seconds(60));
            return std::string("never");
        });
        ::_exit(0);
    }
    pid_t worker = 0;
    const auto named_by = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (worker == 0 && std::chrono::steady_clock::now() < named_by) {
        std::ifstream(pid_file) >> worker;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::remove(pid_file.c_str());
    ::rmdir(folder);
    ASSERT_GT(worker, 0) << "the worker never named itself";
    ASSERT_FALSE(Ended(worker));
    ::kill(parent, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(parent, &status, 0), parent);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!Ended(worker) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const bool ended = Ended(worker);
    if (!ended) {
        ::kill(worker, SIGKILL);  // not to leave it behind when the test fails
    }
    EXPECT_TRUE(ended) << "the worker outlived its parent";
}

// Runs under AddressSanitizer too, where the worker counts its allocations instead of living
// under an address-space limit: 256 MiB blocks pass a 1 GiB limit at the fourth.
TEST(WorkerProcessPoolTest, FailedAllocationIsReportedAsOutOfMemory) {
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            2, 1, WorkerLimits{std::uint64_t{1} << 30, 0}, [](std::size_t i, const ProgressNote&) {
                std::vector<std::unique_ptr<char[]>> blocks;
                for (int k = 0; i == 0 && k < 64; ++k) {
                    blocks.emplace_back(new char[std::size_t{256} << 20]);
                }
                return std::string(i == 0 ? "unreachable" : "fine");
            });
    EXPECT_EQ(results[0].failure, WorkerFailure::kOutOfMemory) << results[0].detail;
    EXPECT_EQ(results[1].payload, "fine");  // a fresh worker took over
}

TEST(WorkerProcessPoolTest, SkippedItemsAreNotRunAndEveryEndIsReported) {
    std::vector<std::size_t> ended;
    const std::vector<WorkerItemResult> results = RunInWorkerProcesses(
            3, 2, WorkerLimits{}, [](std::size_t, const ProgressNote&) { return std::string("x"); },
            [](std::size_t i) { return i != 1; },
            [&](std::size_t i, const WorkerItemResult&) { ended.push_back(i); });
    EXPECT_EQ(results[1].failure, WorkerFailure::kSkipped);
    EXPECT_EQ(results[0].payload, "x");
    EXPECT_EQ(results[2].payload, "x");
    EXPECT_EQ(ended.size(), 3U);
}

// Page faults of each item after the first, in one worker, when every item allocates 160 MiB in
// 4 KiB blocks, touches them and frees them: far more than glibc keeps at the heap's top even
// after its thresholds have grown (to at most 64 MiB) in the process the worker was forked from,
// as they have when this runs after other tests in one process. (With 80 MiB, as before, only
// 16 MiB, 4,096 pages, were sure to go back: the whole binary run in one process gave 6,951.)
std::vector<long> LaterItemsPageFaults(bool keep_freed_memory) {
    constexpr int kBlocks = 40960;
    constexpr std::size_t kBlock = 4096;
    WorkerLimits limits;
    limits.keep_freed_memory = keep_freed_memory;
    const std::vector<WorkerItemResult> results =
            RunInWorkerProcesses(4, 1, limits, [](std::size_t, const ProgressNote&) {
                rusage before{};
                ::getrusage(RUSAGE_SELF, &before);
                {
                    std::vector<std::unique_ptr<char[]>> blocks;
                    blocks.reserve(kBlocks);
                    for (int b = 0; b < kBlocks; ++b) {
                        blocks.push_back(std::make_unique<char[]>(kBlock));
                        blocks.back()[0] = 1;
                    }
                }
                rusage after{};
                ::getrusage(RUSAGE_SELF, &after);
                return std::to_string(after.ru_minflt - before.ru_minflt);
            });
    std::vector<long> faults;
    for (std::size_t i = 1; i < results.size(); ++i) {
        faults.push_back(std::stol(results[i].payload));
    }
    return faults;
}

TEST(WorkerProcessPoolTest, AWorkerAskedToKeepFreedMemoryDoesNotFaultItInAgain) {
#if defined(TIDEPOOL_TEST_ADDRESS_SANITIZER)
    GTEST_SKIP() << "AddressSanitizer's allocator is not glibc's";
#endif
    // glibc hands the heap's free top back after each item (40,960 pages here), unless asked
    // not to.
    for (long faults : LaterItemsPageFaults(false)) {
        EXPECT_GE(faults, 10000);
    }
    for (long faults : LaterItemsPageFaults(true)) {
        EXPECT_LT(faults, 100);
    }
}

}  // namespace
}  // namespace tidepool::base
