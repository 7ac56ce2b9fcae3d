#pragma once
// Records GPU work against the Device's handles. Created by Device::beginCommands().
#include <cstdint>
#include <span>
#include <string>

#include "gpu/types.h"

namespace penumbra::gpu {

class Device;

class CommandList {
public:
    void transition(TextureHandle texture, TextureState from, TextureState to);
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
    // Copies a tightly packed buffer into level 0 of `texture` (depth aspect for depth formats); the
    // texture goes from Undefined to `finalState`.
    void copyBufferToTexture(BufferHandle source, TextureHandle texture, TextureState finalState);
    // Copies the rectangles `rects` of a tightly packed texture-sized buffer into them in `texture`,
    // which goes from `from` (Undefined discards the rest) to `to`.
    void copyBufferToTextureRects(BufferHandle source, TextureHandle texture, std::span<const Rect> rects,
                                  TextureState from, TextureState to);
    // Inside beginRendering: sets the depth of `rects` to `depth` (the rest of the target is kept).
    void clearDepthRects(std::span<const Rect> rects, float depth);
    void clearBuffer(BufferHandle buffer, uint32_t value);
    void copyBuffer(const BufferSlice& source, BufferHandle destination, uint64_t destinationOffset);
    // Copies level 0 of `texture` (in `state`, left there) tightly packed into `destination`.
    void copyTextureToBuffer(TextureHandle texture, TextureState state, BufferHandle destination);
    // Blits `source` (ColorTarget, left TransferSrc) onto an imported external image, converting the
    // format, and leaves that image in target.finalLayout.
    void blitToExternal(TextureHandle source, TextureHandle external, const ExternalTarget& target);
    // A full memory barrier between compute/graphics writes and later reads (buffers and storage images).
    void memoryBarrier();
    // Transfer writes so far become visible to the host once the frame's fence has signalled.
    void hostReadBarrier();
    // GPU timestamps around a named pass (timers nest: a pass may time its steps inside its own
    // timer); results in Device::takeCompletedFrames() once the frame is done. One-off command lists
    // (Device::beginCommands) record none.
    void beginTimer(const std::string& name);
    void endTimer();

    // Internal: the Device fills these.
    Device* device = nullptr;
    void* nativeCommandBuffer = nullptr;
    PipelineHandle boundPipeline;
    std::vector<std::string> timerNames;
    std::vector<uint32_t> openTimers;  // nested timers, innermost last
    uint32_t queryBase = ~0u;  // first timestamp query of this list's range, ~0u = no timers
    uint32_t queryCapacity = 0;
};

}  // namespace penumbra::gpu
