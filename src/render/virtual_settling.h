#pragma once
// Skipping the virtual shadow maps' page update while nothing changes. A frame's marking, page table
// and page drawing depend only on its inputs: the camera, the settings, the casters and the lights. Once
// a finished frame reports that every page it requested was already resident and that it allocated,
// drew, evicted and lost nothing, every later frame with the same inputs would do the same: those frames
// skip the directional maps' (or the faces') update entirely and sample the page tables as they are,
// so a still camera costs no page pass (Unreal Engine's "Virtual Shadow Maps" documentation: cached
// pages cost nothing while nothing invalidates them). Any change of an input, an invalidation or a
// change of the faces' pool pressure ends it; the next frame updates again. Nothing settles while a
// directional light counts as turning: its bias changes a few frames after it stops (VirtualShadows).
#include <array>
#include <cstdint>

#include "penumbra/camera.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

namespace penumbra {

// What a frame's page update depends on besides the GPU state it leaves behind.
struct VirtualFrameInputs {
    const Settings& settings;
    const CameraView& view;
    uint64_t sceneVersion = 0;  // the casters: transforms, cast flags, materials
    uint64_t lightVersion = 0;  // the lights
    uint32_t facePressureSteps = 0;  // the faces' pool pressure (VirtualFaceShadows::poolPressureSteps)
    bool directionalMoving = false;  // a directional light still counts as turning (VirtualShadows::moving)
};

// One kind of virtual map's page counts and per-level counts, as a settled frame found them.
struct SettledPages {
    VirtualPageCounts pages;
    std::array<FrameStats::VirtualMapLevels, 4> levels{};  // per directional map, or [0] the faces' mips
};

class VirtualSettling {
public:
    // At a frame's submission (frame index `frameIndex`): compares its inputs with the previous frame's;
    // a difference unsettles both kinds. Allocates nothing while the settings keep their size.
    void beginFrame(uint64_t frameIndex, const VirtualFrameInputs& inputs);
    bool directionalSettled() const { return directional_; }
    bool facesSettled() const { return faces_; }
    // A finished frame that updated its pages (not skipped): counts that show nothing to do settle its kind
    // when its inputs are the current ones.
    void directionalFinished(uint64_t frameIndex, const FrameStats& stats);
    void facesFinished(uint64_t frameIndex, const FrameStats& stats);
    // An invalidation (pages to draw again, a coarser pool pressure): the next frame updates again.
    void unsettle() { directional_ = faces_ = false; }
    const SettledPages& directionalPages() const { return directionalPages_; }
    const SettledPages& facePages() const { return facePages_; }

private:
    Settings settings_;
    CameraView view_;
    uint64_t sceneVersion_ = 0, lightVersion_ = 0;
    uint32_t facePressureSteps_ = 0;
    bool haveInputs_ = false;
    uint64_t changedAt_ = 0;  // the first frame with the current inputs
    bool directional_ = false, faces_ = false;
    SettledPages directionalPages_, facePages_;
};

// Whether a finished frame's page counts leave nothing for a frame of the same inputs to do.
bool pagesAtRest(const VirtualPageCounts& pages);

}  // namespace penumbra
