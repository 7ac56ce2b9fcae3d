#pragma once
// shadows.raster = auto: which shadow-map rasterizer a device runs faster, by measurement.
// The first frames that draw shadow tiles alternate: kWarmup + kSamples frames with the hardware path,
// as many with the compute path; the shadow passes' GPU time (timestamps) decides, and later frames use
// the faster. Frames whose tiles are all cached measure nothing (the renderer does not report them).
// Without timestamps a table decides: compute on
// datacenter NVIDIA GPUs (H100, H200, A100, GH200, B200: few SMs run graphics, measured 7-100x
// slower raster there, docs/performance.md), the hardware path elsewhere. No GPU here: unit-tested.
// render.mainView = auto decides between the forward and the visibility-buffer main view the same way.
#include <string>
#include <vector>

#include "penumbra/shadow_settings.h"

namespace penumbra {

// The names of the two paths and of what is timed, for describe(): render.mainView = auto uses
// the same rule with {"forward", "visibility", "main view"}.
struct RasterChoiceNames {
    const char* hw = "hw";
    const char* compute = "compute";
    const char* timed = "shadow passes";
};

class RasterChoice {
public:
    static constexpr int kWarmup = 1, kSamples = 3;

    using Names = RasterChoiceNames;
    RasterChoice(bool timestamps, const std::string& deviceName, Names names = {});

    // Whether the next frame draws its shadow maps with the compute path.
    bool useCompute(ShadowRaster setting) const;
    // A finished auto frame: which path drew it and its shadow passes' GPU milliseconds.
    void measured(bool compute, double shadowMilliseconds);
    bool decided() const { return phase_ == Phase::Decided; }
    // For the stats: "measuring", or the choice with its reason (valid until the next measured()).
    const char* describe() const;

private:
    enum class Phase { MeasureHw, MeasureCompute, Decided };
    Phase phase_;
    bool compute_ = false;
    std::string reason_;
    Names names_;
    std::vector<double> hw_, compute__;
};

}  // namespace penumbra
