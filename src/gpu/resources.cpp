// Buffers, textures, samplers and texture tables: creation, upload, readback, destruction.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu/vk_internal.h"

namespace penumbra::gpu {

VkFormat toVkFormat(Format format) {
    switch (format) {
        case Format::RGBA8Unorm: return VK_FORMAT_R8G8B8A8_UNORM;
        case Format::RGBA8Srgb: return VK_FORMAT_R8G8B8A8_SRGB;
        case Format::R8Unorm: return VK_FORMAT_R8_UNORM;
        case Format::R32Float: return VK_FORMAT_R32_SFLOAT;
        case Format::R32Uint: return VK_FORMAT_R32_UINT;
        case Format::RGBA16Float: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case Format::D32Float: return VK_FORMAT_D32_SFLOAT;
        case Format::Undefined: break;
    }
    return VK_FORMAT_UNDEFINED;
}

bool isDepthFormat(Format format) { return format == Format::D32Float; }

uint32_t bytesPerPixel(Format format) {
    switch (format) {
        case Format::R8Unorm: return 1;
        case Format::RGBA16Float: return 8;
        case Format::Undefined: return 0;
        default: return 4;
    }
}

uint32_t Device::Impl::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memoryProperties.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (memoryProperties.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw Error("GPU memory: no memory type with the required properties");
}

VkDeviceMemory Device::Impl::allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = findMemoryType(requirements.memoryTypeBits, flags);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateMemory(device, &info, nullptr, &memory));
    return memory;
}

BufferHandle Device::createBuffer(size_t size, uint32_t usage, MemoryKind memory, const void* initialData,
                                  const std::string&) {
    Impl& d = *impl_;
    BufferResource resource;
    resource.size = std::max<size_t>(size, 16);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = resource.size;
    if (usage & kBufferStorage) info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (usage & kBufferUniform) info.usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (usage & kBufferIndex) info.usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    info.usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VK_CHECK(vkCreateBuffer(d.device, &info, nullptr, &resource.buffer));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(d.device, resource.buffer, &requirements);
    const VkMemoryPropertyFlags flags = memory == MemoryKind::HostVisible
                                            ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                            : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    resource.memory = d.allocate(requirements, flags);
    VK_CHECK(vkBindBufferMemory(d.device, resource.buffer, resource.memory, 0));
    if (memory == MemoryKind::HostVisible) VK_CHECK(vkMapMemory(d.device, resource.memory, 0, VK_WHOLE_SIZE, 0, &resource.mapped));
    d.buffers.push_back(resource);
    const BufferHandle handle{uint32_t(d.buffers.size() - 1)};
    if (initialData && size > 0) {
        if (resource.mapped) {
            std::memcpy(resource.mapped, initialData, size);
        } else {
            const BufferHandle staging = createBuffer(size, kBufferTransferSrc, MemoryKind::HostVisible, initialData);
            d.immediate([&](VkCommandBuffer cb) {
                VkBufferCopy copy{0, 0, size};
                vkCmdCopyBuffer(cb, d.buffers[staging.id].buffer, d.buffers[handle.id].buffer, 1, &copy);
            });
            destroy(staging);
        }
    }
    return handle;
}

void Device::writeBuffer(BufferHandle buffer, const void* data, size_t size, size_t offset) {
    BufferResource& resource = impl_->buffers.at(buffer.id);
    PENUMBRA_ASSERT(resource.mapped && offset + size <= resource.size);
    std::memcpy(static_cast<uint8_t*>(resource.mapped) + offset, data, size);
}

void* Device::mappedPointer(BufferHandle buffer) { return impl_->buffers.at(buffer.id).mapped; }

void Device::destroy(BufferHandle handle) {
    Impl& d = *impl_;
    BufferResource& resource = d.buffers.at(handle.id);
    if (resource.buffer) vkDestroyBuffer(d.device, resource.buffer, nullptr);
    if (resource.memory) vkFreeMemory(d.device, resource.memory, nullptr);
    resource = BufferResource{};
}

TextureHandle Device::createTexture(const TextureDesc& desc) {
    Impl& d = *impl_;
    TextureResource resource;
    resource.desc = desc;
    if (resource.desc.mipLevels == 0)
        resource.desc.mipLevels = 1 + uint32_t(std::floor(std::log2(double(std::max(desc.width, desc.height)))));
    resource.format = toVkFormat(desc.format);
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = resource.format;
    info.extent = {desc.width, desc.height, 1};
    info.mipLevels = resource.desc.mipLevels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (desc.usage & kTextureSampled) info.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (desc.usage & kTextureColorTarget) info.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (desc.usage & kTextureDepthTarget) info.usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (desc.usage & kTextureStorage) info.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(d.device, &info, nullptr, &resource.image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(d.device, resource.image, &requirements);
    resource.memory = d.allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VK_CHECK(vkBindImageMemory(d.device, resource.image, resource.memory, 0));
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = resource.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = resource.format;
    viewInfo.subresourceRange = {VkImageAspectFlags(isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                                 0, resource.desc.mipLevels, 0, 1};
    VK_CHECK(vkCreateImageView(d.device, &viewInfo, nullptr, &resource.view));
    d.textures.push_back(resource);
    return TextureHandle{uint32_t(d.textures.size() - 1)};
}

void Device::destroy(TextureHandle handle) {
    Impl& d = *impl_;
    TextureResource& resource = d.textures.at(handle.id);
    if (resource.view) vkDestroyImageView(d.device, resource.view, nullptr);
    if (resource.image) vkDestroyImage(d.device, resource.image, nullptr);
    if (resource.memory) vkFreeMemory(d.device, resource.memory, nullptr);
    resource = TextureResource{};
}

namespace {
void mipBarrier(VkCommandBuffer cb, VkImage image, uint32_t level, VkImageLayout from, VkImageLayout to,
                VkAccessFlags2 srcAccess, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cb, &dependency);
}
}  // namespace

void Device::uploadTexture(TextureHandle handle, std::span<const uint8_t> pixels) {
    Impl& d = *impl_;
    const TextureResource& t = d.textures.at(handle.id);
    PENUMBRA_ASSERT(pixels.size() == size_t(t.desc.width) * t.desc.height * bytesPerPixel(t.desc.format));
    const BufferHandle staging = createBuffer(pixels.size(), kBufferTransferSrc, MemoryKind::HostVisible, pixels.data());
    d.immediate([&](VkCommandBuffer cb) {
        const VkAccessFlags2 write = VK_ACCESS_2_TRANSFER_WRITE_BIT, read = VK_ACCESS_2_TRANSFER_READ_BIT;
        for (uint32_t level = 0; level < t.desc.mipLevels; ++level)
            mipBarrier(cb, t.image, level, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, write);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {t.desc.width, t.desc.height, 1};
        vkCmdCopyBufferToImage(cb, d.buffers[staging.id].buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        // Box-filtered mip chain by successive linear blits.
        int32_t w = int32_t(t.desc.width), h = int32_t(t.desc.height);
        for (uint32_t level = 1; level < t.desc.mipLevels; ++level) {
            mipBarrier(cb, t.image, level - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, write, read);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
            blit.srcOffsets[1] = {w, h, 1};
            w = std::max(1, w / 2);
            h = std::max(1, h / 2);
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            blit.dstOffsets[1] = {w, h, 1};
            vkCmdBlitImage(cb, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &blit, VK_FILTER_LINEAR);
            mipBarrier(cb, t.image, level - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       read, VK_ACCESS_2_SHADER_READ_BIT);
        }
        mipBarrier(cb, t.image, t.desc.mipLevels - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, write, VK_ACCESS_2_SHADER_READ_BIT);
    });
    destroy(staging);
}

namespace {
VkFilter toVkFilter(Filter filter) { return filter == Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }
VkSamplerAddressMode toVkAddressMode(AddressMode mode) {
    switch (mode) {
        case AddressMode::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case AddressMode::ClampToBorderWhite: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
        case AddressMode::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case AddressMode::Repeat: break;
    }
    return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}
}  // namespace

SamplerHandle Device::createSampler(const SamplerDesc& desc) {
    Impl& d = *impl_;
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = toVkFilter(desc.filter);
    info.minFilter = toVkFilter(desc.minFilter.value_or(desc.filter));
    info.mipmapMode = desc.mipmapFilter.value_or(desc.filter) == Filter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                                                : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeW = toVkAddressMode(desc.addressMode);
    info.addressModeV = toVkAddressMode(desc.addressModeV.value_or(desc.addressMode));
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    info.maxLod = desc.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
    info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
    info.compareOp = toVkCompareOp(desc.compareOp);
    VkSampler sampler = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSampler(d.device, &info, nullptr, &sampler));
    d.samplers.push_back(sampler);
    return SamplerHandle{uint32_t(d.samplers.size() - 1)};
}

TextureTableHandle Device::createTextureTable(std::span<const TextureHandle> textures, SamplerHandle sampler) {
    const std::vector<SamplerHandle> samplers(textures.size(), sampler);
    return createTextureTable(textures, samplers);
}

TextureTableHandle Device::createTextureTable(std::span<const TextureHandle> textures,
                                              std::span<const SamplerHandle> samplers) {
    Impl& d = *impl_;
    PENUMBRA_ASSERT(samplers.size() == textures.size());
    TextureTableResource table;
    table.count = uint32_t(textures.size());
    PENUMBRA_ASSERT(table.count > 0);
    VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, table.count, VK_SHADER_STAGE_ALL, nullptr};
    VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layoutInfo.bindingCount = 1;
    layoutInfo.pBindings = &binding;
    VK_CHECK(vkCreateDescriptorSetLayout(d.device, &layoutInfo, nullptr, &table.layout));
    VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, table.count};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    VK_CHECK(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &table.pool));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = table.pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &table.layout;
    VK_CHECK(vkAllocateDescriptorSets(d.device, &alloc, &table.set));
    std::vector<VkDescriptorImageInfo> images;
    for (size_t i = 0; i < textures.size(); ++i)
        images.push_back({d.samplers.at(samplers[i].id), d.textures.at(textures[i].id).view,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = table.set;
    write.descriptorCount = table.count;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = images.data();
    vkUpdateDescriptorSets(d.device, 1, &write, 0, nullptr);
    d.tables.push_back(table);
    return TextureTableHandle{uint32_t(d.tables.size() - 1)};
}

Image Device::readTexture(TextureHandle handle, TextureState state) {
    Impl& d = *impl_;
    const TextureResource& t = d.textures.at(handle.id);
    const uint32_t bpp = bytesPerPixel(t.desc.format);
    const size_t size = size_t(t.desc.width) * t.desc.height * bpp;
    const BufferHandle readback = createBuffer(size, kBufferTransferDst, MemoryKind::HostVisible);
    d.immediate([&](VkCommandBuffer cb) {
        recordTransition(cb, t, state, TextureState::TransferSrc);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VkImageAspectFlags(isDepthFormat(t.desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 0, 1};
        copy.imageExtent = {t.desc.width, t.desc.height, 1};
        vkCmdCopyImageToBuffer(cb, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.buffers[readback.id].buffer, 1, &copy);
        recordTransition(cb, t, TextureState::TransferSrc, state);
    });
    Image image(t.desc.width, t.desc.height, bpp);
    std::memcpy(image.pixels.data(), d.buffers[readback.id].mapped, size);
    destroy(readback);
    return image;
}

}  // namespace penumbra::gpu
