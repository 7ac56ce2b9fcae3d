#pragma once
// GPU culling of the shadow casters (cull_structs.h): each frame one compute pass tests
// every instance against every shadow tile of both atlases and a second turns the survivors into
// compacted indirect draws per tile and caster kind. The CPU planner computes lights, matrices and
// tiles only; its caster culling (PlanOptions::cullCasters) is the reference tests compare with.
// The same pass culls the visibility buffer's main view (cull_structs.h: the camera frustum, then
// two-phase occlusion against a depth pyramid) into two more lists, recordView's.
#include <array>
#include <string_view>
#include <vector>

#include "cull_structs.h"
#include "gpu/device.h"
#include "render/gpu_scene.h"
#include "shadows/shadow_planner.h"

namespace penumbra {

class ShadowCullingPass {
public:
    // Lists for tileCapacity tiles: kMaxCullTiles for the atlases (and the main view's two lists), or
    // more for the virtual pages (render/virtual_page_draw_pass.h: such a pass records no main view).
    ShadowCullingPass(gpu::Device& device, const GpuScene& gpuScene, uint32_t tileCapacity = gpu_data::kMaxCullTiles);
    // The lists it keeps besides the tiles' (the main view's two; kept by a pass for more tiles too).
    static constexpr uint32_t kViewLists = gpu_data::kCullListCount - gpu_data::kMaxCullTiles;
    ~ShadowCullingPass();
    ShadowCullingPass(const ShadowCullingPass&) = delete;
    ShadowCullingPass& operator=(const ShadowCullingPass&) = delete;

    // Culls for every tile of the tile list `tiles` (CullTileListHeader + CullTile[], at most tileCapacity:
    // CPU-written by packCullTiles, or GPU-written) by indirect dispatches of its header, and leaves
    // the draw lists for drawList; `cullFrame` is packCullFrame(plan) (its counts and spheres). Its frame
    // graph passes are passName, passName/clear and passName/draws.
    void record(gpu::CommandList& commands, const gpu::BufferSlice& cullFrame, const gpu::BufferSlice& tiles,
                std::string_view passName = "shadows.culling");

    // A main-view phase (kCullPassCameraEarly / Late) into list kCullListCameraEarly / Late;
    // `pyramid` is the depth pyramid the late phase tests against (the early phase binds it unread).
    // `cullFrame` holds CullFrame::camera.
    void recordView(gpu::CommandList& commands, const gpu::BufferSlice& cullFrame, uint32_t phase,
                    gpu::BufferHandle pyramid);
    // What the main view's two lists hold (instances y, triangles z), GPU-written this frame.
    gpu::BufferSlice viewStats() const;

    // The indirect draws of culling tile `tile` and caster kind (0 opaque, 1 alpha-tested).
    struct DrawList {
        gpu::BufferHandle commands;
        uint64_t offset = 0;
        gpu::BufferHandle count;
        uint64_t countOffset = 0;
        uint32_t maxDraws = 0;
    };
    DrawList drawList(uint32_t tile, uint32_t kind) const;
    // The uses of a pass that draws drawList()s: the commands and counts as indirect arguments, the
    // visible instances read by the vertex shader.
    void addDrawUses(std::vector<gpu::ResourceUse>& uses) const;
    // The visible-instance lists (cull_structs.h), split over visibleBufferCount() buffers of
    // listsPerBuffer() lists each (splitVisibleLists): the buffer that holds culling tile `tile`'s list
    // (the one its drawList()'s firstInstance values index), the array writes of a shader's list binding
    // (kVisibleListBuffers elements; the ones past the last buffer repeat the first), and their uses.
    gpu::BufferHandle visibleListBuffer(uint32_t tile) const;
    void appendVisibleListWrites(std::vector<gpu::DescriptorWrite>& writes, uint32_t binding) const;
    void addVisibleListUses(std::vector<gpu::ResourceUse>& uses, gpu::Usage usage) const;
    uint32_t listsPerBuffer() const { return listsPerBuffer_; }
    uint32_t visibleBufferCount() const { return visibleBufferCount_; }
    gpu::BufferHandle listCounts() const { return listCounts_; }
    // Per-tile stats (CullTileStats), GPU-written; read them back with Device::readBackAtFrameEnd.
    gpu::BufferSlice tileStats(uint32_t tileCount) const;
    // Tests and debugging (waits for the GPU): the instances each of the first `tileCount` tiles
    // kept in the last recorded culling, sorted.
    std::vector<std::vector<uint32_t>> readVisibleLists(uint32_t tileCount);

private:
    void create();
    void destroyAll();
    gpu::Device& device_;
    const GpuScene& scene_;
    uint32_t tileCapacity_ = 0, listCount_ = 0, listsPerBuffer_ = 1, visibleBufferCount_ = 1;
    gpu::PipelineHandle cull_, buildDraws_;
    // The cull dispatch's writes and uses (any phase), in scratch kept so a steady frame allocates nothing.
    const std::vector<gpu::DescriptorWrite>& cullWrites(const gpu::BufferSlice& cullFrame, const gpu::BufferSlice& tiles,
                                                        gpu::BufferHandle pyramid);
    const std::vector<gpu::ResourceUse>& cullUses(gpu::BufferHandle pyramid, std::initializer_list<gpu::ResourceUse> more = {});
    gpu::BufferHandle listCounts_, drawCommands_, drawCounts_, tileStats_;
    std::array<gpu::BufferHandle, gpu_data::kVisibleListBuffers> visible_{};
    gpu::BufferHandle viewHistory_;  // kView* bits per instance, carried from frame to frame
    std::vector<gpu::DescriptorWrite> writes_;
    std::vector<gpu::ResourceUse> uses_;
};

}  // namespace penumbra
