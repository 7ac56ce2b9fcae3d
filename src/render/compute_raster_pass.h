#pragma once
// The compute rasterizer of the shadow atlases (shaders/shadow_raster.glsl): the tiles of
// an atlas drawn by compute shaders from the GPU culling pass's visible lists into a buffer of depth
// by atomic min, then copied into the atlas's depth image, which the lit pass samples as always.
// Three passes: per visible instance (small triangles rasterized at once, large ones queued), per
// large triangle (split into chunks), per chunk.
#include <string>

#include "cull_structs.h"
#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"

namespace penumbra {

// What both compute rasterizers (this one and VisibilityPass) share: the pipeline that sizes the
// indirect dispatches of passes 2 and 3 from a RasterCounters buffer (shadow_raster_args.comp), and
// its recording as the frame graph pass `passName` (queue = kRasterArgsLarge or kRasterArgsChunks).
gpu::PipelineHandle createRasterArgsPipeline(gpu::Device& device, const char* debugName);
void recordRasterDispatchSize(gpu::CommandList& commands, std::string_view passName, gpu::PipelineHandle args,
                              gpu::BufferHandle counters, uint32_t queue /* kRasterArgs* */, uint32_t largeCapacity, uint32_t chunkCapacity);
// The buffers every rasterizer dispatch may read: the scene's, the meshes, indices and meshlets, and
// the culled lists (into `uses`, emptied first: its storage is reused frame to frame).
void rasterReads(const GpuScene& scene, const ShadowCullingPass& culling, std::vector<gpu::ResourceUse>& uses);
struct RasterQueues {
    gpu::BufferHandle counters, large, chunks;
};
void appendRasterMeshWrites(std::vector<gpu::DescriptorWrite>& writes, const GpuScene& gpuScene,
                            const ShadowCullingPass& culling, const RasterQueues& queues);

class ComputeRasterPass {
public:
    // largeQueue, chunkQueue: the queues' first capacities (0 = kRasterInitialLarge / Chunks).
    ComputeRasterPass(gpu::Device& device, const GpuScene& gpuScene, uint32_t largeQueue = 0, uint32_t chunkQueue = 0);
    ~ComputeRasterPass();
    ComputeRasterPass(const ComputeRasterPass&) = delete;
    ComputeRasterPass& operator=(const ComputeRasterPass&) = delete;

    // What one atlas pass draws: entries [listOffset, listOffset + rects.size()) of the cull frame's
    // raster tile list, whose viewports are `rects`; the atlas's other tiles are cached.
    struct AtlasTiles {
        uint32_t listOffset = 0;
        std::vector<gpu::Rect> rects;
        bool freshAtlas = false;  // the atlas and its depth hold nothing yet: clear and copy all of it
    };
    // Draws the tiles into `depth` (atlasSize^2 uints, kept across frames for the cached tiles) and
    // copies them into `atlas` (D32, left in ShaderRead). `writes`: the scene bindings 0-4.
    // meshletCulling: skip the meshlets whose box lies outside their tile (render.meshletCulling). Its
    // steps are timed as PREFIX/clear, /instances, /chunks, /copy.
    void record(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes,
                const gpu::BufferSlice& cullFrame, const ShadowCullingPass& culling, const AtlasTiles& tiles,
                gpu::TextureHandle atlas, uint32_t atlasSize, gpu::BufferHandle depth, bool meshletCulling,
                std::string_view timerPrefix);
    // The counters of the last recorded pass (RasterCounters): read back to see dropped triangles and
    // skipped meshlets.
    gpu::BufferSlice counters() const { return {counters_, 0, sizeof(gpu_data::RasterCounters)}; }
    // Grows the queues to hold a frame that asked for this many (what its counters said).
    void reserve(uint32_t largePieces, uint32_t chunks);
    static constexpr uint32_t kMaxLargeCapacity = 4u << 20, kMaxChunkCapacity = 32u << 20;

private:
    void create(uint32_t largeQueue, uint32_t chunkQueue);
    void destroyAll();
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle clear_, small_, bin_, chunks_, args_;
    gpu::BufferHandle counters_, large_, chunkList_;
    uint32_t largeCapacity_ = 0, chunkCapacity_ = 0;
    // Per-record scratch, kept so that a steady frame allocates nothing.
    std::vector<gpu::DescriptorWrite> writes_;
    std::vector<gpu::ResourceUse> reads_;
};

}  // namespace penumbra
