#include "tidepool/base/CoreCompetitor.h"

#include <cstddef>
#include <system_error>
#include <vector>

#include <pthread.h>

namespace tidepool::base {
namespace {

// Pins `thread` to `cpu` alone; false when the system refuses.
bool PinTo(pthread_t thread, int cpu) {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(static_cast<std::size_t>(cpu), &one);
    return pthread_setaffinity_np(thread, sizeof one, &one) == 0;
}

}  // namespace

CoreCompetitor::CoreCompetitor() {
    const pthread_t self = pthread_self();
    const int cpu = sched_getcpu();
    restore_ = cpu >= 0 && pthread_getaffinity_np(self, sizeof cores_, &cores_) == 0;
    pinned_ = restore_ && PinTo(self, cpu);
    try {
        thread_ = std::thread([this] {
            constexpr std::size_t kLine = 64;
            std::vector<unsigned char> buffer(kBufferBytes);
            // volatile: the writes are the point, though nothing reads them.
            volatile unsigned char* bytes = buffer.data();
            while (!stop_.load(std::memory_order_relaxed)) {
                for (std::size_t i = 0; i < kBufferBytes; i += kLine) {
                    bytes[i] = static_cast<unsigned char>(bytes[i] + 1);
                }
                passes_.fetch_add(1, std::memory_order_relaxed);
            }
        });
    } catch (const std::system_error&) {
        pinned_ = false;  // no competitor
        return;
    }
    pinned_ = pinned_ && PinTo(thread_.native_handle(), cpu);
}

CoreCompetitor::~CoreCompetitor() {
    stop_.store(true, std::memory_order_relaxed);
    if (thread_.joinable()) {
        thread_.join();
    }
    if (restore_) {
        pthread_setaffinity_np(pthread_self(), sizeof cores_, &cores_);
    }
}

}  // namespace tidepool::base
