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
        case Format::R16Unorm: return VK_FORMAT_R16_UNORM;
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
        case Format::R16Unorm: return 2;
        case Format::RGBA16Float: return 8;
        case Format::Undefined: return 0;
        default: return 4;
    }
}

BufferHandle Device::createBuffer(size_t size, uint32_t usage, MemoryKind memory, const void* initialData,
                                  const std::string& debugName) {
    Impl& d = *impl_;
    BufferResource resource;
    resource.size = std::max<size_t>(size, 16);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = resource.size;
    if (usage & kBufferStorage) info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (usage & kBufferUniform) info.usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (usage & kBufferIndex) info.usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    if (usage & kBufferIndirect) info.usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VK_CHECK(vkCreateBuffer(d.device, &info, nullptr, &resource.buffer));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(d.device, resource.buffer, &requirements);
    const VkMemoryPropertyFlags flags = memory == MemoryKind::HostVisible
                                            ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                            : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    try {
        resource.memory = d.memory->allocate(requirements, flags, true, debugName);
        VK_CHECK(vkBindBufferMemory(d.device, resource.buffer, resource.memory.memory, resource.memory.offset));
    } catch (...) {
        d.destroyNow(resource);
        throw;
    }
    resource.mapped = resource.memory.mapped;
    d.setDebugName(VK_OBJECT_TYPE_BUFFER, uint64_t(resource.buffer), debugName);
    d.noteCreated(debugName);
    const BufferHandle handle{d.buffers.insert(resource)};
    d.frameGraph.forget({handle.id, false});  // a reused id starts unused
    d.frameGraph.setName({handle.id, false}, debugName);
    if (initialData && size > 0) {
        if (resource.mapped) {
            std::memcpy(resource.mapped, initialData, size);
        } else {
            BufferHandle staging;
            try {
                staging = createBuffer(size, kBufferTransferSrc, MemoryKind::HostVisible, initialData, "staging");
                d.immediate([&](VkCommandBuffer cb) {
                    VkBufferCopy copy{0, 0, size};
                    vkCmdCopyBuffer(cb, d.buffers.at(staging.id).buffer, d.buffers.at(handle.id).buffer, 1, &copy);
                });
            } catch (...) {
                // The submission failed or never ran (a lost device has been waited for): free both now.
                if (staging) {
                    BufferResource stagingResource = d.buffers.remove(staging.id);
                    d.destroyNow(stagingResource);
                }
                BufferResource failed = d.buffers.remove(handle.id);
                d.destroyNow(failed);
                throw;
            }
            BufferResource stagingResource = d.buffers.remove(staging.id);
            d.destroyNow(stagingResource);  // the copy has finished
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
uint64_t Device::bufferSize(BufferHandle buffer) const { return impl_->buffers.at(buffer.id).size; }
uint64_t Device::nativeBuffer(BufferHandle buffer) const {
    return reinterpret_cast<uint64_t>(impl_->buffers.at(buffer.id).buffer);
}
uint64_t Device::nativeImageView(TextureHandle texture) const {
    return reinterpret_cast<uint64_t>(impl_->textures.at(texture.id).view);
}
uint64_t Device::nativeSampler(SamplerHandle sampler) const {
    return reinterpret_cast<uint64_t>(impl_->samplers.at(sampler.id));
}

void Device::Impl::destroyNow(BufferResource& resource) {
    if (resource.buffer) vkDestroyBuffer(device, resource.buffer, nullptr);
    memory->free(resource.memory);
    resource = BufferResource{};
}

void Device::destroy(BufferHandle handle) {
    if (!handle) return;
    impl_->garbageList().buffers.push_back(impl_->buffers.remove(handle.id));
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
    if (desc.width == 0 || desc.height == 0 || desc.width > maxImageSize() || desc.height > maxImageSize())
        throw Error("texture '" + desc.debugName + "' of " + std::to_string(desc.width) + "x" +
                    std::to_string(desc.height) + " exceeds the device's limit of " + std::to_string(maxImageSize()) +
                    " texels");
    VK_CHECK(vkCreateImage(d.device, &info, nullptr, &resource.image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(d.device, resource.image, &requirements);
    try {
        resource.memory = d.memory->allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false, desc.debugName);
        VK_CHECK(vkBindImageMemory(d.device, resource.image, resource.memory.memory, resource.memory.offset));
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = resource.image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = resource.format;
        viewInfo.subresourceRange = {VkImageAspectFlags(isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                                     0, resource.desc.mipLevels, 0, 1};
        VK_CHECK(vkCreateImageView(d.device, &viewInfo, nullptr, &resource.view));
    } catch (...) {
        d.destroyNow(resource);
        throw;
    }
    d.setDebugName(VK_OBJECT_TYPE_IMAGE, uint64_t(resource.image), desc.debugName);
    d.setDebugName(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(resource.view), desc.debugName);
    d.noteCreated(desc.debugName);
    const TextureHandle handle{d.textures.insert(resource)};
    d.frameGraph.forget({handle.id, true});  // a reused id starts unused (VK_IMAGE_LAYOUT_UNDEFINED)
    d.frameGraph.setName({handle.id, true}, desc.debugName);
    return handle;
}

TextureHandle Device::importTexture(const ExternalTarget& target, const std::string& debugName) {
    Impl& d = *impl_;
    if (!target.image || target.width == 0 || target.height == 0)
        throw Error("external image: a VkImage and its size are required");
    TextureResource resource;
    resource.image = reinterpret_cast<VkImage>(target.image);
    resource.imported = true;
    resource.format = VkFormat(target.format);
    resource.desc = {target.width, target.height, Format::Undefined, kTextureTransferDst, 1, debugName};
    d.noteCreated(debugName);
    const TextureHandle handle{d.textures.insert(resource)};
    d.frameGraph.forget({handle.id, true});
    d.frameGraph.setName({handle.id, true}, debugName);
    return handle;
}

TextureHandle Device::importDepthTexture(uint64_t vkImage, uint64_t vkImageView, uint32_t width, uint32_t height,
                                        const std::string& debugName) {
    Impl& d = *impl_;
    if (!vkImage || !vkImageView || width == 0 || height == 0)
        throw Error("external depth image: a VkImage, its VkImageView and its size are required");
    TextureResource resource;
    resource.image = reinterpret_cast<VkImage>(vkImage);
    resource.view = reinterpret_cast<VkImageView>(vkImageView);
    resource.imported = resource.importedView = true;
    resource.format = VK_FORMAT_D32_SFLOAT;
    resource.desc = {width, height, Format::D32Float, kTextureSampled | kTextureDepthTarget, 1, debugName};
    d.noteCreated(debugName);
    const TextureHandle handle{d.textures.insert(resource)};
    d.frameGraph.forget({handle.id, true});
    d.frameGraph.setName({handle.id, true}, debugName);
    return handle;
}

void Device::assumeWritten(TextureHandle texture, Usage usage) { impl_->frameGraph.assumeWritten({texture.id, true}, usage); }

const TextureDesc& Device::textureDesc(TextureHandle texture) const { return impl_->textures.at(texture.id).desc; }

void Device::Impl::destroyNow(TextureResource& resource) {
    if (resource.view && !resource.importedView) vkDestroyImageView(device, resource.view, nullptr);
    // An imported image belongs to the caller. (Not "has no memory": an image whose allocation
    // failed has none either, and must still go.)
    if (resource.image && !resource.imported) vkDestroyImage(device, resource.image, nullptr);
    memory->free(resource.memory);
    resource = TextureResource{};
}

void Device::destroy(TextureHandle handle) {
    if (!handle) return;
    impl_->garbageList().textures.push_back(impl_->textures.remove(handle.id));
}

namespace {
void mipBarrier(VkCommandBuffer cb, VkImage image, uint32_t level, VkImageLayout from, VkImageLayout to,
                VkAccessFlags2 srcAccess, VkAccessFlags2 dstAccess) {
    recordColorImageBarrier(cb, image, level, from, to, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, srcAccess,
                            VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, dstAccess);
}
}  // namespace

void Device::uploadTexture(TextureHandle handle, std::span<const uint8_t> pixels) {
    Impl& d = *impl_;
    const TextureResource& t = d.textures.at(handle.id);
    PENUMBRA_ASSERT(pixels.size() == size_t(t.desc.width) * t.desc.height * bytesPerPixel(t.desc.format));
    const BufferHandle staging =
        createBuffer(pixels.size(), kBufferTransferSrc, MemoryKind::HostVisible, pixels.data(), "texture staging");
    struct FreeStaging {  // also when the submission fails
        Impl& d;
        BufferHandle staging;
        ~FreeStaging() {
            BufferResource resource = d.buffers.remove(staging.id);
            d.destroyNow(resource);  // the upload has finished, or never ran
        }
    } freeStaging{d, staging};
    d.immediate([&](VkCommandBuffer cb) {
        const VkAccessFlags2 write = VK_ACCESS_2_TRANSFER_WRITE_BIT, read = VK_ACCESS_2_TRANSFER_READ_BIT;
        for (uint32_t level = 0; level < t.desc.mipLevels; ++level)
            mipBarrier(cb, t.image, level, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, write);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {t.desc.width, t.desc.height, 1};
        vkCmdCopyBufferToImage(cb, d.buffers.at(staging.id).buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
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
    d.noteCreated("sampler");
    return SamplerHandle{d.samplers.insert(sampler)};
}

void Device::destroy(SamplerHandle handle) {
    if (!handle) return;
    impl_->garbageList().samplers.push_back(impl_->samplers.remove(handle.id));
}

void Device::Impl::destroyNow(TextureTableResource& table) {
    if (table.pool) vkDestroyDescriptorPool(device, table.pool, nullptr);
    if (table.layout) vkDestroyDescriptorSetLayout(device, table.layout, nullptr);
    table = TextureTableResource{};
}

void Device::destroy(TextureTableHandle handle) {
    if (!handle) return;
    impl_->garbageList().tables.push_back(impl_->tables.remove(handle.id));
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
    d.noteCreated("texture table");
    return TextureTableHandle{d.tables.insert(table)};
}

std::vector<uint8_t> Device::readBuffer(BufferHandle handle) {
    const BufferResource& buffer = impl_->buffers.at(handle.id);
    return readExternalBuffer(reinterpret_cast<uint64_t>(buffer.buffer), 0, buffer.size);  // the same copy through the host
}

}  // namespace penumbra::gpu
