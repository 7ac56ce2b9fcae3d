#include "render/virtual_settling.h"

namespace penumbra {

namespace {

bool sameView(const CameraView& a, const CameraView& b) {
    return a.viewFromWorld == b.viewFromWorld && a.clipFromWorld == b.clipFromWorld && a.width == b.width &&
           a.height == b.height;
}

}  // namespace

bool pagesAtRest(const VirtualPageCounts& pages) {
    return pages.requested == pages.cached && pages.allocated == 0 && pages.drawn == 0 && pages.evicted == 0 &&
           pages.overflowed == 0 && pages.deferred == 0;
}

void VirtualSettling::beginFrame(uint64_t frameIndex, const VirtualFrameInputs& inputs) {
    const bool same = haveInputs_ && !inputs.directionalMoving && inputs.sceneVersion == sceneVersion_ &&
                      inputs.lightVersion == lightVersion_ &&
                      inputs.facePressureSteps == facePressureSteps_ &&
                      sameView(inputs.view, view_) && inputs.settings == settings_;
    if (same) return;
    settings_ = inputs.settings;  // assignment reuses the key list's storage
    view_ = inputs.view;
    sceneVersion_ = inputs.sceneVersion;
    lightVersion_ = inputs.lightVersion;
    facePressureSteps_ = inputs.facePressureSteps;
    haveInputs_ = true;
    changedAt_ = frameIndex;
    unsettle();
}

void VirtualSettling::directionalFinished(uint64_t frameIndex, const FrameStats& stats) {
    if (frameIndex < changedAt_ || stats.virtualPages.maps == 0 || !pagesAtRest(stats.virtualPages)) return;
    directional_ = true;
    directionalPages_.pages = stats.virtualPages;
    directionalPages_.levels = stats.virtualMaps;
}

void VirtualSettling::facesFinished(uint64_t frameIndex, const FrameStats& stats) {
    if (frameIndex < changedAt_ || stats.virtualFacePages.maps == 0 || !pagesAtRest(stats.virtualFacePages)) return;
    faces_ = true;
    facePages_.pages = stats.virtualFacePages;
    facePages_.levels[0] = stats.virtualFaceMips;
}

}  // namespace penumbra
