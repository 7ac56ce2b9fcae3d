#pragma once
// The window's swapchain: an sRGB format, FIFO (vsync) or mailbox, images usable as transfer
// source and destination (the viewer copies Penumbra's frame in, and screenshots out) and as colour
// attachments (the inspector draws on top). Re-made when the window's size changes.
#include <vector>

#include <vulkan/vulkan.h>

namespace penumbra::viewer {

class VulkanContext;

class Swapchain {
public:
    Swapchain(VulkanContext& context, VkPresentModeKHR presentMode);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // (Re)creates it for a framebuffer of width x height pixels; waits for the device first.
    void recreate(uint32_t width, uint32_t height);

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_.format; }
    VkExtent2D extent() const { return extent_; }
    VkPresentModeKHR presentMode() const { return presentMode_; }
    const std::vector<VkImage>& images() const { return images_; }
    const std::vector<VkImageView>& views() const { return views_; }
    // Signalled by the frame that draws image i, waited on by its present (one per image, so a
    // semaphore is never re-signalled while a present still waits on it).
    VkSemaphore renderedSemaphore(uint32_t image) const { return rendered_[image]; }

private:
    void destroyImages();

    VulkanContext& context_;
    VkPresentModeKHR presentMode_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format_{};
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> rendered_;
};

}  // namespace penumbra::viewer
