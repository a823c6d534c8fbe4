#include "tidepool/base/SharedClaims.h"

#include <algorithm>
#include <new>
#include <thread>

#include <sys/mman.h>

namespace tidepool::base {

// Atomics in memory two processes map work only when they need no lock (a lock would live in
// one process); lock-free atomics are address-free, so both see one variable.
static_assert(std::atomic<int>::is_always_lock_free);
static_assert(std::atomic<std::int64_t>::is_always_lock_free);

namespace {

std::int64_t NowNs() {
    // steady_clock is CLOCK_MONOTONIC on Linux: one clock for every process on the machine.
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
}

int Int(SharedClaims::State state) {
    return static_cast<int>(state);
}

}  // namespace

std::unique_ptr<SharedClaims> SharedClaims::Create(std::size_t units) {
    const std::size_t bytes = sizeof(Header) + std::max<std::size_t>(units, 1) * sizeof(int);
    void* memory =
            ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) {
        return nullptr;
    }
    return std::unique_ptr<SharedClaims>(new SharedClaims(memory, bytes, units));
}

SharedClaims::SharedClaims(void* memory, std::size_t bytes, std::size_t units)
    : memory_(memory), bytes_(bytes), units_(units) {
    header_ = new (memory_) Header{};
    header_->heartbeat_ns.store(NowNs());
    header_->helper_taking.store(0);
    header_->helper_expected_ns.store(0);
    auto* slots = reinterpret_cast<std::atomic<int>*>(static_cast<char*>(memory_) + sizeof(Header));
    for (std::size_t i = 0; i < units_; ++i) {
        new (slots + i) std::atomic<int>(Int(State::kFree));
    }
    states_ = slots;
}

SharedClaims::~SharedClaims() {
    ::munmap(memory_, bytes_);
}

std::atomic<int>& SharedClaims::Slot(std::size_t unit) const {
    return states_[unit];
}

SharedClaims::State SharedClaims::StateOf(std::size_t unit) const {
    return static_cast<State>(Slot(unit).load());
}

bool SharedClaims::ClaimForOwner(std::size_t unit) {
    int expected = Int(State::kFree);
    return Slot(unit).compare_exchange_strong(expected, Int(State::kOwner)) ||
           expected == Int(State::kOwner);
}

bool SharedClaims::ClaimForHelper(std::size_t unit) {
    Beat();
    int expected = Int(State::kFree);
    return Slot(unit).compare_exchange_strong(expected, Int(State::kHelperWorking));
}

bool SharedClaims::FinishForHelper(std::size_t unit) {
    int expected = Int(State::kHelperWorking);
    const bool finished = Slot(unit).compare_exchange_strong(expected, Int(State::kHelperDone));
    Beat();
    return finished;
}

void SharedClaims::Beat() {
    header_->heartbeat_ns.store(NowNs());
}

bool SharedClaims::HelperSilentFor(std::chrono::milliseconds quiet) const {
    return NowNs() - header_->heartbeat_ns.load() >
           std::chrono::duration_cast<std::chrono::nanoseconds>(quiet).count();
}

void SharedClaims::SetHelperTaking(bool taking) {
    header_->helper_taking.store(taking ? 1 : 2);
}

bool SharedClaims::HelperTaking() const {
    return header_->helper_taking.load() == 1;
}

bool SharedClaims::HelperStopped() const {
    return header_->helper_taking.load() == 2;
}

void SharedClaims::ExpectHelperAt(std::chrono::steady_clock::time_point when) {
    header_->helper_expected_ns.store(std::max<std::int64_t>(
            1,
            std::chrono::duration_cast<std::chrono::nanoseconds>(when.time_since_epoch()).count()));
}

std::optional<std::chrono::steady_clock::time_point> SharedClaims::HelperExpectedAt() const {
    const std::int64_t ns = header_->helper_expected_ns.load();
    if (ns == 0) {
        return std::nullopt;
    }
    return std::chrono::steady_clock::time_point(
            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                    std::chrono::nanoseconds(ns)));
}

bool SharedClaims::HelperHas(std::size_t unit) const {
    if (unit >= units_) {
        return false;
    }
    const int state = Slot(unit).load();
    return state == Int(State::kHelperWorking) || state == Int(State::kHelperDone);
}

std::vector<std::size_t> SharedClaims::AwaitHelper(std::chrono::milliseconds stall,
                                                   std::chrono::milliseconds poll,
                                                   const std::function<void()>& each_poll) {
    const auto stall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(stall).count();
    while (true) {
        std::vector<std::size_t> working;
        for (std::size_t i = 0; i < units_; ++i) {
            if (Slot(i).load() == Int(State::kHelperWorking)) {
                working.push_back(i);
            }
        }
        if (working.empty()) {
            return {};
        }
        if (NowNs() - header_->heartbeat_ns.load() > stall_ns) {
            std::vector<std::size_t> taken;
            for (std::size_t i : working) {
                int expected = Int(State::kHelperWorking);
                if (Slot(i).compare_exchange_strong(expected, Int(State::kOwner))) {
                    taken.push_back(i);
                }
            }
            return taken;
        }
        if (each_poll) {
            each_poll();
        }
        std::this_thread::sleep_for(poll);
    }
}

}  // namespace tidepool::base
