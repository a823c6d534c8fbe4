// The one parallel loop: independent work items spread over a few threads, for the report's
// image comparisons and the benchmarks.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tidepool::base {

/// Runs fn(i) for every i in [0, count) on up to `jobs` threads (at most `count`; the calling
/// thread alone when that is 1 or less), each index exactly once, in no particular order; fn
/// must only touch state owned by index i. Threads take the next index as they finish one, so
/// uneven items balance. When fn throws, the remaining items still run and the first exception
/// is rethrown here after every thread has finished.
template <typename Fn>
void ParallelFor(std::size_t count, int jobs, Fn fn) {
    const std::size_t workers =
            std::min<std::size_t>(count, static_cast<std::size_t>(std::max(jobs, 1)));
    if (workers <= 1) {
        for (std::size_t i = 0; i < count; ++i) {
            fn(i);
        }
        return;
    }
    std::atomic<std::size_t> next{0};
    std::mutex failure_mutex;
    std::exception_ptr failure;
    std::vector<std::thread> threads;
    threads.reserve(workers);
    for (std::size_t w = 0; w < workers; ++w) {
        threads.emplace_back([&] {
            for (std::size_t i = next++; i < count; i = next++) {
                try {
                    fn(i);
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(failure_mutex);
                    if (!failure) {
                        failure = std::current_exception();
                    }
                }
            }
        });
    }
    for (std::thread& thread : threads) {
        thread.join();
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
}

}  // namespace tidepool::base
