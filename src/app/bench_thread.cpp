#include "app/bench_thread.h"

#include <pthread.h>

#include <cstring>
#include <string>

#include "penumbra/error.h"

namespace penumbra {

namespace {

cpu_set_t threadCpus() {
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    if (pthread_getaffinity_np(pthread_self(), sizeof(cpus), &cpus) != 0) CPU_ZERO(&cpus);
    return cpus;
}

}  // namespace

void checkPinCpu(int cpu) {
    if (cpu < 0) return;
    const cpu_set_t allowed = threadCpus();
    if (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))
        throw Error("--pin-cpu " + std::to_string(cpu) + ": this process may not run on that CPU (it may use " +
                    std::to_string(CPU_COUNT(&allowed)) + " CPUs; see `nproc`)");
}

FrameThreadCpus::FrameThreadCpus(int cpu) : pinnedCpu_(cpu) {
    CPU_ZERO(&seen_);
    if (cpu >= 0) {
        checkPinCpu(cpu);
        before_ = threadCpus();
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpu, &one);
        if (const int error = pthread_setaffinity_np(pthread_self(), sizeof(one), &one); error != 0)
            throw Error("--pin-cpu " + std::to_string(cpu) + ": " + std::strerror(error));
    }
    const cpu_set_t allowed = threadCpus();
    allowedCpus_ = CPU_COUNT(&allowed);
}

void FrameThreadCpus::observe() {
    const int cpu = sched_getcpu();
    if (cpu < 0 || cpu >= CPU_SETSIZE) return;
    CPU_SET(cpu, &seen_);
    if (lastCpu_ >= 0 && cpu != lastCpu_) ++migrations_;
    lastCpu_ = cpu;
}

void FrameThreadCpus::unpin() {
    if (pinnedCpu_ >= 0 && CPU_COUNT(&before_) > 0) pthread_setaffinity_np(pthread_self(), sizeof(before_), &before_);
}

std::string FrameThreadCpus::summary() const {
    const std::string where = pinnedCpu_ >= 0 ? "CPU " + std::to_string(pinnedCpu_) + " (pinned)"
                                              : "any of " + std::to_string(allowedCpus_) + " CPUs";
    const int seen = cpusSeen();
    return "frame thread: " + where + ", " + std::to_string(seen) + (seen == 1 ? " CPU" : " CPUs") + " seen, " +
           std::to_string(migrations_) + (migrations_ == 1 ? " migration" : " migrations") + " between frames";
}

nlohmann::json FrameThreadCpus::json() const {
    return {{"pinnedCpu", pinnedCpu_}, {"allowedCpus", allowedCpus_}, {"cpusSeen", cpusSeen()},
            {"migrations", migrations_}};
}

}  // namespace penumbra
