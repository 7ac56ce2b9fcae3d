#pragma once
// Wall-clock milliseconds since construction (or restart), for the CPU phase times that `penumbra
// bench` reports.
#include <chrono>

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

}  // namespace penumbra
