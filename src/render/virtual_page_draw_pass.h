#pragma once
// Draws the dirty pages of a directional light's virtual shadow map (or of spot and point light faces'
// maps: virtual_face_tiles.comp gives each page its perspective projection) with the compute rasterizer the
// atlases use (render/compute_raster_pass.h), from the page table's draw list (render/
// virtual_page_table_pass.h: VirtualPageDrawHeader + VirtualPageDraw[]) that exists only on the GPU: no
// readback, every loop over the pages an indirect dispatch or a dispatch over the pages one record draws.
//
// Per record: virtual_page_tiles.comp turns the list into the rasterizer's tile lists (one tile per page:
// the page's orthographic projection, its square, its physical page's viewport; shaders/shared/
// virtual_page_draw_structs.h has the rules); the culling pass keeps, per page, the instances whose bounds
// overlap its square; the rasterizer clears each page's slot of the record's depth target to far and
// draws it (a triangle reaches only the pages whose lists hold its instance and, within a page, the
// 16 x 16 chunks it overlaps); virtual_page_copy.comp copies each slot into its physical page of the
// pool's image as 16-bit codes of the page's own depth range (virtual_page_structs.h, "The pool's
// texels") and writes the range into the page's entry. Pages not in the list keep their texels. The depth
// target holds one record's pages (at most kMaxVirtualPagesPerRecord), not the pool's, so a pool costs
// one image: 2 bytes a texel (4 on devices without R16_UNORM storage images).
// The image may be a pool texture that several maps share (render/virtual_page_storage.h): this pass
// then writes only its square, the rows from poolOriginY on, and neither initializes nor destroys it.
//
// The design follows the published virtual shadow maps: Timberdoodle's GPU-driven page drawing (GPU Zen 3,
// "Virtual Shadow Maps") and Unreal Engine's ("Virtual Shadow Maps" documentation: one depth range for
// the whole clipmap, cached pages redrawn only when invalidated).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "gpu/device.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"
#include "render/virtual_page_storage.h"
#include "shadows/virtual_clipmap.h"
#include "shadows/virtual_faces.h"
#include "virtual_page_draw_structs.h"
#include "virtual_page_structs.h"

namespace penumbra {

// Where a light's pages are drawn: the clipmap, the light's rotation and the depth range that every page
// shares (virtual_page_draw_structs.h).
struct VirtualPageDrawSpace {
    VirtualClipmapConfig clipmap;
    glm::mat4 lightRotationFromWorld{1.0f};  // the clipmap's space: shadows/virtual_clipmap.h clipmapRotationFromWorld
    float lsDepthNear = 1.0f;                // light-space z of depth 0
    float lsDepthFar = -1.0f;                // light-space z of depth 1
    float slopeBias = 0.0f;                  // slope-scale depth bias of every page
};

// The space of a light travelling along wsLightDirection over a scene within wsSceneBounds: the depth range
// is the bounds' light-space z range, widened by 1% of it (and 1 cm) on each side so that no caster lies
// on a plane. Fixed while the scene's bounds and the light stay: the pages stay comparable and cached.
VirtualPageDrawSpace makeVirtualPageDrawSpace(const VirtualClipmapConfig& clipmap, const glm::vec3& wsLightDirection,
                                              const Aabb& wsSceneBounds);
// The projection of global page `page` of `level` (what virtual_page_tiles.comp computes): its square to
// clip x, y in [-1, 1] (rows with light-space y), the depth range to z in [0, 1], w = 1.
glm::mat4 virtualPageClipFromWorld(const VirtualPageDrawSpace& space, uint32_t level, const glm::ivec2& page);
// The texel rectangle of page `index` of a square of pagesPerSide^2 pages of pageSize texels, row by row:
// a physical page of the pool, or a slot of a record's depth target.
gpu::Rect virtualPageRect(uint32_t index, uint32_t pagesPerSide, uint32_t pageSize);

// How many pages one record of a VirtualPageDrawPass draws: every page of a pool of poolPages up to
// kMaxVirtualPagesPerRecord, unless the culling's visible lists (cull_structs.h: each has room for every
// instance, so a list of a million instances takes 4 MB) would then take more than listBytes; then as
// many as fit, at least kMinVirtualPagesPerRecord (or the pool). The page table's draw budget (VirtualPageTablePass::
// setDrawBudget) is this: dirty pages past it wait for the next frames.
// A record draws at most kMaxVirtualPagesPerRecord pages: its depth target's slots (22^2 pages of 128^2
// texels take 31 MiB beside the default pool's 220.5 MiB image).
constexpr uint64_t kVirtualPageListBytes = 512ull << 20;  // the lists' budget: 512 MiB
constexpr uint32_t kMinVirtualPagesPerRecord = 32;
constexpr uint32_t kMaxVirtualPagesPerRecord = 484;
uint32_t virtualPagesPerRecord(uint32_t poolPages, uint32_t instanceCount, uint64_t listBytes);
// The depth target's slots per side for a record of pagesPerRecord pages: the smallest square that holds them.
uint32_t virtualDrawTargetPagesPerSide(uint32_t pagesPerRecord);
// The page table's draw budget for shadows.virtual.pagesPerFrame (0: no limit of its own) and a drawing
// pass that draws pagesPerRecord pages a record.
inline uint32_t virtualDrawBudget(uint32_t pagesPerFrame, uint32_t pagesPerRecord) {
    return pagesPerFrame == 0 ? pagesPerRecord : std::min(pagesPerFrame, pagesPerRecord);
}

struct VirtualPageDrawInputs {
    gpu::BufferHandle drawList;  // VirtualPageDrawHeader + VirtualPageDraw[] (the table pass's drawList())
    gpu::BufferSlice entries;    // the table's entries (entriesSlice()): a drawn page's depth range goes there
    const VirtualPageDrawSpace* space = nullptr;  // a clipmap's pages (else faces below)
    ShadowRasterOptions raster;                   // render.meshletCulling, shadows.lodErrorTexels
    gpu::BufferSlice faces;  // a faces' pass: faceCount VirtualFaceData (storage)
    uint32_t faceCount = 0;
};

class VirtualPageDrawPass {
public:
    // A pool of poolPagesPerSide^2 physical pages of clipmap pageSize texels (its depth buffer and image
    // start far), tile lists for as many pages; draws with `raster`, which the atlases may share. With
    // `shared` whose poolTexture is set, the image is that one (virtualPoolTextureDesc: poolSide() texels
    // wide, at least poolOriginY + poolSide() rows high: else Error), its pool the square at
    // (0, poolOriginY); without, an image of its own.
    VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                        const VirtualClipmapConfig& clipmap, uint32_t poolPagesPerSide,
                        const VirtualPageStorage* shared = nullptr);
    // The same for the pages of spot and point light faces (shadows/virtual_faces.h: a table of fixed
    // windows, level = mip * faceCount + face), an image of its own: record() then takes inputs.faces.
    VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster,
                        const VirtualFaceConfig& faces, uint32_t poolPagesPerSide);
    ~VirtualPageDrawPass();
    VirtualPageDrawPass(const VirtualPageDrawPass&) = delete;
    VirtualPageDrawPass& operator=(const VirtualPageDrawPass&) = delete;

    // Draws the pages of inputs.drawList (its count is read on the GPU, at most pagesPerRecord()); its steps are
    // the frame graph passes virtualPages.tiles, virtualPages.culling*, virtualPages/clear ... /chunks,
    // virtualPages/copy; GPU timers PREFIX/cull (tiles and culling), PREFIX/clear ... /chunks (the raster)
    // and PREFIX/copy, PREFIX virtualFacePages for faces' pages, else virtualPages. Allocates nothing.
    void record(gpu::CommandList& commands, const VirtualPageDrawInputs& inputs);

    gpu::TextureHandle poolTexture() const { return poolTexture_; }  // virtualPoolTextureDesc, left in General after a record
    uint32_t poolOriginY() const { return poolOriginY_; }            // rows: the pool's first row in poolTexture()
    gpu::BufferHandle targetDepth() const { return targetDepth_; }  // float bits per texel: the slots a record draws
    uint32_t targetPagesPerSide() const { return targetPagesPerSide_; }
    uint32_t poolSide() const { return poolPagesPerSide_ * pageSize_; }  // texels along the pool's side
    uint32_t capacity() const { return poolPagesPerSide_ * poolPagesPerSide_; }
    // The most pages one record draws (virtualPagesPerRecord for the scene and the device): the rest of
    // a longer draw list is not drawn, so the page table's draw budget must not be larger.
    uint32_t pagesPerRecord() const { return pagesPerRecord_; }
    // The last record's GPU-written lists (tests, debugging).
    gpu::BufferHandle tileList() const { return tiles_; }
    gpu::BufferHandle rasterList() const { return rasterList_; }
    const ShadowCullingPass& culling() const { return culling_; }

private:
    VirtualPageDrawPass(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster, uint32_t pageSize,
                        uint32_t pagesPerLevelSide, uint32_t poolPagesPerSide, bool faces, const VirtualPageStorage* shared);
    void useSharedTexture(const VirtualPageStorage& shared);
    void create();
    void release();
    gpu::Device& device_;
    const GpuScene& scene_;
    std::vector<gpu::DescriptorWrite> sceneWrites_;  // the scene's bindings, refreshed per record (capacity kept)
    ComputeRasterPass& raster_;
    uint32_t poolPagesPerSide_ = 0, pageSize_ = 0, pagesPerLevelSide_ = 0;
    uint32_t pagesPerRecord_ = 0, targetPagesPerSide_ = 0;
    uint32_t poolOriginY_ = 0;  // pool texture texels
    gpu::Format poolFormat_ = gpu::Format::R16Unorm;  // virtualPoolFormat, or the shared texture's
    bool ownsTexture_ = true;
    bool faces_ = false;  // spot and point light faces' pages (virtual_face_tiles.comp)
    ShadowCullingPass culling_;
    gpu::PipelineHandle tilesPipeline_, copyPipeline_;
    gpu::BufferHandle cullFrame_, tiles_, rasterList_, targetDepth_;
    gpu::TextureHandle poolTexture_;
};

}  // namespace penumbra
