#pragma once
// Frames in flight on the window: each slot has its fence, its acquire semaphore, the image Penumbra
// renders into (through <penumbra/vulkan.h>'s ExternalImage, signalling the slot's semaphore) and a
// command buffer that copies that image into the acquired swapchain image, draws the overlays and the
// inspector over it, optionally copies it out for a screenshot, and presents.
#include <cstdint>
#include <functional>
#include <vector>

#include <vulkan/vulkan.h>

#include "penumbra/image.h"
#include "penumbra/renderer.h"

namespace penumbra::viewer {

class ImGuiLayer;
class Swapchain;
class VulkanContext;

class Presenter {
public:
    static constexpr uint32_t kFramesInFlight = 2;

    Presenter(VulkanContext& context, Swapchain& swapchain);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    VkCommandPool commandPool() const { return pool_; }

    // Waits for the slot's previous frame and acquires a swapchain image; false when the swapchain
    // must be re-made first (the window changed size).
    bool beginFrame();
    // This frame's target for Renderer::submitFrame: the slot's image, in the sRGB variant of the
    // swapchain's format for colour, in its UNORM variant for an AOV (whose bytes are copied as they
    // are, like the PNG of penumbra render --aov).
    ExternalImage sceneTarget(bool aov);
    // Records the composition (the scene image, then `overlay`, then ImGui) and presents. With
    // `screenshot`, waits for the frame and returns the presented pixels in it (RGB). False when the
    // swapchain is out of date.
    using OverlayRecorder = std::function<void(VkCommandBuffer, VkImage swapchainImage, VkExtent2D)>;
    bool endFrame(ImGuiLayer& imgui, const OverlayRecorder& overlay, Image* screenshot);

private:
    struct Slot {
        VkFence fence = VK_NULL_HANDLE;
        VkSemaphore acquired = VK_NULL_HANDLE, sceneRendered = VK_NULL_HANDLE;
        VkCommandBuffer commands = VK_NULL_HANDLE;
        VkImage sceneImage = VK_NULL_HANDLE;
        VkDeviceMemory sceneMemory = VK_NULL_HANDLE;
        VkFormat sceneFormat = VK_FORMAT_UNDEFINED;
        VkExtent2D sceneExtent{};
    };
    void makeSceneImage(Slot& slot, VkFormat format);
    void destroySceneImage(Slot& slot);
    void recordScreenshotCopy(VkCommandBuffer commands, VkImage image);
    Image readScreenshot();
    void release();

    VulkanContext& context_;
    Swapchain& swapchain_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::vector<Slot> slots_;
    uint32_t slot_ = 0, image_ = 0;
    VkBuffer screenshotBuffer_ = VK_NULL_HANDLE;
    VkDeviceMemory screenshotMemory_ = VK_NULL_HANDLE;
    VkDeviceSize screenshotBytes_ = 0;
};

// A layout transition of a whole colour image (synchronization2).
void colorImageBarrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                       VkAccessFlags2 dstAccess);

}  // namespace penumbra::viewer
