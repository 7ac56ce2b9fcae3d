#include "render/raster_choice.h"

#include <algorithm>
#include <sstream>

namespace penumbra {

namespace {

bool datacenterNvidia(const std::string& name) {
    for (const char* model : {"H100", "H200", "H800", "A100", "A800", "GH200", "B200", "B100"})
        if (name.find(model) != std::string::npos) return true;
    return false;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace

RasterChoice::RasterChoice(bool timestamps, const std::string& deviceName, Names names)
    : phase_(Phase::MeasureHw), names_(names) {
    if (datacenterNvidia(deviceName)) {
        phase_ = Phase::Decided;
        compute_ = byTable_ = true;
        reason_ = std::string(names_.compute) + " (by the device table: a datacenter GPU, graphics on few SMs)";
    } else if (!timestamps) {
        phase_ = Phase::Decided;
        reason_ = std::string(names_.hw) + " (no timestamps to measure with)";
    }
}

bool RasterChoice::useCompute(ShadowRaster setting) const {
    if (setting == ShadowRaster::Hw) return false;
    if (setting == ShadowRaster::Compute) return true;
    return phase_ == Phase::Decided ? compute_ : phase_ == Phase::MeasureCompute;
}

void RasterChoice::measured(bool compute, double shadowMilliseconds) {
    if (phase_ == Phase::Decided) return;
    std::vector<double>& samples = compute ? compute__ : hw_;
    if ((compute ? Phase::MeasureCompute : Phase::MeasureHw) != phase_) return;  // a frame of the other phase
    samples.push_back(shadowMilliseconds);
    if (samples.size() < size_t(kWarmup + kSamples)) return;
    if (phase_ == Phase::MeasureHw) {
        phase_ = Phase::MeasureCompute;
        return;
    }
    const double hw = median({hw_.begin() + kWarmup, hw_.end()});
    const double computed = median({compute__.begin() + kWarmup, compute__.end()});
    compute_ = computed < hw;
    std::ostringstream text;
    text << (compute_ ? names_.compute : names_.hw) << " (measured " << names_.timed << ": " << names_.hw << " " << hw
         << " ms, " << names_.compute << " " << computed << " ms)";
    reason_ = text.str();
    phase_ = Phase::Decided;
}

const char* RasterChoice::describe() const { return phase_ == Phase::Decided ? reason_.c_str() : "measuring"; }

}  // namespace penumbra
