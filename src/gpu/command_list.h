#pragma once
// Records GPU work against the Device's handles. Created by Device::beginCommands().
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include "gpu/frame_graph.h"
#include "gpu/types.h"

namespace penumbra::gpu {

class Device;

// One region of a buffer-to-buffer copy (a VkBufferCopy).
struct BufferCopyRegion {
    uint64_t sourceOffset = 0, destinationOffset = 0, size = 0;
};

// One VkDrawIndexedIndirectCommand, as indirect draws read it from a buffer (20 bytes).
struct IndexedDrawCommand {
    uint32_t indexCount = 0, instanceCount = 0, firstIndex = 0;
    int32_t vertexOffset = 0;
    uint32_t firstInstance = 0;
};

class CommandList {
public:
    // Declares the next pass of the frame graph: the resources it uses and how. Records the barriers
    // and layout transitions those uses need after the passes declared before (frame_graph.h); every
    // command below that touches a buffer or texture comes after the pass that declares it.
    void pass(std::string_view name, std::span<const ResourceUse> uses);
    void pass(std::string_view name, std::initializer_list<ResourceUse> uses) {
        pass(name, std::span<const ResourceUse>(uses.begin(), uses.size()));
    }
    // Scratch for building a pass's name and uses without a heap allocation once warm: the result
    // stays valid until the next call of the same function on any CommandList of the Device.
    std::string_view joinName(std::string_view prefix, std::string_view suffix);
    std::span<const ResourceUse> joinUses(std::span<const ResourceUse> first, std::initializer_list<ResourceUse> more);
    void beginRendering(const RenderingDesc& desc);
    void endRendering();
    void bindPipeline(PipelineHandle pipeline);
    void pushDescriptors(std::span<const DescriptorWrite> writes);  // set 0 of the bound pipeline
    void bindTextureTable(TextureTableHandle table);                // set 1 of the bound pipeline
    void pushConstants(const void* data, uint32_t size);
    void setViewport(const Rect& rect);
    void setScissor(const Rect& rect);
    void setDepthBias(float constantFactor, float slopeFactor);
    void bindIndexBuffer(BufferHandle buffer);
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t vertexOffset,
                     uint32_t firstInstance);
    void draw(uint32_t vertexCount, uint32_t instanceCount = 1);
    // vkCmdDrawIndexedIndirectCount: up to maxDraws VkDrawIndexedIndirectCommands (20 bytes each) from
    // `commands` at `offset`, as many as the uint32 at `countOffset` of `count` says.
    void drawIndexedIndirectCount(BufferHandle commands, uint64_t offset, BufferHandle count, uint64_t countOffset,
                                  uint32_t maxDraws);
    void dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ = 1);
    void dispatchIndirect(BufferHandle arguments, uint64_t offset);  // a VkDispatchIndirectCommand
    void fillBuffer(BufferHandle buffer, uint32_t value);             // every 32-bit word
    void fillBuffer(const BufferSlice& slice, uint32_t value);        // the words of the slice (size a multiple of 4)
    // Copies a tightly packed buffer into level 0 of `texture` (depth aspect for depth formats), which
    // its pass declared TransferWrite.
    void copyBufferToTexture(BufferHandle source, TextureHandle texture);
    // Inside beginRendering: sets the depth of `rects` to `depth` (the rest of the target is kept).
    void clearDepthRects(std::span<const Rect> rects, float depth);
    void clearBuffer(BufferHandle buffer, uint32_t value);
    void copyBuffer(const BufferSlice& source, BufferHandle destination, uint64_t destinationOffset);
    // Many regions of `source` into `destination` in one command (a scattered update).
    void copyBufferRegions(BufferHandle source, BufferHandle destination, std::span<const BufferCopyRegion> regions);
    // Copies level 0 of `source` (declared TransferRead) into level 0 of `destination` (TransferWrite):
    // the same size, formats of one texel size (RGBA8 UNORM into sRGB keeps the bytes).
    void copyTexture(TextureHandle source, TextureHandle destination);
    // Copies level 0 of `texture` (declared TransferRead) tightly packed into `destination`.
    void copyTextureToBuffer(TextureHandle texture, BufferHandle destination);
    // Blits `source` (declared TransferRead) onto an imported external image, converting the format:
    // the external image goes from target.initialLayout to target.finalLayout here (the caller's
    // layouts and semaphores, outside the frame graph).
    void blitToExternal(TextureHandle source, TextureHandle external, const ExternalTarget& target);
    // GPU timestamps around a named pass (timers nest: a pass may time its steps inside its own
    // timer); results in Device::takeCompletedFrames() once the frame is done. One-off command lists
    // (Device::beginCommands) record none.
    void beginTimer(std::string_view name);
    void endTimer();

    // Internal: the Device fills these.
    Device* device = nullptr;
    void* nativeCommandBuffer = nullptr;
    PipelineHandle boundPipeline;
    std::vector<std::string> timerNames;  // the first timerCount are this list's (storage reused)
    uint32_t timerCount = 0;
    std::vector<uint32_t> openTimers;  // nested timers, innermost last
    uint32_t queryBase = ~0u;  // first timestamp query of this list's range, ~0u = no timers
    uint32_t queryCapacity = 0;
};

}  // namespace penumbra::gpu
