#pragma once
// The renderer's virtual shadow maps of spot and point lights (shadows.spot.mode = virtual): every
// reserved light's faces (the plan's OtherShadowPlan::faces, shadows/virtual_faces.h) share one page table
// of fixed windows and one pool, so that the lit pass, the visibility resolve and the screen-space
// resolve bind three things whatever the light count (penumbra/shadows/virtual_shadows.glsl): the uniform
// VirtualFaceShadowData, the pool's texture and the page table's buffer. With the atlas the same
// bindings hold a disabled block and placeholders the shaders never read.
//
// A frame: beginFrame (the passes for the plan's faces, this frame's upload slot and lit block), then
// appendLitInputs before the lit writes are used, then record once the view's depth is final and before
// anything shades (mark -> page table -> draw -> mark drawn, as render/virtual_shadow_map.h; no
// readback), then stats() for the frame-end readback.
//
// Invalidation (Unreal Engine's "Virtual Shadow Maps" documentation: cached pages redrawn only when
// invalidated): a face whose projection changed (its light moved or turned, its range or the scene's
// bounds changed) has every mip redrawn; casters that moved, appeared, disappeared or changed their cast
// flag pass their old and new world bounds (casterChanged), whose pages in every face and mip
// (casterFacePageRects) are drawn again; more rectangles than one record holds, a material edit, new
// faces or shadows.virtual.cache = false redraw everything requested.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/renderer.h"
#include "penumbra/shadow_settings.h"
#include "render/main_pass.h"
#include "render/virtual_face_mark_pass.h"
#include "render/virtual_page_draw_pass.h"
#include "render/virtual_page_table_pass.h"
#include "shadows/shadow_planner.h"
#include "virtual_lit_structs.h"

namespace penumbra {

class VirtualFaceShadows {
public:
    static constexpr uint32_t kMaxInvalidations = 256;  // rectangles per record; more invalidate everything

    VirtualFaceShadows(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster);
    ~VirtualFaceShadows();
    VirtualFaceShadows(const VirtualFaceShadows&) = delete;
    VirtualFaceShadows& operator=(const VirtualFaceShadows&) = delete;

    // Before a frame is recorded: the table and pool for the plan's faces when it has any (a changed face
    // count or configuration makes new ones: every page drawn again), this frame's lit block (enabled or
    // not). A pool larger than the device holds is shrunk, with a warning.
    void beginFrame(const ShadowSettings& settings, const OtherShadowPlan& plan, const ShadowRasterOptions& raster,
                    const CameraView& view, std::vector<std::string>& warnings);
    bool active() const { return active_; }

    // The three lit bindings into inputs.writes, the pool among inputs.sampled (before its last entry,
    // which the screen-space resolve replaces) and the page table among the storage reads.
    void appendLitInputs(MainPassInputs& inputs, gpu::SamplerHandle pointSampler) const;

    // A caster's world bounds before or after an edit: its pages are drawn again by the next record.
    void casterChanged(const Aabb& wsBounds);
    // The next record draws every requested page again (a material edit, new geometry).
    void invalidateAll() { invalidateAll_ = true; }

    // Records the faces' chain for the view whose depth `depth` holds (after beginFrame of the same plan).
    // The rasterizer's counters after the pages are read back into rasterReadback (Device::readBackAtFrameEnd
    // offset).
    void record(gpu::CommandList& commands, const VirtualPageDepthSource& depth, const CameraView& view,
                uint64_t& rasterReadback);

    // A finished frame's page counts (FrameStats::virtualFacePages) set how many steps coarser than
    // faceLodBias the frames recorded next mark and read their pages (shadows/virtual_page_pool.h,
    // nextPoolPressureSteps). True when they went coarser: the pool overflowed.
    bool notePoolLoad(const VirtualPageCounts& pages);
    uint32_t poolPressureSteps() const { return active_ ? pressureSteps_ : 0u; }

    uint32_t faceCount() const { return active_ ? config_.faceCount : 0u; }
    uint32_t poolPages() const { return active_ ? config_.poolSide * config_.poolSide : 0u; }
    uint32_t pagesPerFrame() const { return active_ && table_ ? table_->drawBudget() : 0u; }  // the table's draw budget
    gpu::BufferSlice stats() const { return table_->stats(); }            // VirtualPageStats of the last record
    gpu::BufferSlice levelStats() const { return table_->levelStats(); }  // per mip (the table's buckets)
    uint32_t mipCount() const { return virtualFaceMipCount(config_.faces); }
    // Tests and debugging.
    VirtualPageTablePass* table() { return table_.get(); }
    const VirtualPageDrawPass* draw() const { return draw_.get(); }

private:
    struct Config {
        VirtualFaceConfig faces;
        uint32_t faceCount = 0, poolSide = 0, keepFrames = 0;
        bool operator==(const Config& other) const {
            return faces.resolution == other.faces.resolution && faces.pageSize == other.faces.pageSize &&
                   faceCount == other.faceCount && poolSide == other.poolSide && keepFrames == other.keepFrames;
        }
    };
    // Byte offsets inside one upload slot (256-aligned: any uniform and storage offset alignment).
    struct SlotLayout {
        uint64_t lit = 0, mark = 0, faces = 0, lights = 0, table = 0, invalidations = 0, size = 0;
    };
    static SlotLayout slotLayout();
    void configure(const Config& config);
    // The faces whose projection changed since the last record, every mip of each, into invalidations_,
    // then the changed casters' rectangles; false when they do not fit one record.
    bool collectInvalidations();

    gpu::Device& device_;
    const GpuScene& scene_;
    ComputeRasterPass& raster_;
    std::unique_ptr<VirtualFaceMarkPass> mark_;  // made with the first faces (its pipelines too)
    std::unique_ptr<VirtualPageTablePass> table_;
    std::unique_ptr<VirtualPageDrawPass> draw_;
    Config config_;               // of the table and pool made last (faceCount 0: none)
    uint32_t lightCount_ = 0;     // this frame's lights with faces
    uint32_t pressureSteps_ = 0;  // pool pressure: steps coarser than faceLodBias (notePoolLoad)
    bool active_ = false, invalidateAll_ = false;
    ShadowRasterOptions rasterOptions_;
    float marginTexels_ = 0.0f, footprintScale_ = 1.0f;
    std::vector<VirtualFace> faces_;        // this frame's (capacity kept)
    std::vector<glm::mat4> drawnFaces_;     // each face's clipFromWorld at the last record
    std::vector<Aabb> changedBounds_;       // since the last record (capacity kept)
    std::array<gpu_data::VirtualPageInvalidation, kMaxInvalidations> invalidations_{};
    std::array<LevelPageRect, gpu_data::kVirtualPageMaxLevels> mipRects_{};
    uint32_t invalidationCount_ = 0;
    gpu::BufferHandle uploads_;  // slotCount_ slots of slotLayout().size bytes
    uint32_t slotCount_ = 0, slot_ = 0;
    gpu::TextureHandle placeholderPool_;  // 1 x 1 R32F, never written: bound with the atlas
    gpu::BufferHandle placeholderPages_;  // one VirtualPageEntry, never written
};

}  // namespace penumbra
