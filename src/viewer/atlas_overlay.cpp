#include "viewer/atlas_overlay.h"

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "viewer/presenter.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

namespace {

constexpr const char* kCubeFaces[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

glm::vec2 tileCorner(uint32_t tile, uint32_t split, uint32_t tileSize) {
    return glm::vec2(float((tile % split) * tileSize), float((tile / split) * tileSize));
}

}  // namespace

std::vector<AtlasTileLabel> atlasTileLabels(const std::string& shadowStatsJson, const Scene& scene) {
    std::vector<AtlasTileLabel> labels;
    const nlohmann::json stats = nlohmann::json::parse(shadowStatsJson, nullptr, false);
    if (stats.is_discarded() || !stats.contains("directional")) return labels;
    const nlohmann::json& directional = stats["directional"];
    const uint32_t tiles = directional.value("tiles", 0u), lights = directional.value("lightsReserved", 0u);
    const uint32_t split = std::max(directional.value("split", 1u), 1u), tileSize = directional.value("tileSize", 0u);
    const uint32_t cascades = lights > 0 ? tiles / lights : 0;
    for (uint32_t t = 0; t < tiles && cascades > 0; ++t) {
        const glm::vec2 corner = tileCorner(t, split, tileSize);
        labels.push_back({corner, corner + glm::vec2(float(tileSize)),
                          "sun" + std::to_string(t / cascades) + " c" + std::to_string(t % cascades)});
    }
    const float otherLeft = tiles > 0 ? float(directional.value("atlasSize", 0u)) : 1.0f;
    const nlohmann::json& other = stats["other"];
    const uint32_t otherSplit = std::max(other.value("split", 1u), 1u), otherTileSize = other.value("tileSize", 0u);
    uint32_t tile = 0;
    for (const auto& lightIndex : other.value("reservedLights", std::vector<uint32_t>{})) {
        const bool point = lightIndex < scene.lights.size() && scene.lights[lightIndex].type == LightType::Point;
        for (uint32_t face = 0; face < (point ? 6u : 1u); ++face, ++tile) {
            const glm::vec2 corner = glm::vec2(otherLeft, 0.0f) + tileCorner(tile, otherSplit, otherTileSize);
            std::string text = (point ? "point" : "spot") + std::to_string(lightIndex);
            if (point) text += std::string(" ") + kCubeFaces[face];
            labels.push_back({corner, corner + glm::vec2(float(otherTileSize)), text});
        }
    }
    return labels;
}

AtlasOverlay::AtlasOverlay(VulkanContext& context) : context_(context) {}

AtlasOverlay::~AtlasOverlay() { release(); }

void AtlasOverlay::release() {
    if (image_) vkDestroyImage(context_.device, image_, nullptr);
    if (imageMemory_) vkFreeMemory(context_.device, imageMemory_, nullptr);
    if (staging_) vkDestroyBuffer(context_.device, staging_, nullptr);
    if (stagingMemory_) vkFreeMemory(context_.device, stagingMemory_, nullptr);
    image_ = VK_NULL_HANDLE;
    imageMemory_ = VK_NULL_HANDLE;
    staging_ = VK_NULL_HANDLE;
    stagingMemory_ = VK_NULL_HANDLE;
}

void AtlasOverlay::update(const Image& atlas) {
    if (atlas.width == 0 || atlas.height == 0 || atlas.channels != 1) return;
    VIEWER_VK(vkQueueWaitIdle(context_.queue));  // a debug view: the frames in flight may still read the last copy
    if (atlas.width != width_ || atlas.height != height_) {
        release();
        width_ = atlas.width;
        height_ = atlas.height;
        image_ = context_.createImage(VK_FORMAT_R8G8B8A8_UNORM, {width_, height_},
                                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &imageMemory_);
        staging_ = context_.createHostBuffer(VkDeviceSize(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                             &stagingMemory_);
    }
    void* mapped = nullptr;
    VIEWER_VK(vkMapMemory(context_.device, stagingMemory_, 0, VK_WHOLE_SIZE, 0, &mapped));
    auto* rgba = static_cast<uint8_t*>(mapped);
    for (size_t p = 0; p < atlas.pixels.size(); ++p) {
        std::memset(rgba + p * 4, atlas.pixels[p], 3);
        rgba[p * 4 + 3] = 255;
    }
    vkUnmapMemory(context_.device, stagingMemory_);
    uploadPending_ = true;
}

glm::vec4 AtlasOverlay::windowRect(VkExtent2D extent) const {
    const float margin = 8.0f;
    const float scale = std::min({0.45f * float(extent.height) / float(height_),
                                  (float(extent.width) - 2.0f * margin) / float(width_), 1.0f});
    const float w = float(width_) * scale, h = float(height_) * scale;
    return {margin, float(extent.height) - margin - h, margin + w, float(extent.height) - margin};
}

void AtlasOverlay::record(VkCommandBuffer commands, VkImage swapchainImage, VkExtent2D extent) {
    if (!ready()) return;
    if (uploadPending_) {
        colorImageBarrier(commands, image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width_, height_, 1};
        vkCmdCopyBufferToImage(commands, staging_, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        colorImageBarrier(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT);
        uploadPending_ = false;
    }
    const glm::vec4 rect = windowRect(extent);
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(width_), int32_t(height_), 1};
    blit.dstOffsets[0] = {int32_t(rect.x), int32_t(rect.y), 0};
    blit.dstOffsets[1] = {int32_t(rect.z), int32_t(rect.w), 1};
    // The scene copy wrote the swapchain image just before: order the blit after it.
    colorImageBarrier(commands, swapchainImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdBlitImage(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainImage,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
}

}  // namespace penumbra::viewer
