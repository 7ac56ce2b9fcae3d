#pragma once
// The shadow atlases as an overlay (--view atlas): the depth the renderer read back (the directional
// atlas left, the spot/point atlas right, as penumbra render --dump-atlas writes them) blitted into
// the bottom-left of the window, each tile labelled with its light and cascade or cube face.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "penumbra/image.h"
#include "penumbra/scene.h"

namespace penumbra::viewer {

class VulkanContext;

// A tile of the atlas image in its pixels, with its label: "sun0 c1" (reserved sun 0, cascade 1),
// "spot2", "point3 +X" (scene light 2, 3; the cube face).
struct AtlasTileLabel {
    glm::vec2 min{0.0f}, max{0.0f};
    std::string text;
};

// The tiles of both atlases from a frame's shadow stats JSON (FrameStats::shadowStatsJson).
std::vector<AtlasTileLabel> atlasTileLabels(const std::string& shadowStatsJson, const Scene& scene);

class AtlasOverlay {
public:
    explicit AtlasOverlay(VulkanContext& context);
    ~AtlasOverlay();
    AtlasOverlay(const AtlasOverlay&) = delete;
    AtlasOverlay& operator=(const AtlasOverlay&) = delete;

    // New depth to show (gray, 1 channel); waits for the frames that still read the last one.
    void update(const Image& atlas);
    bool ready() const { return image_ != VK_NULL_HANDLE; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    // Where it lands in a window of `extent` pixels (x0, y0, x1, y1), and the scale from atlas pixels.
    glm::vec4 windowRect(VkExtent2D extent) const;
    // Copies the new depth in (once) and blits it into the swapchain image (in TRANSFER_DST_OPTIMAL).
    void record(VkCommandBuffer commands, VkImage swapchainImage, VkExtent2D extent);

private:
    void release();

    VulkanContext& context_;
    uint32_t width_ = 0, height_ = 0;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory imageMemory_ = VK_NULL_HANDLE;
    VkBuffer staging_ = VK_NULL_HANDLE;
    VkDeviceMemory stagingMemory_ = VK_NULL_HANDLE;
    bool uploadPending_ = false;
};

}  // namespace penumbra::viewer
