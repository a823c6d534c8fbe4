// Runs work items in forked worker processes, so that a crash, a hang or an allocation failure
// inside a third-party library (glslang) becomes the failure of one item instead of the end of
// tidepool. Browsers run their shader translators out of process for the same reason. The
// validator runs glslang this way, and `run` its render beside the stability and plan stages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tidepool::base {

/// What one worker may use.
struct WorkerLimits {
    std::uint64_t memory_bytes = 0;  // address-space limit (RLIMIT_AS) per worker; 0: none
    double seconds_per_item = 0;     // wall time one item may take before its worker is killed
    /// Items handed to a worker beyond the one it runs, so that it starts the next one without
    /// waiting for the parent to read its last result (a round trip of some 20 to 70 µs here):
    /// worth it for items of a millisecond or less. 0 for long items, which one busy worker
    /// would otherwise hold back from an idle one.
    int items_ahead = 0;
    /// Keep freed memory mapped for the worker's next item instead of handing the top of the
    /// heap back to the system (glibc does that whenever 128 KiB of it are free): for many short
    /// items that each allocate and free that much, as glslang parses do, which otherwise fault
    /// their pages in again every time. It also fixes glibc's threshold for mapping large blocks
    /// on their own at 128 KiB, so it is not for long items that allocate large buffers.
    bool keep_freed_memory = false;
    /// Each worker takes its items in order from its own contiguous share of [0, count) (one of
    /// as many equal parts as there are workers), and one whose share is done takes the last
    /// item of the largest share left. For items next to each other that share work a worker
    /// keeps between items (the links of one vertex stage, ordered so by the caller): handed out
    /// in plain order, every worker would do that work. Items are then handed out, and
    /// should_run asked, in another order than [0, count).
    bool contiguous_shares = false;
    /// The stack each worker runs its items on, in bytes (a thread of its own with a stack that
    /// size), and an item run without isolation (no worker process could be started) too; 0:
    /// the stack of the thread that forked the worker, or that runs the item. For work whose
    /// recursion the input sets: glslang's preprocessor evaluates an `#if` expression one call
    /// deeper for each parenthesis and unary operator, and on the usual 8 MiB stack 60,000 of them
    /// crashed it.
    std::size_t stack_bytes = 0;
};

/// How an item ended.
enum class WorkerFailure {
    kNone,         // the item ran; `payload` is its result
    kSkipped,      // should_run said no
    kCrashed,      // the worker died (a signal, or an exit without a result)
    kOutOfMemory,  // an allocation failed under the memory limit
    kTimedOut,     // the item took longer than seconds_per_item
};

/// The result of one item.
struct WorkerItemResult {
    WorkerFailure failure = WorkerFailure::kNone;
    std::string payload;             // what `work` returned, when failure is kNone
    std::string detail;              // for a failure: e.g. "signal 11 (Segmentation fault)"
    std::vector<std::string> notes;  // every note the item sent, in order (kept on failure too)
};

/// Sends a note from inside an item to the parent: what it is about to do, so that a failure can
/// be attributed to the step that was running, or a partial result that must survive a later
/// failure of the same item. The parent collects an item's notes when the item ends, not as
/// they are sent (a note does not wake it): they are no channel for live progress.
using ProgressNote = std::function<void(const std::string&)>;

/// Runs work(i, note) for each i in [0, count) in up to `workers` forked processes (each runs its
/// items one after another; a worker that fails is replaced by a fresh one), and returns each
/// item's result in order. `should_run(i)`, asked in the parent just before item i is handed
/// out, lets the caller skip items that earlier results made pointless; `on_result(i, result)` is
/// called in the parent as soon as item i has ended, in the order items end. Must be called from a
/// single-threaded caller (fork copies only the calling thread). Falls back to no isolation (and
/// says so in every failed item's detail) only if fork itself fails.
std::vector<WorkerItemResult> RunInWorkerProcesses(
        std::size_t count, int workers, const WorkerLimits& limits,
        const std::function<std::string(std::size_t, const ProgressNote&)>& work,
        const std::function<bool(std::size_t)>& should_run = {},
        const std::function<void(std::size_t, const WorkerItemResult&)>& on_result = {});

}  // namespace tidepool::base
