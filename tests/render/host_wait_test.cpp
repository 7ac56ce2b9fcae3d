// DeviceOptions::spinWait: the device waits for the GPU by polling its fences instead of sleeping in the
// driver (a waiting core that never idles: steadier CPU phases, docs/performance.md "Waiting for the
// GPU"). Only the wait differs: the frames are the same. Lavapipe, validation on.
#include <gtest/gtest.h>

#include "gpu/device.h"
#include "gpu/device_access.h"
#include "penumbra/renderer.h"
#include "render_test_support.h"

using namespace penumbra;

namespace {

class HostWaitTest : public test::RenderTest {};

Device spinningDevice() {
    DeviceOptions options = test::testDeviceOptions();
    options.spinWait = true;
    return Device(options);
}

// Five real-time frames (every slot of the per-frame rings waited for at least once), then a one-shot
// render: its image.
Image realTimeFramesThenOneShot(Device& device) {
    Renderer renderer(device, test::sunAndSpotBoxScene());
    const RenderRequest request = test::colourRequest(96, 64);
    const CameraView view = resolveCameraView(renderer.scene(), 96, 64);
    for (int i = 0; i < 5; ++i) renderer.submitFrame(request, {}, view);
    renderer.waitIdle();
    return renderer.render(request, {}).image;
}

}  // namespace

TEST_F(HostWaitTest, ASpinningDeviceDrawsTheSameFramesAsASleepingOne) {
    Device spinning = spinningDevice();
    const Image slept = realTimeFramesThenOneShot(device());
    const Image spun = realTimeFramesThenOneShot(spinning);
    ASSERT_EQ(slept.pixels.size(), spun.pixels.size());
    EXPECT_TRUE(slept.pixels == spun.pixels);
    EXPECT_EQ(spinning.validationMessageCount(), 0u);
}

TEST_F(HostWaitTest, ASpinningDevicePollsItsFencesAndASleepingOneNever) {
    Device spinning = spinningDevice();
    realTimeFramesThenOneShot(spinning);
    EXPECT_GE(DeviceAccess::backend(spinning).spinWaitPolls(), 6u) << "at least one poll per frame waited for";
    realTimeFramesThenOneShot(device());
    EXPECT_EQ(DeviceAccess::backend(device()).spinWaitPolls(), 0u);
}
