// A list of work units that two processes forked from one parent share: each unit is done by
// exactly one of them, claimed first come, first served. `run` uses it so that the process
// beside the render, which has its own core, takes configurations' images off the render's
// work list instead of leaving that core idle.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace tidepool::base {

/// The claim table: one state per unit in memory shared (mmap MAP_SHARED) with every process
/// forked after it is made. The "owner" process is the one whose results hold every unit in the
/// end; the "helper" takes units and hands each back when it is done. The owner takes back a unit
/// the helper claimed but stopped working on (it crashed or stalled), so a unit is never lost.
class SharedClaims {
public:
    enum class State : int { kFree = 0, kOwner, kHelperWorking, kHelperDone };

    /// A table of `units` free units, or null when the shared memory cannot be mapped (the caller
    /// then runs without a helper).
    static std::unique_ptr<SharedClaims> Create(std::size_t units);
    ~SharedClaims();
    SharedClaims(const SharedClaims&) = delete;
    SharedClaims& operator=(const SharedClaims&) = delete;

    std::size_t Size() const { return units_; }
    State StateOf(std::size_t unit) const;

    /// The owner claims `unit`; false when the helper has it.
    bool ClaimForOwner(std::size_t unit);
    /// The helper claims `unit` and beats its heartbeat; false when the unit is taken.
    bool ClaimForHelper(std::size_t unit);
    /// The helper finished `unit`; false when the owner took it back meanwhile (the helper's
    /// result must then be dropped).
    bool FinishForHelper(std::size_t unit);

    /// The helper is alive (working on its claimed units, or on its own work before them): sets
    /// its heartbeat to now.
    void Beat();
    /// Whether the helper's heartbeat is older than `quiet` (the table's creation counts as a
    /// beat).
    bool HelperSilentFor(std::chrono::milliseconds quiet) const;
    /// Whether the helper is taking units now (it says so; it stops when none are left for it,
    /// or when it cannot take any), and whether it has stopped: a helper that has stopped does
    /// not start again.
    void SetHelperTaking(bool taking);
    bool HelperTaking() const;
    bool HelperStopped() const;
    /// Whether the helper has claimed `unit`, done or not; false for a unit past the table.
    bool HelperHas(std::size_t unit) const;

    /// When the helper expects to start taking units (it has other work first), as it last said;
    /// the owner plans its own share with it. Nothing until the helper has said.
    void ExpectHelperAt(std::chrono::steady_clock::time_point when);
    std::optional<std::chrono::steady_clock::time_point> HelperExpectedAt() const;

    /// Waits until the helper has finished every unit it claimed, checking every `poll` and
    /// calling `each_poll` (when given) before each wait. When its heartbeat is older than
    /// `stall`, takes its unfinished units back for the owner and returns them (the owner must
    /// then do them itself); otherwise returns nothing.
    std::vector<std::size_t> AwaitHelper(std::chrono::milliseconds stall,
                                         std::chrono::milliseconds poll,
                                         const std::function<void()>& each_poll = {});

private:
    struct Header {
        std::atomic<std::int64_t> heartbeat_ns;        // steady clock, shared by every process
        std::atomic<int> helper_taking;                // 0: not yet, 1: taking, 2: stopped
        std::atomic<std::int64_t> helper_expected_ns;  // steady clock; 0: not said
    };
    SharedClaims(void* memory, std::size_t bytes, std::size_t units);
    std::atomic<int>& Slot(std::size_t unit) const;

    void* memory_;
    std::size_t bytes_;
    std::size_t units_;
    Header* header_;
    std::atomic<int>* states_;
};

}  // namespace tidepool::base
