#include "tidepool/base/WorkerProcessPool.h"

#include "tidepool/base/CpuPlacement.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <deque>
#include <exception>
#include <new>

#include <fmt/format.h>
#include <malloc.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define TIDEPOOL_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TIDEPOOL_ADDRESS_SANITIZER 1
#endif
#endif

#if defined(TIDEPOOL_ADDRESS_SANITIZER)
// From the sanitizer runtime's allocator interface (sanitizer/allocator_interface.h, which GCC 12
// does not install): hooks called after every allocation and before every release, and the size
// of a live allocation.
extern "C" {
int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                  std::size_t),
                                              void (*free_hook)(const volatile void*));
std::size_t __sanitizer_get_allocated_size(const volatile void* pointer);
}
#endif

namespace tidepool::base {
namespace {

// A worker that hits its memory limit leaves with this status, from the new-handler, before
// anything can unwind through a library that was not written to survive it.
constexpr int kOutOfMemoryExit = 86;
// A worker whose item threw something else.
constexpr int kExceptionExit = 87;

#if defined(TIDEPOOL_ADDRESS_SANITIZER)
// AddressSanitizer reserves terabytes of address space for its shadow memory, so an
// address-space limit would stop every sanitized worker before it starts; and it reports a
// failed allocation and aborts instead of letting the new-handler see it. A sanitized worker
// therefore counts what it holds through the sanitizer's allocation hooks and leaves as out of
// memory once that passes the limit, so the limit and its handling are tested there too.
//
// Bytes the worker allocated since it started and still holds (signed: memory inherited from
// the parent may be freed without having been counted), and the ceiling; one thread per worker.
long long g_worker_bytes = 0;
long long g_worker_ceiling = 0;

void CountAllocation(const volatile void*, std::size_t size) {
    g_worker_bytes += static_cast<long long>(size);
    if (g_worker_ceiling > 0 && g_worker_bytes > g_worker_ceiling) {
        ::_exit(kOutOfMemoryExit);
    }
}

void CountRelease(const volatile void* pointer) {
    g_worker_bytes -= static_cast<long long>(__sanitizer_get_allocated_size(pointer));
}

void LimitMemory(std::uint64_t bytes) {
    g_worker_ceiling = static_cast<long long>(bytes);
    __sanitizer_install_malloc_and_free_hooks(CountAllocation, CountRelease);
}
#else
// An address-space limit: an allocation beyond it fails, and the new-handler ends the worker.
void LimitMemory(std::uint64_t bytes) {
    const rlimit memory{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &memory);
}
#endif

using Clock = std::chrono::steady_clock;

// Moves all `size` bytes with `step` (one send or recv), retrying after a signal; false when the
// peer has gone (a recv of 0 bytes) or the socket failed.
template <typename Byte, typename Step>
bool TransferAll(Byte* bytes, std::size_t size, Step step) {
    while (size > 0) {
        const ssize_t moved = step(bytes, size);
        if (moved < 0 && errno == EINTR) {
            continue;
        }
        if (moved <= 0) {
            return false;
        }
        bytes += moved;
        size -= static_cast<std::size_t>(moved);
    }
    return true;
}

bool SendAll(int fd, const void* data, std::size_t size) {
    // MSG_NOSIGNAL: a peer that died must be an error here, not a SIGPIPE for the process.
    return TransferAll(static_cast<const char*>(data), size, [fd](const char* b, std::size_t n) {
        return ::send(fd, b, n, MSG_NOSIGNAL);
    });
}

bool ReceiveAll(int fd, void* data, std::size_t size) {
    return TransferAll(static_cast<char*>(data), size,
                       [fd](char* b, std::size_t n) { return ::recv(fd, b, n, 0); });
}

// Records from a worker: a type byte ('P' progress note, 'R' result), a 64-bit length, the bytes.
// One send for the whole record, so that the parent wakes once for it, not three times.
bool SendRecord(int fd, char type, const std::string& bytes) {
    const std::uint64_t size = bytes.size();
    std::string record(1 + sizeof size + bytes.size(), '\0');
    record[0] = type;
    std::memcpy(record.data() + 1, &size, sizeof size);
    std::memcpy(record.data() + 1 + sizeof size, bytes.data(), bytes.size());
    return SendAll(fd, record.data(), record.size());
}

// The longest note sent through a worker's notes socket; a longer one takes the main socket.
constexpr std::size_t kLongestQuietNote = 64 * 1024;

// A note through the notes socket: the item's index, then the note. One message (SOCK_SEQPACKET
// sends all of it or none), never waiting: false when it cannot go at once.
bool SendQuietNote(int notes_fd, std::uint64_t index, const std::string& text) {
    if (text.size() > kLongestQuietNote) {
        return false;
    }
    std::string message(sizeof index, '\0');
    std::memcpy(message.data(), &index, sizeof index);
    message += text;
    return ::send(notes_fd, message.data(), message.size(), MSG_DONTWAIT | MSG_NOSIGNAL) ==
           static_cast<ssize_t>(message.size());
}

[[noreturn]] void ExitOutOfMemory() {
    ::_exit(kOutOfMemoryExit);
}

// Receives items from `fd` and runs each through `work` until the parent has no more; ends the
// process.
[[noreturn]] void ServeItems(
        int fd, int notes_fd,
        const std::function<std::string(std::size_t, const ProgressNote&)>& work,
        const CpuPlacement& placement) {
    for (bool first = true;; first = false) {
        std::uint64_t index = 0;
        if (!ReceiveAll(fd, &index, sizeof index)) {
            ::_exit(0);  // the parent has no more items
        }
        if (first) {
            // The parent placed this process before it sent the first item: from now on it may
            // run on any allowed CPU (CpuPlacement).
            placement.AllowAll();
        }
        // A note goes through the notes socket, which the parent reads only when a record comes
        // or the worker ends, so that it does not wake the parent (a cold validate sends
        // hundreds). One that cannot (too long, or the socket full) takes the main socket, and
        // so does every later note of the item, which keeps its notes in order.
        bool quiet = true;
        const ProgressNote note = [fd, notes_fd, index, &quiet](const std::string& text) {
            quiet = quiet && SendQuietNote(notes_fd, index, text);
            if (!quiet) {
                SendRecord(fd, 'P', text);
            }
        };
        std::string result;
        try {
            result = work(static_cast<std::size_t>(index), note);
        } catch (const std::bad_alloc&) {
            ::_exit(kOutOfMemoryExit);
        } catch (...) {
            ::_exit(kExceptionExit);
        }
        if (!SendRecord(fd, 'R', result)) {
            ::_exit(0);
        }
    }
}

// Runs `task` on a thread of its own with a stack of `bytes` and waits for it, passing on what
// it throws; false, with `task` not run, when no such thread could be made (the caller then runs
// it on its own stack). A task that ends the process never returns here.
template <typename Task>
bool RunOnStack(std::size_t bytes, Task& task) {
    struct Run {
        Task& task;
        std::exception_ptr thrown;
    } run{task, nullptr};
    pthread_attr_t attributes;
    if (::pthread_attr_init(&attributes) != 0) {
        return false;
    }
    pthread_t thread;
    const bool started = ::pthread_attr_setstacksize(&attributes, bytes) == 0 &&
                         ::pthread_create(
                                 &thread, &attributes,
                                 [](void* argument) -> void* {
                                     Run& r = *static_cast<Run*>(argument);
                                     try {
                                         r.task();
                                     } catch (...) {
                                         r.thrown = std::current_exception();
                                     }
                                     return nullptr;
                                 },
                                 &run) == 0;
    ::pthread_attr_destroy(&attributes);
    if (!started) {
        return false;
    }
    ::pthread_join(thread, nullptr);
    if (run.thrown) {
        std::rethrow_exception(run.thrown);
    }
    return true;
}

[[noreturn]] void WorkerMain(
        int fd, int notes_fd, const WorkerLimits& limits,
        const std::function<std::string(std::size_t, const ProgressNote&)>& work,
        const CpuPlacement& placement) {
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);  // a crashing worker is expected; no core files
    if (limits.memory_bytes > 0) {
        LimitMemory(limits.memory_bytes);
    }
    std::set_new_handler(ExitOutOfMemory);
    if (limits.keep_freed_memory) {
        // (3,500 of the 6,100 page faults of a cold `validate` of the default matrix.) The peak
        // is unchanged.
        constexpr int kKeepFreedBytes = 1 << 30;
        ::mallopt(M_TRIM_THRESHOLD, kKeepFreedBytes);
    }
    if (limits.stack_bytes > 0) {
        auto serve = [&] { ServeItems(fd, notes_fd, work, placement); };  // ends the process
        RunOnStack(limits.stack_bytes, serve);
    }
    ServeItems(fd, notes_fd, work, placement);
}

struct Worker {
    pid_t pid = -1;
    int fd = -1;
    int notes_fd = -1;  // SendQuietNote's messages
    // The items handed to it, in the order it runs them: the front one is running, the others
    // wait in its socket (WorkerLimits::items_ahead).
    std::deque<std::size_t> items;
    // Its share of the items not yet handed out, [next, end) (WorkerLimits::contiguous_shares).
    std::size_t next = 0;
    std::size_t end = 0;
    Clock::time_point started;  // when the front item started, as the parent saw it
    std::string buffer;         // bytes received and not yet parsed into records
};

std::string DescribeStatus(int status) {
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        return fmt::format("signal {} ({})", signal, ::strsignal(signal));
    }
    if (WIFEXITED(status)) {
        return fmt::format("exit status {}", WEXITSTATUS(status));
    }
    return "ended unexpectedly";
}

class Pool {
public:
    Pool(std::size_t count, const WorkerLimits& limits,
         const std::function<std::string(std::size_t, const ProgressNote&)>& work,
         const std::function<bool(std::size_t)>& should_run,
         const std::function<void(std::size_t, const WorkerItemResult&)>& on_result)
        : count_(count),
          limits_(limits),
          work_(work),
          should_run_(should_run),
          on_result_(on_result),
          results_(count) {}

    std::vector<WorkerItemResult> Run(int worker_count) {
        workers_.resize(static_cast<std::size_t>(std::max(worker_count, 1)));
        for (std::size_t w = 0; w < workers_.size(); ++w) {
            workers_[w].next = w * count_ / workers_.size();
            workers_[w].end = (w + 1) * count_ / workers_.size();
        }
        // One item each first, so that a few long items spread over the workers.
        for (Worker& worker : workers_) {
            Fill(worker, 1);
        }
        for (Worker& worker : workers_) {
            Fill(worker, Depth());
        }
        while (std::any_of(workers_.begin(), workers_.end(),
                           [](const Worker& w) { return !w.items.empty(); })) {
            Wait();
        }
        for (Worker& worker : workers_) {
            Stop(worker, false);
        }
        return std::move(results_);
    }

private:
    std::size_t Depth() const {
        return 1 + static_cast<std::size_t>(std::max(limits_.items_ahead, 0));
    }

    void Ended(std::size_t i) {
        if (on_result_) {
            on_result_(i, results_[i]);
        }
    }

    // The next item for `worker` to run: one a failed worker left unstarted, else the next one
    // in order (WorkerLimits::contiguous_shares: of its share, else the last of the largest share
    // left), marking skipped ones on the way; -1 when none is left.
    long NextItem(Worker& worker) {
        if (!unstarted_.empty()) {
            const std::size_t i = unstarted_.front();
            unstarted_.pop_front();
            return static_cast<long>(i);
        }
        for (;;) {
            std::size_t i = 0;
            if (!limits_.contiguous_shares) {
                if (next_ >= count_) {
                    return -1;
                }
                i = next_++;
            } else if (worker.next < worker.end) {
                i = worker.next++;
            } else {
                Worker& largest = *std::max_element(workers_.begin(), workers_.end(),
                                                    [](const Worker& a, const Worker& b) {
                                                        return a.end - a.next < b.end - b.next;
                                                    });
                if (largest.next >= largest.end) {
                    return -1;
                }
                i = --largest.end;
            }
            if (!should_run_ || should_run_(i)) {
                return static_cast<long>(i);
            }
            results_[i].failure = WorkerFailure::kSkipped;
            Ended(i);
        }
    }

    bool Start(Worker& worker) {
        int fds[2];
        int notes[2];
        if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
            return false;
        }
        if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, notes) != 0) {
            ::close(fds[0]);
            ::close(fds[1]);
            return false;
        }
        const pid_t parent = ::getpid();
        const pid_t pid = ::fork();
        if (pid < 0) {
            for (int fd : {fds[0], fds[1], notes[0], notes[1]}) {
                ::close(fd);
            }
            return false;
        }
        if (pid == 0) {
            // A worker dies with the process that forked it. Killed by `timeout`, a cancelled CI
            // job or a build tool, that process would otherwise leave its workers running with
            // nobody to enforce their time limit: on a shader glslang never finishes, for good.
            // (The signal comes when the forking thread ends; it waits for its workers.)
            ::prctl(PR_SET_PDEATHSIG, SIGKILL);
            if (::getppid() != parent) {
                ::_exit(1);  // it died before the line above
            }
            // Every descriptor but stdio and this worker's two sockets goes: another worker's
            // socket held open here would hide that worker's death from us, and a socket of a
            // pool on another thread (`run` plans scenes on two) would keep that pool's worker
            // from ever seeing its end, so both pools would wait forever.
            const auto low = static_cast<unsigned>(std::min(fds[1], notes[1]));
            const auto high = static_cast<unsigned>(std::max(fds[1], notes[1]));
            if (low > 3) {
                ::close_range(3, low - 1, 0);
            }
            if (high > low + 1) {
                ::close_range(low + 1, high - 1, 0);
            }
            ::close_range(high + 1, ~0U, 0);
            WorkerMain(fds[1], notes[1], limits_, work_, placement_);
        }
        placement_.StartProcessAway(pid, static_cast<int>(&worker - workers_.data()));
        ::close(fds[1]);
        ::close(notes[1]);
        worker.pid = pid;
        worker.fd = fds[0];
        worker.notes_fd = notes[0];
        worker.buffer.clear();
        return true;
    }

    // Hands `worker` items until it holds `depth` (starting it when needed); ends it when no item
    // is left for it.
    void Fill(Worker& worker, std::size_t depth) {
        while (worker.items.size() < depth) {
            const long item = NextItem(worker);
            if (item < 0) {
                break;
            }
            const auto i = static_cast<std::size_t>(item);
            if (worker.pid < 0 && !Start(worker)) {
                // No process to isolate it in: run it here rather than not at all, on the stack
                // a worker would have given it.
                auto run = [&] { results_[i].payload = work_(i, [](const std::string&) {}); };
                if (limits_.stack_bytes == 0 || !RunOnStack(limits_.stack_bytes, run)) {
                    run();
                }
                results_[i].detail = "run without isolation: no worker process could be started";
                Ended(i);
                continue;
            }
            if (worker.items.empty()) {
                worker.started = Clock::now();
            }
            worker.items.push_back(i);
            const auto index = static_cast<std::uint64_t>(i);
            if (!SendAll(worker.fd, &index, sizeof index) && worker.items.size() == 1) {
                // (Behind a running item, the worker's end shows when its socket closes.)
                Fail(worker, WorkerFailure::kCrashed, "the worker process ended before its item");
                return;
            }
        }
        if (worker.items.empty()) {
            Stop(worker, false);
        }
    }

    // Ends a worker: politely (closing its socket makes it exit) or by SIGKILL.
    int Stop(Worker& worker, bool kill) {
        int status = 0;
        if (worker.pid < 0) {
            return status;
        }
        if (kill) {
            ::kill(worker.pid, SIGKILL);
        }
        ::close(worker.fd);
        while (::waitpid(worker.pid, &status, 0) < 0 && errno == EINTR) {
        }
        // All of them now that the worker has ended, but only the running item's: an item behind
        // it that the worker had begun runs again elsewhere and sends its notes again.
        TakeQuietNotes(worker, true);
        ::close(worker.notes_fd);
        worker.pid = -1;
        worker.fd = -1;
        worker.notes_fd = -1;
        worker.items.clear();
        return status;
    }

    // The worker's running item failed; the items behind it go to the next worker that asks.
    void Fail(Worker& worker, WorkerFailure failure, std::string detail) {
        const std::size_t i = worker.items.front();
        unstarted_.insert(unstarted_.begin(), worker.items.begin() + 1, worker.items.end());
        const int status = Stop(worker, true);
        if (failure == WorkerFailure::kCrashed && WIFEXITED(status) &&
            WEXITSTATUS(status) == kOutOfMemoryExit) {
            failure = WorkerFailure::kOutOfMemory;
            detail = "an allocation failed";
        } else if (failure == WorkerFailure::kCrashed && detail.empty()) {
            detail = DescribeStatus(status);
        }
        results_[i].failure = failure;
        results_[i].detail = std::move(detail);
        Ended(i);
        Fill(worker, Depth());
    }

    // The notes waiting in the worker's notes socket, each to its item's result (with
    // `front_only`, only those of the item the worker was running).
    void TakeQuietNotes(Worker& worker, bool front_only = false) {
        std::vector<char>& message = note_buffer_;
        message.resize(sizeof(std::uint64_t) + kLongestQuietNote);
        for (;;) {
            const ssize_t got =
                    ::recv(worker.notes_fd, message.data(), message.size(), MSG_DONTWAIT);
            if (got < 0 && errno == EINTR) {
                continue;
            }
            if (got < static_cast<ssize_t>(sizeof(std::uint64_t))) {
                return;  // none left (or the worker has gone)
            }
            std::uint64_t index = 0;
            std::memcpy(&index, message.data(), sizeof index);
            const bool wanted =
                    index < results_.size() &&
                    (!front_only || (!worker.items.empty() && worker.items.front() == index));
            if (wanted) {
                results_[index].notes.emplace_back(message.data() + sizeof index,
                                                   static_cast<std::size_t>(got) - sizeof index);
            }
        }
    }

    // Parses whole records out of the worker's buffer. The notes socket is read before each
    // one: an item's notes there were sent before any record of it.
    void TakeRecords(Worker& worker) {
        constexpr std::size_t kHeader = 1 + sizeof(std::uint64_t);
        while (!worker.items.empty() && worker.buffer.size() >= kHeader) {
            std::uint64_t size = 0;
            std::memcpy(&size, worker.buffer.data() + 1, sizeof size);
            if (worker.buffer.size() < kHeader + size) {
                return;
            }
            TakeQuietNotes(worker);
            const char type = worker.buffer[0];
            std::string bytes = worker.buffer.substr(kHeader, size);
            worker.buffer.erase(0, kHeader + size);
            const std::size_t i = worker.items.front();
            if (type == 'P') {
                results_[i].notes.push_back(std::move(bytes));
            } else {
                results_[i].payload = std::move(bytes);
                worker.items.pop_front();
                worker.started = Clock::now();
                Ended(i);
                Fill(worker, Depth());
            }
        }
    }

    void Wait() {
        std::vector<pollfd> fds;
        std::vector<Worker*> polled;
        auto timeout = std::chrono::milliseconds(-1);
        const Clock::time_point now = Clock::now();
        for (Worker& worker : workers_) {
            if (worker.items.empty()) {
                continue;
            }
            fds.push_back(pollfd{worker.fd, POLLIN, 0});
            polled.push_back(&worker);
            if (limits_.seconds_per_item > 0) {
                const auto deadline =
                        worker.started +
                        std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(limits_.seconds_per_item));
                const auto left = std::max(
                        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now) +
                                std::chrono::milliseconds(1),
                        std::chrono::milliseconds(0));
                timeout = timeout.count() < 0 ? left : std::min(timeout, left);
            }
        }
        const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(timeout.count()));
        if (ready < 0 && errno != EINTR) {
            return;
        }
        for (std::size_t k = 0; k < fds.size(); ++k) {
            Worker& worker = *polled[k];
            if ((fds[k].revents & (POLLIN | POLLHUP | POLLERR)) != 0 && !worker.items.empty()) {
                char chunk[65536];
                const ssize_t got = ::recv(worker.fd, chunk, sizeof chunk, 0);
                if (got > 0) {
                    worker.buffer.append(chunk, static_cast<std::size_t>(got));
                    TakeRecords(worker);
                } else if (got == 0 || (errno != EINTR && errno != EAGAIN)) {
                    Fail(worker, WorkerFailure::kCrashed, "");
                }
            }
        }
        if (limits_.seconds_per_item > 0) {
            const Clock::time_point later = Clock::now();
            for (Worker& worker : workers_) {
                if (!worker.items.empty() &&
                    std::chrono::duration<double>(later - worker.started).count() >
                            limits_.seconds_per_item) {
                    Fail(worker, WorkerFailure::kTimedOut,
                         fmt::format("took longer than {} s", limits_.seconds_per_item));
                }
            }
        }
    }

    std::size_t count_;
    const WorkerLimits& limits_;
    const std::function<std::string(std::size_t, const ProgressNote&)>& work_;
    const std::function<bool(std::size_t)>& should_run_;
    const std::function<void(std::size_t, const WorkerItemResult&)>& on_result_;
    std::vector<WorkerItemResult> results_;
    std::vector<Worker> workers_;
    CpuPlacement placement_;             // workers start on other CPUs than the parent's
    std::deque<std::size_t> unstarted_;  // handed to a worker that failed before starting them
    std::vector<char> note_buffer_;      // TakeQuietNotes's, kept for the next call
    std::size_t next_ = 0;
};

}  // namespace

std::vector<WorkerItemResult> RunInWorkerProcesses(
        std::size_t count, int workers, const WorkerLimits& limits,
        const std::function<std::string(std::size_t, const ProgressNote&)>& work,
        const std::function<bool(std::size_t)>& should_run,
        const std::function<void(std::size_t, const WorkerItemResult&)>& on_result) {
    if (count == 0) {
        return {};
    }
    Pool pool(count, limits, work, should_run, on_result);
    return pool.Run(static_cast<int>(
            std::min<std::size_t>(count, static_cast<std::size_t>(std::max(workers, 1)))));
}

}  // namespace tidepool::base
