#pragma once
// Wall-clock milliseconds since construction (or restart), for the CPU phase times that `penumbra
// bench` reports; and the calling thread's CPU time (CLOCK_THREAD_CPUTIME_ID), which leaves out the
// time the thread was not running (preempted by the host), for telling a slow frame of the engine's
// from a slow frame of the machine's.
#include <chrono>
#include <ctime>

namespace penumbra {

class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    void restart() { start_ = std::chrono::steady_clock::now(); }
    double milliseconds() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::chrono::steady_clock::time_point start_;
};

class ThreadStopwatch {
public:
    ThreadStopwatch() : start_(now()) {}
    void restart() { start_ = now(); }
    double milliseconds() const { return now() - start_; }

private:
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
    }
    double start_;
};

}  // namespace penumbra
