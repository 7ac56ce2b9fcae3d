// Reads of a caller's own buffers and images (ShadowSystem's caster buffers): one copy into host memory
// on the device's queue, after every earlier submission's writes.
#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

// Copies `size` bytes through a host-visible buffer; `record` records the copy into it.
template <typename Record>
std::vector<uint8_t> readThroughHost(Device& device, Device::Impl& d, uint64_t size, Record&& record) {
    const BufferHandle readback = device.createBuffer(size, kBufferTransferDst, MemoryKind::HostVisible, nullptr, "external readback");
    const VkBuffer destination = d.buffers.at(readback.id).buffer;
    d.immediate([&](VkCommandBuffer cb) {
        // The caller's writes, submitted before, become visible to the copy.
        recordMemoryBarrier(cb, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        record(cb, destination);
        recordMemoryBarrier(cb, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    const auto* mapped = static_cast<const uint8_t*>(d.buffers.at(readback.id).mapped);
    std::vector<uint8_t> bytes(mapped, mapped + size);
    BufferResource resource = d.buffers.remove(readback.id);
    d.destroyNow(resource);
    return bytes;
}

// Bytes per texel of the formats readExternalImageRgba8 accepts, 0 for any other.
uint32_t externalTexelBytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8_UNORM: return 1;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_SRGB: return 4;
        default: return 0;
    }
}

}  // namespace

std::vector<uint8_t> Device::readExternalBuffer(uint64_t vkBuffer, uint64_t offset, uint64_t size) {
    if (size == 0) return {};
    const VkBuffer source = reinterpret_cast<VkBuffer>(vkBuffer);
    return readThroughHost(*this, *impl_, size, [&](VkCommandBuffer cb, VkBuffer destination) {
        const VkBufferCopy copy{offset, 0, size};
        vkCmdCopyBuffer(cb, source, destination, 1, &copy);
    });
}

std::vector<uint8_t> Device::readExternalImageRgba8(uint64_t vkImage, uint32_t vkFormat, uint32_t width, uint32_t height,
                                                    uint32_t vkImageLayout) {
    const VkFormat format = VkFormat(vkFormat);
    const uint32_t texelBytes = externalTexelBytes(format);
    if (texelBytes == 0 || width == 0 || height == 0) throw Error("internal: readExternalImageRgba8 of an unsupported image");
    const VkImage image = reinterpret_cast<VkImage>(vkImage);
    const VkImageLayout layout = VkImageLayout(vkImageLayout);
    std::vector<uint8_t> texels =
        readThroughHost(*this, *impl_, uint64_t(width) * height * texelBytes, [&](VkCommandBuffer cb, VkBuffer destination) {
            recordColorImageBarrier(cb, image, 0, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                    VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                    VK_ACCESS_2_TRANSFER_READ_BIT);
            VkBufferImageCopy copy{};
            copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(cb, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, destination, 1, &copy);
            // Back in the caller's layout; its later commands (in later submissions) see it as before.
            recordColorImageBarrier(cb, image, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
        });
    if (texelBytes == 4 && (format == VK_FORMAT_R8G8B8A8_UNORM || format == VK_FORMAT_R8G8B8A8_SRGB)) return texels;
    std::vector<uint8_t> rgba(size_t(width) * height * 4);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        if (texelBytes == 1) {  // R8: the value is the alpha; colour white
            rgba[4 * i + 0] = rgba[4 * i + 1] = rgba[4 * i + 2] = 255;
            rgba[4 * i + 3] = texels[i];
        } else {  // BGRA
            rgba[4 * i + 0] = texels[4 * i + 2];
            rgba[4 * i + 1] = texels[4 * i + 1];
            rgba[4 * i + 2] = texels[4 * i + 0];
            rgba[4 * i + 3] = texels[4 * i + 3];
        }
    }
    return rgba;
}

}  // namespace penumbra::gpu
