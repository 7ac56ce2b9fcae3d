#pragma once
// The compute rasterizer of the shadow atlases and of the virtual shadow map's pages
// (shaders/shadow_raster.glsl): the tiles of a raster tile list (cull_structs.h: CPU-written for an
// atlas, GPU-written for the dirty pages) drawn by compute shaders from the GPU culling pass's visible
// lists into a buffer of depth by atomic min; an atlas's is then copied into its depth image, which the
// lit pass samples as always. Four passes: per slot of each drawn tile's culled list (the visible
// instances become work items of a few meshlets), per work item (small triangles rasterized at once,
// large ones queued), per large triangle (split into chunks), per chunk: a triangle reaches only the
// tiles whose culling list holds its instance and, within a tile, only the chunks it overlaps. Every
// loop is an indirect dispatch sized by its list's header or by the queue before it, so the work grows
// with what the drawn tiles hold, not with tiles x the scene's meshlets.
#include <string>

#include "cull_structs.h"
#include "penumbra/settings.h"
#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"

namespace penumbra {

// What both compute rasterizers (this one and VisibilityPass) share: the pipeline that sizes the
// indirect dispatches of passes 2 and 3 from a RasterCounters buffer (shadow_raster_args.comp), and
// its recording as the frame graph pass `passName` (queue = kRasterArgsLarge or kRasterArgsChunks).
gpu::PipelineHandle createRasterArgsPipeline(gpu::Device& device, const char* debugName);
void recordRasterDispatchSize(gpu::CommandList& commands, std::string_view passName, gpu::PipelineHandle args,
                              gpu::BufferHandle counters, const gpu_data::RasterArgsConstants& constants);
// The buffers every rasterizer dispatch may read: the scene's, the meshes, indices and meshlets, and
// the culled lists (into `uses`, emptied first: its storage is reused frame to frame).
void rasterReads(const GpuScene& scene, const ShadowCullingPass& culling, std::vector<gpu::ResourceUse>& uses);
struct RasterQueues {
    gpu::BufferHandle counters, large, chunks;
};
void appendRasterMeshWrites(std::vector<gpu::DescriptorWrite>& writes, const GpuScene& gpuScene,
                            const ShadowCullingPass& culling, const RasterQueues& queues);

// The lists one raster pass reads (cull_structs.h), in the upload ring or GPU-written buffers.
// What the shadow rasterizer skips or simplifies: meshlets outside their tile or between its texel
// centres (render.meshletCulling), casters drawn with a simplified level of their mesh whose error stays
// within lodErrorTexels texels of the tile (shadows.lodErrorTexels; 0: full meshes).
struct ShadowRasterOptions {
    bool meshletCulling = true;
    float lodErrorTexels = 0.5f;
    bool operator==(const ShadowRasterOptions&) const = default;
};
inline ShadowRasterOptions shadowRasterOptions(const Settings& settings) {
    return {settings.render.meshletCulling, settings.shadows.lodErrorTexels};
}

struct RasterTileLists {
    gpu::BufferSlice cullFrame;   // CullFrame: the instance and mesh counts
    gpu::BufferSlice tiles;       // the culling pass's CullTileListHeader + CullTile[]
    gpu::BufferSlice rasterList;  // RasterTileListHeader + the culling tiles to draw
};

class ComputeRasterPass {
public:
    // largeQueue, chunkQueue, workQueue: the queues' first capacities (0 = kRasterInitialLarge / Chunks / Work).
    ComputeRasterPass(gpu::Device& device, const GpuScene& gpuScene, uint32_t largeQueue = 0, uint32_t chunkQueue = 0,
                      uint32_t workQueue = 0);
    ~ComputeRasterPass();
    ComputeRasterPass(const ComputeRasterPass&) = delete;
    ComputeRasterPass& operator=(const ComputeRasterPass&) = delete;

    // What one atlas pass draws: the tiles of its raster list (packRasterTiles), whose viewports are
    // `rects` (the copy's); the atlas's other tiles are cached.
    struct AtlasTiles {
        std::vector<gpu::Rect> rects;
        bool freshAtlas = false;  // the atlas and its depth hold nothing yet: clear all of it (and copy all)
    };
    // Draws the tiles into `depth` (atlasSize^2 uints; the caller copies the drawn rects into the sampled
    // atlas, AtlasCopyPass, which keeps the cached tiles). `writes`: the scene bindings
    // 0-4. options: the meshlets it skips, the simplified levels it draws.
    // Its steps are timed as PREFIX/clear, /instances, /chunks.
    void record(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes, const RasterTileLists& lists,
                const ShadowCullingPass& culling, const AtlasTiles& tiles, uint32_t atlasSize, gpu::BufferHandle depth,
                const ShadowRasterOptions& options, std::string_view timerPrefix);
    // Clears the raster list's tiles (their viewports) in `depth` (depthSide^2 uints) to far and draws
    // them, nothing known to the CPU but the lists' buffers (the virtual pages' GPU-written lists). Timed
    // as PREFIX/clear, /instances, /chunks.
    void recordTiles(gpu::CommandList& commands, const std::vector<gpu::DescriptorWrite>& writes, const RasterTileLists& lists,
                     const ShadowCullingPass& culling, gpu::BufferHandle depth, uint32_t depthSide,
                     const ShadowRasterOptions& options, std::string_view timerPrefix);
    // The counters of the last recorded pass (RasterCounters): read back to see dropped triangles and
    // skipped meshlets.
    gpu::BufferSlice counters() const { return {counters_, 0, sizeof(gpu_data::RasterCounters)}; }
    // Grows the queues to hold a frame that asked for this many (what its counters said): a queue more
    // than half full doubles (queueCapacityFor), before a frame overflows it, and a moving camera's slowly
    // rising needs cost a few allocations, not one per new maximum.
    void reserve(uint32_t largePieces, uint32_t chunks, uint32_t workItems = 0);
    // A queue's capacity after a frame asked for `needed` entries: unchanged while it holds twice that, else
    // twice the larger of itself and the ask, never above `limit`.
    static uint32_t queueCapacityFor(uint32_t capacity, uint32_t needed, uint32_t limit);
    static constexpr uint32_t kMaxLargeCapacity = 4u << 20, kMaxChunkCapacity = 32u << 20, kMaxWorkCapacity = 8u << 20;

private:
    void create(uint32_t largeQueue, uint32_t chunkQueue, uint32_t workQueue);
    void resizeQueues(uint32_t large, uint32_t chunks, uint32_t work);  // remakes the queues whose size changes
    uint32_t maxLargeCapacity() const;
    uint32_t maxChunkCapacity() const;
    void destroyAll();
    // The pieces both records share: the writes and constants, the list's clear, passes 1-3.
    void prepare(const std::vector<gpu::DescriptorWrite>& writes, const RasterTileLists& lists, const ShadowCullingPass& culling,
                 gpu::BufferHandle depth, uint32_t depthSide, const ShadowRasterOptions& options);
    void bind(gpu::CommandList& commands, gpu::PipelineHandle pipeline);
    void recordClearTiles(gpu::CommandList& commands, std::string_view timerPrefix, gpu::BufferHandle depth);
    void recordDraw(gpu::CommandList& commands, std::string_view timerPrefix, gpu::BufferHandle depth);
    gpu::Device& device_;
    const GpuScene& scene_;
    gpu::PipelineHandle clear_, expand_, small_, bin_, chunks_, args_;
    gpu::BufferHandle counters_, large_, chunkList_, work_;
    uint32_t largeCapacity_ = 0, chunkCapacity_ = 0, workCapacity_ = 0;
    // Per-record scratch, kept so that a steady frame allocates nothing.
    std::vector<gpu::DescriptorWrite> writes_;
    std::vector<gpu::ResourceUse> reads_;
    RasterTileLists lists_;
    gpu_data::ShadowRasterConstants constants_{};
};

}  // namespace penumbra
