#pragma once
// A CPU image drawn over the window after the scene copy: the shadow atlases (--view atlas, scaled
// into the bottom-left corner), the reference-difference picture (--view reference, the whole window)
// or the second settings' image (--compare-settings, the right half), the last two pixel for pixel
// with their bytes as they are, like the AOV views.
#include <cstdint>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "penumbra/image.h"

namespace penumbra::viewer {

class VulkanContext;

class ImageOverlay {
public:
    // BottomLeft: scaled (linear filter) to at most 45 % of the window's height, 8 px from the corner.
    // Window: copied at the top left, one image pixel per window pixel, byte for byte.
    // RightHalf: the same for the right half of the window only (x >= width / 2) of a window-sized image.
    enum class Placement { BottomLeft, Window, RightHalf };

    ImageOverlay(VulkanContext& context, Placement placement);
    ~ImageOverlay();
    ImageOverlay(const ImageOverlay&) = delete;
    ImageOverlay& operator=(const ImageOverlay&) = delete;

    // A new image to show (gray or RGB; in the byte order of `swapchainFormat` for Window); waits for
    // the frames that still read the last one.
    void update(const Image& image, VkFormat swapchainFormat);
    bool ready() const { return image_ != VK_NULL_HANDLE; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    // Where it lands in a window of `extent` pixels (x0, y0, x1, y1).
    glm::vec4 windowRect(VkExtent2D extent) const;
    // Copies the new image in (once) and draws it into the swapchain image (in TRANSFER_DST_OPTIMAL).
    void record(VkCommandBuffer commands, VkImage swapchainImage, VkExtent2D extent);

private:
    void release();
    void recordUpload(VkCommandBuffer commands);

    VulkanContext& context_;
    Placement placement_;
    uint32_t width_ = 0, height_ = 0;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory imageMemory_ = VK_NULL_HANDLE;
    VkBuffer staging_ = VK_NULL_HANDLE;
    VkDeviceMemory stagingMemory_ = VK_NULL_HANDLE;
    bool uploadPending_ = false;
};

}  // namespace penumbra::viewer
