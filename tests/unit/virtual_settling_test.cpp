// render/virtual_settling.h: when a frame may skip the virtual maps' page update. Pure CPU.
#include <gtest/gtest.h>

#include "render/virtual_settling.h"

namespace penumbra {
namespace {

FrameStats atRest(uint32_t requested) {
    FrameStats stats;
    stats.virtualPages.maps = 1;
    stats.virtualPages.requested = stats.virtualPages.cached = stats.virtualPages.resident = requested;
    stats.virtualFacePages = stats.virtualPages;
    return stats;
}

struct Frames {
    Settings settings;
    CameraView view;
    uint64_t sceneVersion = 0, lightVersion = 0;
    uint32_t pressure = 0;
    VirtualSettling settling;
    void begin(uint64_t frame) { settling.beginFrame(frame, {settings, view, sceneVersion, lightVersion, pressure}); }
};

TEST(VirtualSettling, AFrameThatFoundEveryPageResidentSettlesTheFramesOfTheSameInputs) {
    Frames f;
    for (uint64_t frame = 1; frame <= 3; ++frame) f.begin(frame);
    EXPECT_FALSE(f.settling.directionalSettled());
    f.settling.directionalFinished(2, atRest(40));
    EXPECT_TRUE(f.settling.directionalSettled());
    EXPECT_FALSE(f.settling.facesSettled()) << "each kind settles on its own counts";
    EXPECT_EQ(f.settling.directionalPages().pages.requested, 40u);
    f.begin(4);
    EXPECT_TRUE(f.settling.directionalSettled()) << "same inputs: still settled";
}

TEST(VirtualSettling, AFrameThatDrewAllocatedEvictedOrOverflowedSettlesNothing) {
    for (int field = 0; field < 5; ++field) {
        Frames f;
        f.begin(1);
        FrameStats stats = atRest(40);
        VirtualPageCounts& pages = stats.virtualPages;
        if (field == 0) pages.drawn = 1;
        if (field == 1) pages.allocated = 1;
        if (field == 2) pages.evicted = 1;
        if (field == 3) pages.overflowed = 1;
        if (field == 4) pages.cached = 39;
        f.settling.directionalFinished(1, stats);
        EXPECT_FALSE(f.settling.directionalSettled()) << field;
        EXPECT_FALSE(pagesAtRest(pages)) << field;
    }
}

TEST(VirtualSettling, AFrameRecordedBeforeTheInputsChangedSettlesNothing) {
    Frames f;
    f.begin(1);
    f.view.viewFromWorld[3].x += 0.01f;  // the camera moved for frame 2
    f.view.clipFromWorld[3].x += 0.01f;
    f.begin(2);
    f.settling.directionalFinished(1, atRest(40));  // frame 1 saw the old camera
    EXPECT_FALSE(f.settling.directionalSettled());
    f.settling.directionalFinished(2, atRest(40));
    EXPECT_TRUE(f.settling.directionalSettled());
}

TEST(VirtualSettling, EveryInputOrAnInvalidationUnsettles) {
    for (int input = 0; input < 6; ++input) {
        Frames f;
        f.begin(1);
        f.settling.directionalFinished(1, atRest(40));
        f.settling.facesFinished(1, atRest(40));
        ASSERT_TRUE(f.settling.directionalSettled() && f.settling.facesSettled());
        if (input == 0) f.view.width += 1;
        if (input == 1) f.settings.shadows.virtualMaps.faceLodBias += 1.0f;
        if (input == 2) ++f.sceneVersion;
        if (input == 3) ++f.lightVersion;
        if (input == 4) ++f.pressure;
        if (input == 5) f.settling.unsettle();
        f.begin(2);
        EXPECT_FALSE(f.settling.directionalSettled()) << input;
        EXPECT_FALSE(f.settling.facesSettled()) << input;
    }
}

}  // namespace
}  // namespace penumbra
