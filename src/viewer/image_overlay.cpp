#include "viewer/image_overlay.h"

#include <algorithm>

#include "viewer/presenter.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

ImageOverlay::ImageOverlay(VulkanContext& context, Placement placement) : context_(context), placement_(placement) {}

ImageOverlay::~ImageOverlay() { release(); }

void ImageOverlay::release() {
    if (image_) vkDestroyImage(context_.device, image_, nullptr);
    if (imageMemory_) vkFreeMemory(context_.device, imageMemory_, nullptr);
    if (staging_) vkDestroyBuffer(context_.device, staging_, nullptr);
    if (stagingMemory_) vkFreeMemory(context_.device, stagingMemory_, nullptr);
    image_ = VK_NULL_HANDLE;
    imageMemory_ = VK_NULL_HANDLE;
    staging_ = VK_NULL_HANDLE;
    stagingMemory_ = VK_NULL_HANDLE;
}

void ImageOverlay::update(const Image& image, VkFormat swapchainFormat) {
    if (image.width == 0 || image.height == 0 || (image.channels != 1 && image.channels < 3)) return;
    VIEWER_VK(vkQueueWaitIdle(context_.queue));  // a debug view: the frames in flight may still read the last copy
    if (image.width != width_ || image.height != height_) {
        release();
        width_ = image.width;
        height_ = image.height;
        // RGBA8 UNORM: blitted with conversion (BottomLeft) or copied bit for bit (Window: the 32-bit
        // formats of the swapchain are copy-compatible with it).
        image_ = context_.createImage(VK_FORMAT_R8G8B8A8_UNORM, {width_, height_},
                                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &imageMemory_);
        staging_ = context_.createHostBuffer(VkDeviceSize(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                             &stagingMemory_);
    }
    const bool blueFirst = placement_ != Placement::BottomLeft && (swapchainFormat == VK_FORMAT_B8G8R8A8_SRGB ||
                                                                swapchainFormat == VK_FORMAT_B8G8R8A8_UNORM);
    void* mapped = nullptr;
    VIEWER_VK(vkMapMemory(context_.device, stagingMemory_, 0, VK_WHOLE_SIZE, 0, &mapped));
    auto* rgba = static_cast<uint8_t*>(mapped);
    const size_t pixels = size_t(width_) * height_;
    for (size_t p = 0; p < pixels; ++p) {
        for (uint32_t c = 0; c < 3; ++c) {
            const uint32_t source = image.channels == 1 ? 0 : (blueFirst ? 2 - c : c);
            rgba[p * 4 + c] = image.pixels[p * image.channels + source];
        }
        rgba[p * 4 + 3] = 255;
    }
    vkUnmapMemory(context_.device, stagingMemory_);
    uploadPending_ = true;
}

glm::vec4 ImageOverlay::windowRect(VkExtent2D extent) const {
    const float right = float(std::min(width_, extent.width)), bottom = float(std::min(height_, extent.height));
    if (placement_ == Placement::Window) return {0.0f, 0.0f, right, bottom};
    if (placement_ == Placement::RightHalf) return {float(extent.width / 2), 0.0f, right, bottom};
    const float margin = 8.0f;
    const float scale = std::min({0.45f * float(extent.height) / float(height_),
                                  (float(extent.width) - 2.0f * margin) / float(width_), 1.0f});
    const float w = float(width_) * scale, h = float(height_) * scale;
    return {margin, float(extent.height) - margin - h, margin + w, float(extent.height) - margin};
}

void ImageOverlay::recordUpload(VkCommandBuffer commands) {
    colorImageBarrier(commands, image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width_, height_, 1};
    vkCmdCopyBufferToImage(commands, staging_, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    colorImageBarrier(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    uploadPending_ = false;
}

void ImageOverlay::record(VkCommandBuffer commands, VkImage swapchainImage, VkExtent2D extent) {
    if (!ready()) return;
    if (uploadPending_) recordUpload(commands);
    const glm::vec4 rect = windowRect(extent);
    // The scene copy wrote the swapchain image just before: order this after it.
    colorImageBarrier(commands, swapchainImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (placement_ != Placement::BottomLeft) {
        if (rect.z <= rect.x || rect.w <= rect.y) return;
        VkImageCopy copy{};
        copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.srcOffset = copy.dstOffset = {int32_t(rect.x), int32_t(rect.y), 0};
        copy.extent = {uint32_t(rect.z - rect.x), uint32_t(rect.w - rect.y), 1};
        vkCmdCopyImage(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainImage,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        return;
    }
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(width_), int32_t(height_), 1};
    blit.dstOffsets[0] = {int32_t(rect.x), int32_t(rect.y), 0};
    blit.dstOffsets[1] = {int32_t(rect.z), int32_t(rect.w), 1};
    vkCmdBlitImage(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainImage,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
}

}  // namespace penumbra::viewer
