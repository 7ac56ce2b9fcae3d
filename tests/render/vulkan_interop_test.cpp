// Embedding (penumbra/vulkan.h): a Penumbra device on the caller's own VkDevice renders into the
// caller's VkImage, synchronised by the caller's semaphore, and the image equals the read-back render.
#include <vector>

#include <gtest/gtest.h>

#include "caller_vulkan.h"
#include "penumbra/error.h"
#include "penumbra/scene_loading.h"

namespace penumbra::test {
namespace {

TEST_F(CallerVulkan, FrameRenderedIntoTheCallersImageEqualsTheReadBackRender) {
    constexpr uint32_t kWidth = 96, kHeight = 54;
    const VkImage target = makeImage(VK_FORMAT_R8G8B8A8_SRGB, kWidth, kHeight);
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    ASSERT_EQ(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore), VK_SUCCESS);
    std::vector<uint8_t> embedded;
    Image readBack;
    {
        Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0));
        Renderer renderer(penumbraDevice, makeDemoScene());
        RenderRequest request;
        request.width = kWidth;
        request.height = kHeight;
        readBack = renderer.render(request, Settings{}).image;
        const CameraView view = resolveCameraView(renderer.scene(), kWidth, kHeight);
        const ExternalImage targetImage =
            externalImage(target, VK_FORMAT_R8G8B8A8_SRGB, {kWidth, kHeight}, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_NULL_HANDLE, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, semaphore);
        renderer.submitFrame(request, Settings{}, view, &targetImage);
        embedded = readImage(target, kWidth, kHeight, semaphore);
        renderer.waitIdle();
    }
    ASSERT_EQ(readBack.pixels.size(), size_t(kWidth) * kHeight * 3);
    size_t differing = 0;
    for (size_t p = 0; p < size_t(kWidth) * kHeight; ++p)
        for (int c = 0; c < 3; ++c) differing += embedded[p * 4 + c] != readBack.pixels[p * 3 + c];
    EXPECT_EQ(differing, 0u);
    bool anyLit = false;
    for (size_t p = 0; p < readBack.pixels.size(); ++p) anyLit |= readBack.pixels[p] > 40;
    EXPECT_TRUE(anyLit);
}

TEST_F(CallerVulkan, DeviceOnTheCallersVulkanLeavesTheirDeviceUsable) {
    { Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0)); }
    // Penumbra destroyed none of the caller's objects: the device still works.
    EXPECT_EQ(vkDeviceWaitIdle(device), VK_SUCCESS);
    EXPECT_NE(makeImage(VK_FORMAT_R8G8B8A8_UNORM, 4, 4), VK_NULL_HANDLE);
}

TEST_F(CallerVulkan, MissingHandlesAreAnError) {
    ExternalVulkanDevice missing = externalVulkanDevice(instance, physicalDevice, VK_NULL_HANDLE, queue, 0);
    EXPECT_THROW(Device{missing}, Error);
}

}  // namespace
}  // namespace penumbra::test
