#include "tidepool/base/CpuPlacement.h"

#include <vector>

namespace tidepool::base {

CpuPlacement::CpuPlacement() {
    CPU_ZERO(&allowed_);
    known_ = sched_getaffinity(0, sizeof allowed_, &allowed_) == 0;
}

bool CpuPlacement::AwayCpu(int n, cpu_set_t* one) const {
    if (!known_ || n < 0) {
        return false;
    }
    std::vector<std::size_t> cpus;
    for (std::size_t cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
        if (CPU_ISSET(cpu, &allowed_)) {
            cpus.push_back(cpu);
        }
    }
    const int current = sched_getcpu();
    std::size_t at = 0;
    while (at < cpus.size() && static_cast<int>(cpus[at]) != current) {
        ++at;
    }
    if (cpus.size() < 2 || at == cpus.size()) {
        return false;
    }
    CPU_ZERO(one);
    CPU_SET(cpus[(at + 1 + static_cast<std::size_t>(n)) % cpus.size()], one);
    return true;
}

void CpuPlacement::StartProcessAway(pid_t pid, int n) const {
    cpu_set_t one;
    if (AwayCpu(n, &one)) {
        static_cast<void>(sched_setaffinity(pid, sizeof one, &one));
    }
}

void CpuPlacement::StartThreadAway(pthread_t thread, int n) const {
    cpu_set_t one;
    if (AwayCpu(n, &one)) {
        static_cast<void>(pthread_setaffinity_np(thread, sizeof one, &one));
    }
}

void CpuPlacement::AllowAll() const {
    if (known_) {
        static_cast<void>(sched_setaffinity(0, sizeof allowed_, &allowed_));
    }
}

}  // namespace tidepool::base
