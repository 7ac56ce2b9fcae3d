// What lavapipe forgives and a discrete GPU does not, made to fail on lavapipe:
// - a buffer range bound at an offset that is a multiple of lavapipe's alignment (16 bytes) but not of a
//   GPU's (NVIDIA's uniform buffers: 64) reads other data there; the GPU layer holds every bound offset
//   to the largest alignment Vulkan allows (256), on every device;
// - a discrete GPU hands out memory holding whatever was there before, lavapipe fresh zero pages; a
//   device whose memory starts as garbage (DeviceFaultInjection::garbageByte) must draw the same images.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gpu/device.h"
#include "gpu/device_access.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"
#include "render_test_support.h"
#include "virtual_shadow_structs.h"

using namespace penumbra;

namespace {

class DevicePortabilityTest : public test::RenderTest {};

struct Variant {
    const char* name;
    Settings settings;
};

std::vector<Variant> variants() {
    std::vector<Variant> list;
    Settings cascades;
    cascades.shadows.directional.mode = DirectionalShadowMode::Cascades;  // what auto would not pick on a GPU
    list.push_back({"cascades", cascades});
    Settings compute = cascades;
    compute.shadows.raster = ShadowRaster::Compute;
    compute.render.mainView = MainView::Visibility;
    list.push_back({"compute raster, visibility buffer", compute});
    Settings virtualPages;
    virtualPages.shadows.directional.mode = DirectionalShadowMode::Virtual;
    virtualPages.shadows.spot.mode = SpotShadowMode::Virtual;
    virtualPages.shadows.virtualMaps.poolPages = 256;
    list.push_back({"virtual pages and faces", virtualPages});
    return list;
}

// Three frames (every slot of the per-frame rings), the last one's image.
Image threeFrames(Device& device, const Settings& settings) {
    Renderer renderer(device, test::sunAndSpotBoxScene());
    const RenderRequest request = test::colourRequest(96, 64);
    renderer.render(request, settings);
    renderer.render(request, settings);
    return renderer.render(request, settings).image;
}

Device deviceWithGarbage(uint32_t byte) {
    gpu::DeviceFaultInjection faults;
    faults.garbageByte = byte;
    return DeviceAccess::makeDevice({test::testDeviceOptions(), faults});
}

}  // namespace

TEST_F(DevicePortabilityTest, BufferRangeBoundOffTheLargestOffsetAlignmentIsRefused) {
    gpu::Device& gpu = gpu::backend(device());
    gpu::ComputePipelineDesc desc;
    desc.shader = desc.debugName = "virtual_shadow_probe.comp";
    desc.bindings = virtualShadowProbeBindings();
    desc.pushConstantSize = sizeof(gpu_data::VirtualShadowProbeConstants);
    const gpu::PipelineHandle pipeline = gpu.createComputePipeline(desc);
    const gpu::BufferHandle buffer = gpu.createBuffer(4096, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal);
    gpu::CommandList commands = gpu.beginCommands();
    commands.bindPipeline(pipeline);
    const gpu::DescriptorWrite at16[] = {{gpu_data::kShadowProbeBindingEntries, gpu::BufferSlice{buffer, 16, 256}}};
    try {
        commands.pushDescriptors(at16);
        ADD_FAILURE() << "offset 16 was bound";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not a multiple of 256"), std::string::npos) << e.what();
    }
    const gpu::DescriptorWrite at256[] = {{gpu_data::kShadowProbeBindingEntries, gpu::BufferSlice{buffer, 256, 256}}};
    EXPECT_NO_THROW(commands.pushDescriptors(at256));
    gpu.submitAndWait(commands);
    gpu.destroy(buffer);
    gpu.destroy(pipeline);
}

TEST_F(DevicePortabilityTest, ConsecutiveFramesBindEveryPerFrameSlotAtAPortableOffset) {
    for (const Variant& variant : variants()) {
        SCOPED_TRACE(variant.name);
        EXPECT_NO_THROW(threeFrames(device(), variant.settings));
    }
}

TEST_F(DevicePortabilityTest, MemoryThatStartsAsGarbageDrawsTheSameImages) {
    for (const uint32_t byte : {0xa5u, 0xffu}) {
        Device garbage = deviceWithGarbage(byte);
        for (const Variant& variant : variants()) {
            SCOPED_TRACE(std::string(variant.name) + ", memory filled with byte " + std::to_string(byte));
            const Image clean = threeFrames(device(), variant.settings);
            const Image dirty = threeFrames(garbage, variant.settings);
            ASSERT_EQ(clean.pixels.size(), dirty.pixels.size());
            size_t differing = 0;
            for (size_t i = 0; i < clean.pixels.size(); ++i) differing += clean.pixels[i] != dirty.pixels[i];
            EXPECT_EQ(differing, 0u);
        }
        EXPECT_EQ(garbage.validationMessageCount(), 0u);
    }
}
