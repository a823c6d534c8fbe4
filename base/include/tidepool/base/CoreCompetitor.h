// Another job on the render thread's core, for a while: the contended half of tidepool's
// timing (PairedEstimate's AcrossHostStates), where each comparison is also timed with its
// rendering thread sharing a core the way it does on a busy machine. Linux only.
#pragma once

#include <atomic>
#include <cstddef>
#include <thread>

#include <sched.h>

namespace tidepool::base {

/// While it lives, the calling thread and one competing thread are both pinned to the core the
/// calling thread was on, and the competitor walks a buffer of kBufferBytes without a pause,
/// writing one byte per cache line: the calling thread then gets its core in turns and finds
/// its caches disturbed, as beside a compiler or `yes`, while the machine's other cores stay
/// free for whatever else runs (`tidepool run`'s second process). Destroying it stops and joins
/// the competitor and gives the calling thread back its own set of cores. Never fails: when the
/// threads cannot be pinned the competitor runs unpinned (Pinned() says so), and when it cannot
/// be started there is none (Running()).
class CoreCompetitor {
public:
    /// Half of a core's L2 cache on the hosts this was measured on (2 MiB a core): enough to
    /// evict part of what the render thread had cached at each turn, as another job would.
    static constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

    CoreCompetitor();
    ~CoreCompetitor();
    CoreCompetitor(const CoreCompetitor&) = delete;
    CoreCompetitor& operator=(const CoreCompetitor&) = delete;

    /// True when the competitor started.
    bool Running() const { return thread_.joinable(); }
    /// True when both threads were pinned to one core.
    bool Pinned() const { return pinned_; }
    /// Passes over its buffer the competitor has finished so far (a test sees it work).
    long Passes() const { return passes_.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> stop_{false};
    std::atomic<long> passes_{0};
    bool pinned_ = false;
    bool restore_ = false;  // the calling thread's own set of cores is saved in `cores_`
    cpu_set_t cores_{};
    std::thread thread_;
};

}  // namespace tidepool::base
