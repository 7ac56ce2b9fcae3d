#pragma once
// shadows.raster = auto: which shadow-map rasterizer a device runs faster.
// On datacenter NVIDIA GPUs (H100, H200, A100, GH200, B200, ...) a table decides at once: compute.
// Few of their SMs run the graphics pipeline (measured 7-100x slower raster there, docs/performance.md),
// so measuring would only cost frames that alternate paths (uneven frame times from the first frame on).
// Elsewhere the first frames that draw shadow tiles alternate: kWarmup + kSamples frames with the
// hardware path, as many with the compute path; the shadow passes' GPU time (timestamps) decides, and
// later frames use the faster. Frames whose tiles are all cached measure nothing (the renderer does not
// report them). Without timestamps the hardware path. No GPU here: tests/unit/raster_choice_test.cpp.
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
    // Whether every frame draws with the compute path, whatever any frame measures: the setting says
    // `compute`, or `auto` on a device the table decides for.
    bool computeForGood(ShadowRaster setting) const {
        return setting == ShadowRaster::Compute || (setting == ShadowRaster::Auto && byTable_);
    }
    // For the stats: "measuring", or the choice with its reason (valid until the next measured()).
    const char* describe() const;

private:
    enum class Phase { MeasureHw, MeasureCompute, Decided };
    Phase phase_;
    bool compute_ = false;
    bool byTable_ = false;  // decided by the device table
    std::string reason_;
    Names names_;
    std::vector<double> hw_, compute__;
};

}  // namespace penumbra
