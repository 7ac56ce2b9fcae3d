#pragma once
// `penumbra bench --pin-cpu N` and the frame thread's CPUs: where the thread that records and submits
// the timed frames ran. A thread the scheduler moves between cores of different clocks or caches shows
// steps in its CPU phases that are not the engine's; pinned, it stays on one.
#include <cstdint>
#include <string>

#include <sched.h>

#include <nlohmann/json.hpp>

namespace penumbra {

// Throws Error (bad input) unless this process may run on logical CPU `cpu`; -1 (unpinned) passes.
void checkPinCpu(int cpu);

class FrameThreadCpus {
public:
    // Pins the calling thread to `cpu` (-1: leaves it as it is) and records the CPUs it may use. Threads
    // started before keep their own CPUs (a new thread inherits its creator's): call it after warm-up.
    explicit FrameThreadCpus(int cpu);

    // Once per timed frame, on the frame thread: notes the CPU it runs on. Allocates nothing.
    void observe();
    // After the timed frames, on the frame thread: the CPUs it had before the constructor pinned it.
    void unpin();

    int pinnedCpu() const { return pinnedCpu_; }
    int allowedCpus() const { return allowedCpus_; }  // the CPUs the frame thread may run on
    int cpusSeen() const { return CPU_COUNT(&seen_); }
    uint64_t migrations() const { return migrations_; }  // frames on another CPU than the frame before

    // "frame thread: CPU 4 (pinned), 1 CPU seen, 0 migrations" / "frame thread: any of 16 CPUs, ...".
    std::string summary() const;
    nlohmann::json json() const;

private:
    int pinnedCpu_ = -1;
    int allowedCpus_ = 0;
    int lastCpu_ = -1;
    uint64_t migrations_ = 0;
    cpu_set_t seen_{};
    cpu_set_t before_{};  // the thread's CPUs before pinning (pinnedCpu_ >= 0)
};

}  // namespace penumbra
