// Command recording: barriers, dynamic rendering, binding, drawing, timers.
#include "gpu/command_list.h"

#include <algorithm>
#include <cstddef>

#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

VkCommandBuffer native(const CommandList& list) { return static_cast<VkCommandBuffer>(list.nativeCommandBuffer); }
Device::Impl& impl(const CommandList& list) { return list.device->impl(); }

}  // namespace

VkImageAspectFlags aspectOf(const TextureResource& texture) {
    return isDepthFormat(texture.desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

void CommandList::pass(std::string_view name, std::span<const ResourceUse> uses) {
    Device::Impl& d = impl(*this);
    const std::span<const Barrier> barriers = d.frameGraph.declare(name, uses);
    if (barriers.empty()) return;
    d.bufferBarriers.clear();
    d.imageBarriers.clear();
    for (const Barrier& b : barriers) {
        if (b.resource.texture) {
            const TextureResource& t = d.textures.at(b.resource.id);
            VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            barrier.srcStageMask = b.srcStages;
            barrier.srcAccessMask = b.srcAccess;
            barrier.dstStageMask = b.dstStages;
            barrier.dstAccessMask = b.dstAccess;
            barrier.oldLayout = VkImageLayout(b.oldLayout);
            barrier.newLayout = VkImageLayout(b.newLayout);
            barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            barrier.image = t.image;
            barrier.subresourceRange = {aspectOf(t), 0, VK_REMAINING_MIP_LEVELS, 0, 1};
            d.imageBarriers.push_back(barrier);
        } else {
            VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            barrier.srcStageMask = b.srcStages;
            barrier.srcAccessMask = b.srcAccess;
            barrier.dstStageMask = b.dstStages;
            barrier.dstAccessMask = b.dstAccess;
            barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            barrier.buffer = d.buffers.at(b.resource.id).buffer;
            barrier.size = VK_WHOLE_SIZE;
            d.bufferBarriers.push_back(barrier);
        }
    }
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = uint32_t(d.bufferBarriers.size());
    dependency.pBufferMemoryBarriers = d.bufferBarriers.data();
    dependency.imageMemoryBarrierCount = uint32_t(d.imageBarriers.size());
    dependency.pImageMemoryBarriers = d.imageBarriers.data();
    vkCmdPipelineBarrier2(native(*this), &dependency);
}

void CommandList::beginRendering(const RenderingDesc& desc) {
    Device::Impl& d = impl(*this);
    std::vector<VkRenderingAttachmentInfo>& colors = d.scratchAttachments;
    colors.clear();
    for (const ColorAttachment& c : desc.colors) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = d.textures.at(c.texture.id).view;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = c.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        for (int i = 0; i < 4; ++i) a.clearValue.color.float32[i] = c.clearColor[i];
        colors.push_back(a);
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (desc.depth.texture) {
        depth.imageView = d.textures.at(desc.depth.texture.id).view;
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = desc.depth.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil.depth = desc.depth.clearDepth;
    }
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {desc.width, desc.height}};
    info.layerCount = 1;
    info.colorAttachmentCount = uint32_t(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = desc.depth.texture ? &depth : nullptr;
    vkCmdBeginRendering(native(*this), &info);
    setViewport({0, 0, desc.width, desc.height});
    setScissor({0, 0, desc.width, desc.height});
}

void CommandList::endRendering() { vkCmdEndRendering(native(*this)); }

void CommandList::bindPipeline(PipelineHandle pipeline) {
    const PipelineResource& p = impl(*this).pipelines.at(pipeline.id);
    vkCmdBindPipeline(native(*this), p.bindPoint, p.pipeline);
    boundPipeline = pipeline;
}

std::string_view CommandList::joinName(std::string_view prefix, std::string_view suffix) {
    std::string& name = impl(*this).scratchName;
    name.assign(prefix).append(suffix);
    return name;
}

std::span<const ResourceUse> CommandList::joinUses(std::span<const ResourceUse> first,
                                                   std::initializer_list<ResourceUse> more) {
    std::vector<ResourceUse>& uses = impl(*this).scratchUses;
    uses.assign(first.begin(), first.end());
    uses.insert(uses.end(), more);
    return uses;
}

void CommandList::pushDescriptors(std::span<const DescriptorWrite> writes) {
    Device::Impl& d = impl(*this);
    const PipelineResource& p = d.pipelines.at(boundPipeline.id);
    std::vector<VkWriteDescriptorSet>& vkWrites = d.scratchWrites;
    std::vector<VkDescriptorBufferInfo>& bufferInfos = d.scratchBufferInfos;
    std::vector<VkDescriptorImageInfo>& imageInfos = d.scratchImageInfos;
    vkWrites.clear();
    bufferInfos.resize(std::max(bufferInfos.size(), writes.size()));  // sized first: writes point into them
    imageInfos.resize(std::max(imageInfos.size(), writes.size()));
    for (size_t i = 0; i < writes.size(); ++i) {
        const DescriptorWrite& w = writes[i];
        const auto declared = std::find_if(p.bindings.begin(), p.bindings.end(),
                                           [&](const BindingDesc& b) { return b.binding == w.binding; });
        if (declared == p.bindings.end()) continue;  // a pass's writes serve pipelines that read fewer bindings
        const DescriptorType type = declared->type;
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        PENUMBRA_ASSERT(w.arrayElement < declared->count);
        write.dstBinding = w.binding;
        write.dstArrayElement = w.arrayElement;
        write.descriptorCount = 1;
        if (type == DescriptorType::UniformBuffer || type == DescriptorType::StorageBuffer) {
            // Held to the largest offset alignment Vulkan allows on every device, not this device's own
            // limit: lavapipe's is 16 bytes, NVIDIA's uniform one 64, and a misaligned offset there reads
            // other data (a test on lavapipe must fail where a GPU would).
            if (w.offset % kPortableBufferOffsetAlignment != 0)
                throw Error("internal: binding " + std::to_string(w.binding) + " bound at offset " +
                            std::to_string(w.offset) + ", not a multiple of " +
                            std::to_string(kPortableBufferOffsetAlignment));
            bufferInfos[i] = {d.buffers.at(w.buffer.id).buffer, w.offset, w.size ? w.size : VK_WHOLE_SIZE};
            write.descriptorType = type == DescriptorType::UniformBuffer ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                                         : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            write.pBufferInfo = &bufferInfos[i];
        } else if (type == DescriptorType::SampledTexture) {
            imageInfos[i] = {d.samplers.at(w.sampler.id), d.textures.at(w.texture.id).view,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            write.pImageInfo = &imageInfos[i];
        } else {
            imageInfos[i] = {VK_NULL_HANDLE, d.textures.at(w.texture.id).view, VK_IMAGE_LAYOUT_GENERAL};
            write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            write.pImageInfo = &imageInfos[i];
        }
        // The elements of an array binding, written in order, go in one write (one VkWriteDescriptorSet per
        // binding): on lavapipe (Mesa 22.3) a shader did not see the elements past the first when each came
        // in a write of its own in the same push.
        if (!vkWrites.empty() && write.pBufferInfo && vkWrites.back().pBufferInfo) {
            VkWriteDescriptorSet& last = vkWrites.back();
            if (last.dstBinding == write.dstBinding && last.dstArrayElement + last.descriptorCount == write.dstArrayElement &&
                last.pBufferInfo + last.descriptorCount == write.pBufferInfo) {
                ++last.descriptorCount;
                continue;
            }
        }
        vkWrites.push_back(write);
    }
    d.cmdPushDescriptorSet(native(*this), p.bindPoint, p.layout, kPassDescriptorSet, uint32_t(vkWrites.size()),
                          vkWrites.data());
}

void CommandList::bindTextureTable(TextureTableHandle table) {
    Device::Impl& d = impl(*this);
    const PipelineResource& p = d.pipelines.at(boundPipeline.id);
    vkCmdBindDescriptorSets(native(*this), p.bindPoint, p.layout, kTextureTableDescriptorSet, 1, &d.tables.at(table.id).set, 0,
                            nullptr);
}

void CommandList::pushConstants(const void* data, uint32_t size) {
    const PipelineResource& p = impl(*this).pipelines.at(boundPipeline.id);
    vkCmdPushConstants(native(*this), p.layout, p.pushStages, 0, size, data);
}

void CommandList::setViewport(const Rect& rect) {
    const VkViewport viewport{float(rect.x), float(rect.y), float(rect.width), float(rect.height), 0.0f, 1.0f};
    vkCmdSetViewport(native(*this), 0, 1, &viewport);
}

void CommandList::setScissor(const Rect& rect) {
    const VkRect2D scissor{{rect.x, rect.y}, {rect.width, rect.height}};
    vkCmdSetScissor(native(*this), 0, 1, &scissor);
}

void CommandList::setDepthBias(float constantFactor, float slopeFactor) {
    vkCmdSetDepthBias(native(*this), constantFactor, 0.0f, slopeFactor);
}

void CommandList::bindIndexBuffer(BufferHandle buffer) {
    vkCmdBindIndexBuffer(native(*this), impl(*this).buffers.at(buffer.id).buffer, 0, VK_INDEX_TYPE_UINT32);
}

void CommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t vertexOffset,
                              uint32_t firstInstance) {
    vkCmdDrawIndexed(native(*this), indexCount, instanceCount, firstIndex, vertexOffset, firstInstance);
}

static_assert(sizeof(IndexedDrawCommand) == sizeof(VkDrawIndexedIndirectCommand));
static_assert(offsetof(IndexedDrawCommand, firstInstance) == offsetof(VkDrawIndexedIndirectCommand, firstInstance));

void CommandList::drawIndexedIndirectCount(BufferHandle commands, uint64_t offset, BufferHandle count,
                                           uint64_t countOffset, uint32_t maxDraws) {
    Device::Impl& d = impl(*this);
    vkCmdDrawIndexedIndirectCount(native(*this), d.buffers.at(commands.id).buffer, offset, d.buffers.at(count.id).buffer,
                                  countOffset, maxDraws, sizeof(VkDrawIndexedIndirectCommand));
}

void CommandList::draw(uint32_t vertexCount, uint32_t instanceCount) {
    vkCmdDraw(native(*this), vertexCount, instanceCount, 0, 0);
}

void CommandList::dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) {
    vkCmdDispatch(native(*this), groupsX, groupsY, groupsZ);
}

void CommandList::dispatchIndirect(BufferHandle arguments, uint64_t offset) {
    vkCmdDispatchIndirect(native(*this), impl(*this).buffers.at(arguments.id).buffer, offset);
}

void CommandList::fillBuffer(BufferHandle buffer, uint32_t value) { clearBuffer(buffer, value); }

void CommandList::fillBuffer(const BufferSlice& slice, uint32_t value) {
    PENUMBRA_ASSERT(slice.offset % 4 == 0 && slice.size % 4 == 0 && slice.size > 0);
    vkCmdFillBuffer(native(*this), impl(*this).buffers.at(slice.buffer.id).buffer, slice.offset, slice.size, value);
}

void CommandList::copyBufferToTexture(BufferHandle source, TextureHandle texture) {
    Device::Impl& d = impl(*this);
    const TextureResource& t = d.textures.at(texture.id);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {aspectOf(t), 0, 0, 1};
    copy.imageExtent = {t.desc.width, t.desc.height, 1};
    vkCmdCopyBufferToImage(native(*this), d.buffers.at(source.id).buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &copy);
}

void CommandList::clearDepthRects(std::span<const Rect> rects, float depth) {
    if (rects.empty()) return;
    VkClearAttachment attachment{};
    attachment.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
    attachment.clearValue.depthStencil.depth = depth;
    std::vector<VkClearRect>& clears = impl(*this).scratchClears;
    clears.clear();
    for (const Rect& r : rects) clears.push_back({{{r.x, r.y}, {r.width, r.height}}, 0, 1});
    vkCmdClearAttachments(native(*this), 1, &attachment, uint32_t(clears.size()), clears.data());
}

void CommandList::clearBuffer(BufferHandle buffer, uint32_t value) {
    vkCmdFillBuffer(native(*this), impl(*this).buffers.at(buffer.id).buffer, 0, VK_WHOLE_SIZE, value);
}

void CommandList::beginTimer(std::string_view name) {
    Device::Impl& d = impl(*this);
    if (queryBase == ~0u || (timerCount + 1) * 2 > queryCapacity) {
        openTimers.push_back(~0u);  // no room: this timer records nothing
        return;
    }
    openTimers.push_back(timerCount);
    if (timerCount < timerNames.size()) timerNames[timerCount].assign(name);
    else timerNames.emplace_back(name);
    ++timerCount;
    vkCmdWriteTimestamp2(native(*this), VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, d.timestampPool,
                         queryBase + openTimers.back() * 2);
}

void CommandList::endTimer() {
    PENUMBRA_ASSERT(!openTimers.empty());
    const uint32_t timer = openTimers.back();
    openTimers.pop_back();
    if (timer == ~0u) return;
    vkCmdWriteTimestamp2(native(*this), VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, impl(*this).timestampPool,
                         queryBase + timer * 2 + 1);
}

void CommandList::copyBuffer(const BufferSlice& source, BufferHandle destination, uint64_t destinationOffset) {
    Device::Impl& d = impl(*this);
    const VkBufferCopy copy{source.offset, destinationOffset, source.size};
    vkCmdCopyBuffer(native(*this), d.buffers.at(source.buffer.id).buffer, d.buffers.at(destination.id).buffer, 1, &copy);
}

static_assert(sizeof(BufferCopyRegion) == sizeof(VkBufferCopy) && offsetof(BufferCopyRegion, sourceOffset) == offsetof(VkBufferCopy, srcOffset) &&
              offsetof(BufferCopyRegion, destinationOffset) == offsetof(VkBufferCopy, dstOffset) &&
              offsetof(BufferCopyRegion, size) == offsetof(VkBufferCopy, size));

void CommandList::copyBufferRegions(BufferHandle source, BufferHandle destination, std::span<const BufferCopyRegion> regions) {
    if (regions.empty()) return;
    Device::Impl& d = impl(*this);
    vkCmdCopyBuffer(native(*this), d.buffers.at(source.id).buffer, d.buffers.at(destination.id).buffer,
                    uint32_t(regions.size()), reinterpret_cast<const VkBufferCopy*>(regions.data()));
}

void CommandList::copyTexture(TextureHandle source, TextureHandle destination) {
    Device::Impl& d = impl(*this);
    const TextureResource& from = d.textures.at(source.id);
    const TextureResource& to = d.textures.at(destination.id);
    PENUMBRA_ASSERT(from.desc.width == to.desc.width && from.desc.height == to.desc.height &&
                    bytesPerPixel(from.desc.format) == bytesPerPixel(to.desc.format));
    VkImageCopy copy{};
    copy.srcSubresource = {aspectOf(from), 0, 0, 1};
    copy.dstSubresource = {aspectOf(to), 0, 0, 1};
    copy.extent = {from.desc.width, from.desc.height, 1};
    vkCmdCopyImage(native(*this), from.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   1, &copy);
}

void CommandList::copyTextureToBuffer(TextureHandle texture, BufferHandle destination) {
    Device::Impl& d = impl(*this);
    const TextureResource& t = d.textures.at(texture.id);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {aspectOf(t), 0, 0, 1};
    copy.imageExtent = {t.desc.width, t.desc.height, 1};
    vkCmdCopyImageToBuffer(native(*this), t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.buffers.at(destination.id).buffer,
                           1, &copy);
}

void recordColorImageBarrier(VkCommandBuffer cb, VkImage image, uint32_t level, VkImageLayout from, VkImageLayout to,
                             VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                             VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
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

void recordMemoryBarrier(VkCommandBuffer cb, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                         VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cb, &dependency);
}

void CommandList::blitToExternal(TextureHandle source, TextureHandle external, const ExternalTarget& target) {
    Device::Impl& d = impl(*this);
    const TextureResource& src = d.textures.at(source.id);
    const VkImage dst = d.textures.at(external.id).image;
    recordColorImageBarrier(native(*this), dst, 0, VkImageLayout(target.initialLayout), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(src.desc.width), int32_t(src.desc.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(target.width), int32_t(target.height), 1};
    vkCmdBlitImage(native(*this), src.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   1, &blit, VK_FILTER_NEAREST);
    recordColorImageBarrier(native(*this), dst, 0, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VkImageLayout(target.finalLayout),
                    VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                    VK_ACCESS_2_MEMORY_READ_BIT);
}

}  // namespace penumbra::gpu
