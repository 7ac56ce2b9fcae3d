// Out-of-memory and device loss, through gpu::DeviceFaultInjection on lavapipe with
// validation on: each failure is one penumbra::Error naming where it happened, leaves no GPU object
// behind, and never hangs; after an allocation failure the renderer renders again.
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "penumbra/scene_builder.h"
#include "render/virtual_page_storage.h"
#include "render_test_support.h"

using namespace penumbra;

namespace {

Scene faultScene() { return test::sunAndSpotBoxScene(); }

RenderRequest smallRequest() { return test::colourRequest(96, 64); }

// An 8192 atlas (256 MiB of depth) needs an allocation of its own while the first frame is made.
Settings bigAtlasSettings() {
    Settings settings;
    settings.shadows.directional.atlasSize = 8192;
    return settings;
}

Device faultyDevice(const gpu::DeviceFaultInjection& faults) {
    DeviceOptions options = test::testDeviceOptions();
    options.pipelineCache = "off";
    return DeviceAccess::makeDevice({options, faults});
}

struct Outcome {
    std::string error;  // "" when the device, the renderer and two frames were made
    uint32_t validationMessages = 0;  // while rendering, and (from stderr) when the device was destroyed
    bool leftObjects = false;  // GPU objects alive after everything but the device was destroyed
};

Outcome renderOn(const gpu::DeviceFaultInjection& faults, const Settings& settings);

// Makes a device with `faults`, a renderer of faultScene and renders two frames. vkDestroyDevice
// reports objects that were never destroyed: the validation layer's message is caught on stderr.
Outcome renderWith(const gpu::DeviceFaultInjection& faults, const Settings& settings = {}) {
    ::testing::internal::CaptureStderr();
    Outcome outcome = renderOn(faults, settings);
    const std::string err = ::testing::internal::GetCapturedStderr();
    if (err.find("Vulkan validation") != std::string::npos) {
        ++outcome.validationMessages;
        std::fprintf(stderr, "%s", err.c_str());
    }
    return outcome;
}

Outcome renderOn(const gpu::DeviceFaultInjection& faults, const Settings& settings) {
    Outcome outcome;
    std::unique_ptr<Device> device;
    try {
        device = std::make_unique<Device>(faultyDevice(faults));
        {
            Renderer renderer(*device, faultScene());
            renderer.render(smallRequest(), settings);
            renderer.render(smallRequest(), settings);
        }
    } catch (const Error& e) {
        outcome.error = e.what();
    }
    if (device) {
        try {
            device->waitIdle();
        } catch (const Error&) {
        }
        const DeviceObjectCounts live = device->liveObjects();
        // Only the device's own objects stay until it goes: one upload ring per frame in flight.
        outcome.leftObjects = live.textures + live.samplers + live.pipelines + live.textureTables + live.pendingDestroys > 0 ||
                              live.buffers > 2;
        outcome.validationMessages = device->validationMessageCount();
    }
    return outcome;
}

bool oneLine(const std::string& text) { return !text.empty() && text.find('\n') == std::string::npos; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(DeviceFaults, EveryFailedAllocationIsAnOutOfMemoryErrorThatLeavesNothingBehind) {
    uint32_t failures = 0;
    for (uint64_t n = 1; n <= 64; ++n) {
        SCOPED_TRACE("allocation " + std::to_string(n));
        gpu::DeviceFaultInjection faults;
        faults.failAllocation = n;
        const Outcome outcome = renderWith(faults, bigAtlasSettings());
        EXPECT_EQ(outcome.validationMessages, 0u);
        EXPECT_FALSE(outcome.leftObjects);
        if (outcome.error.empty()) break;  // n is past the last allocation the render makes
        ++failures;
        EXPECT_TRUE(oneLine(outcome.error)) << outcome.error;
        EXPECT_TRUE(contains(outcome.error, "out of GPU memory: vkAllocateMemory")) << outcome.error;
    }
    EXPECT_GE(failures, 3u);  // the device, the scene upload and the frame each allocate
}

TEST(DeviceFaults, AllocationFailingInAFrameNamesTheFrameAndWhatItMade) {
    bool named = false;
    for (uint64_t n = 1; n <= 64 && !named; ++n) {
        gpu::DeviceFaultInjection faults;
        faults.failAllocation = n;
        const Outcome outcome = renderWith(faults, bigAtlasSettings());
        if (outcome.error.empty()) break;
        named = contains(outcome.error, "frame 0, render targets and shadow atlases: out of GPU memory") &&
                contains(outcome.error, "directional atlas");
    }
    EXPECT_TRUE(named);
}

TEST(DeviceFaults, SceneUploadFailureSaysTheSceneWasGoingOnTheGpu) {
    bool named = false;
    for (uint64_t n = 1; n <= 64 && !named; ++n) {
        gpu::DeviceFaultInjection faults;
        faults.failAllocation = n;
        const Outcome outcome = renderWith(faults);
        if (outcome.error.empty()) break;
        named = contains(outcome.error, "putting the scene on the GPU: out of GPU memory");
    }
    EXPECT_TRUE(named);
}

TEST(DeviceFaults, RendererRendersAgainAfterAFrameRanOutOfMemory) {
    // Find the allocation that the first frame's atlas makes, then fail exactly that one.
    for (uint64_t n = 1; n <= 64; ++n) {
        gpu::DeviceFaultInjection faults;
        faults.failAllocation = n;
        std::unique_ptr<Device> made;
        std::unique_ptr<Renderer> renderer;
        try {
            made = std::make_unique<Device>(faultyDevice(faults));
            renderer = std::make_unique<Renderer>(*made, faultScene());
        } catch (const Error&) {
            continue;  // allocation n is made before the first frame
        }
        Device& device = *made;
        try {
            renderer->render(smallRequest(), bigAtlasSettings());
            continue;  // this n failed nothing in the frame (or was spent before it)
        } catch (const Error& e) {
            ASSERT_TRUE(contains(e.what(), "frame 0")) << e.what();
        }
        const RenderResult again = renderer->render(smallRequest(), bigAtlasSettings());
        EXPECT_EQ(again.image.width, 96u);
        Device clean(test::testDeviceOptions());
        Renderer reference(clean, faultScene());
        EXPECT_EQ(again.image.pixels, reference.render(smallRequest(), bigAtlasSettings()).image.pixels);
        EXPECT_EQ(device.validationMessageCount(), 0u);
        return;
    }
    FAIL() << "no allocation failed inside a frame";
}

TEST(DeviceFaults, FrameThatFailsWhileRecordingIsDroppedAndTheNextOneRenders) {
    // The screen-space resolve makes its textures while the first frame is recorded.
    Settings screenSpace;
    screenSpace.shadows.screenSpace = true;
    for (uint64_t n = 1; n <= 64; ++n) {
        gpu::DeviceFaultInjection faults;
        faults.failAllocation = n;
        std::unique_ptr<Device> device;
        std::unique_ptr<Renderer> renderer;
        try {
            device = std::make_unique<Device>(faultyDevice(faults));
            renderer = std::make_unique<Renderer>(*device, faultScene());
            renderer->render(smallRequest(), screenSpace);
            continue;
        } catch (const Error& e) {
            if (!contains(e.what(), "frame 0, screen-space shadows")) continue;
        }
        const RenderResult again = renderer->render(smallRequest(), screenSpace);
        EXPECT_EQ(again.stats.frameIndex, 1u);
        Device clean(test::testDeviceOptions());
        Renderer reference(clean, faultScene());
        EXPECT_EQ(again.image.pixels, reference.render(smallRequest(), screenSpace).image.pixels);
        EXPECT_EQ(device->validationMessageCount(), 0u);
        return;
    }
    FAIL() << "no allocation failed while a frame was recorded";
}

TEST(DeviceFaults, DeviceLostAtSubmitNamesTheFrameAndItsPasses) {
    bool named = false;
    for (uint64_t n = 1; n <= 16 && !named; ++n) {
        SCOPED_TRACE("submission " + std::to_string(n));
        gpu::DeviceFaultInjection faults;
        faults.loseDeviceAtSubmit = n;
        const Outcome outcome = renderWith(faults);
        EXPECT_EQ(outcome.validationMessages, 0u);
        EXPECT_FALSE(outcome.leftObjects);
        if (outcome.error.empty()) break;
        EXPECT_TRUE(oneLine(outcome.error));
        EXPECT_TRUE(contains(outcome.error, "GPU device lost (VK_ERROR_DEVICE_LOST)")) << outcome.error;
        named = contains(outcome.error, "submitting frame ") &&
                contains(outcome.error, "(passes shadows.culling, shadows.directional, shadows.other, lightClusters, main)");
    }
    EXPECT_TRUE(named);
}

TEST(DeviceFaults, DeviceLostWhileTheGpuRanAFrameNamesItsPasses) {
    bool named = false;
    for (uint64_t n = 1; n <= 16 && !named; ++n) {
        gpu::DeviceFaultInjection faults;
        faults.loseDeviceAtWait = n;
        const Outcome outcome = renderWith(faults);
        EXPECT_EQ(outcome.validationMessages, 0u);
        if (outcome.error.empty()) break;
        named = contains(outcome.error, "while the GPU ran frame ") && contains(outcome.error, "main)");
    }
    EXPECT_TRUE(named);
}

TEST(DeviceFaults, EveryFrameAfterADeviceLossFailsAtOnce) {
    gpu::DeviceFaultInjection faults;
    faults.loseDeviceAtWait = 3;  // a frame's wait, after the scene upload's
    Device device(faultyDevice(faults));
    Renderer renderer(device, faultScene());
    EXPECT_THROW(
        for (int i = 0; i < 8; ++i) renderer.render(smallRequest(), {}), Error);
    EXPECT_TRUE(device.lost());
    const CameraView view = resolveCameraView(renderer.scene(), 96, 64);
    try {
        renderer.submitFrame(smallRequest(), {}, view);
        FAIL() << "a frame was submitted on a lost device";
    } catch (const Error& e) {
        EXPECT_TRUE(contains(e.what(), "GPU device lost earlier")) << e.what();
    }
    renderer.waitIdle();  // returns: nothing of a lost device is waited for
    EXPECT_EQ(device.validationMessageCount(), 0u);
}

TEST(DeviceFaults, ALostDeviceWithFramesInFlightIsDestroyedCleanly) {
    gpu::DeviceFaultInjection faults;
    // The scene upload, frame 0's tight-fit depth reduction (nothing earlier to plan from) and frame 0;
    // frame 1 plans from frame 0's reduction: submission 4 is frame 1's.
    faults.loseDeviceAtSubmit = 4;
    Device device(faultyDevice(faults));
    {
        Renderer renderer(device, faultScene());
        const CameraView view = resolveCameraView(renderer.scene(), 96, 64);
        renderer.submitFrame(smallRequest(), {}, view);  // in flight, not waited for
        try {
            renderer.submitFrame(smallRequest(), {}, view);
            ADD_FAILURE() << "frame 1 was not lost";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("submitting frame 1"), std::string::npos) << e.what();
        }
    }  // the renderer goes while frame 0 may still run: the loss waited for the queue once
    EXPECT_TRUE(device.lost());
    EXPECT_EQ(device.validationMessageCount(), 0u);
}

// The compute shaders need basic, ballot and arithmetic subgroup operations (optional in Vulkan 1.3):
// a device without them is refused when it is made, in one line that names what it lacks.
TEST(DeviceFaults, ADeviceWithoutSubgroupArithmeticIsRefusedInOneLine) {
    gpu::DeviceFaultInjection faults;
    faults.noSubgroupArithmetic = true;
    const Outcome outcome = renderWith(faults, Settings{});
    EXPECT_TRUE(oneLine(outcome.error)) << outcome.error;
    EXPECT_TRUE(contains(outcome.error, "no Vulkan device: ")) << outcome.error;
    EXPECT_TRUE(contains(outcome.error, "lacks basic, ballot and arithmetic subgroup operations")) << outcome.error;
    EXPECT_FALSE(outcome.leftObjects);
}

// Without shaderStorageImageExtendedFormats the virtual shadow maps' pools are R32_SFLOAT images of the
// same 16-bit codes (render/virtual_page_storage.h): the frame is the very image an R16_UNORM pool gives.
TEST(DeviceFaults, WithoutR16StorageImagesVirtualPoolsHoldFloatsAndRenderTheSameImage) {
    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.spot.mode = SpotShadowMode::Virtual;
    Image images[2];
    for (int wide = 0; wide < 2; ++wide) {
        gpu::DeviceFaultInjection faults;
        faults.noStorageImageExtendedFormats = wide == 1;
        Device device = faultyDevice(faults);
        EXPECT_EQ(gpu::backend(device).hasStorageImageExtendedFormats(), wide == 0);
        EXPECT_EQ(virtualPoolFormat(gpu::backend(device)), wide ? gpu::Format::R32Float : gpu::Format::R16Unorm);
        Renderer renderer(device, faultScene());
        images[wide] = renderer.render(smallRequest(), settings).image;
        EXPECT_EQ(device.validationMessageCount(), 0u);
    }
    ASSERT_FALSE(images[0].empty());
    EXPECT_EQ(images[1].pixels, images[0].pixels);
}
