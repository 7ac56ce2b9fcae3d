#pragma once
// The scene on the GPU: one vertex storage buffer, one index buffer, the instance and material
// buffers and the base-colour texture table. Draws are recorded from DrawItems (one per Instance),
// which any pass (main view, shadow tiles, a future compute rasterizer) can filter. Instances and
// materials may change between frames: only the changed entries go through the frame's upload ring at
// the start of the next frame (instances packed with their indices and written to their places by
// scene_scatter.comp, one dispatch however scattered; materials by copy regions).
#include <optional>
#include <string>
#include <vector>

#include "gpu/device.h"
#include "penumbra/scene.h"
#include "cull_structs.h"
#include "scene_structs.h"

namespace penumbra {

struct DrawItem {
    uint32_t instanceIndex = 0;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t materialIndex = 0;
};

// An instance's GPU record (scene_structs.h InstanceData): the first three rows of its affine
// worldFromObject and its material; the shaders rebuild the matrix and derive the normal matrix from it.
gpu_data::InstanceData packInstanceData(const glm::mat4& worldFromObject, uint32_t materialIndex);

// What the packed scene buffers hold, checked against what the GPU layout can address.
struct GpuSceneTotals {
    uint64_t vertices = 0, indices = 0, instances = 0, materials = 0;
};
// Throws Error when the scene does not fit: more than 2^32 - 1 indices in all (32-bit firstIndex and
// index values), more than 2^31 - 1 vertices (32-bit signed vertexOffset), a packed buffer larger
// than the device's maxStorageBufferRange, or the atlases' culling lists (splitVisibleLists of
// kCullListCount lists) over visibleListBuffers buffers of that size. Per instance the GPU keeps
// 64 bytes of InstanceData and 48 of CullInstance, so on a device with the 128 MiB that Vulkan
// guarantees a scene holds up to 2^21 instances (the instance records are the first to fill a binding).
void checkGpuSceneLimits(const GpuSceneTotals& totals, uint64_t maxStorageBufferRange,
                         uint32_t visibleListBuffers = gpu_data::kVisibleListBuffers);

// How a culling pass's visible-instance lists (cull_structs.h: `listCount` lists with room for every
// instance) split over storage buffers that each fit maxStorageBufferRange: as many whole lists per
// buffer as fit, at most maxBuffers buffers (the last holds the rest). Throws Error when they need more.
struct VisibleListSplit {
    uint32_t listsPerBuffer = 1;
    uint32_t bufferCount = 1;
};
VisibleListSplit splitVisibleLists(uint64_t instanceCount, uint32_t listCount, uint64_t maxStorageBufferRange,
                                   uint32_t maxBuffers);
// The most such lists maxBuffers buffers of maxStorageBufferRange hold (what splitVisibleLists accepts).
uint64_t maxVisibleLists(uint64_t instanceCount, uint64_t maxStorageBufferRange, uint32_t maxBuffers);
// The storage buffers a device's shaders may index as one binding's array: kVisibleListBuffers, or 1.
uint32_t visibleListBuffersOn(const gpu::Device& device);
// The GPU sampler of a glTF texture sampler (filters, mipmap mode, wrap modes).
gpu::SamplerDesc samplerDesc(const TextureSampler& sampler);

class GpuScene {
public:
    // Textures larger than the device's maxImageSize are downscaled (warnings()).
    GpuScene(gpu::Device& device, const Scene& scene);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    const std::vector<DrawItem>& draws() const { return draws_; }
    gpu::BufferHandle vertexBuffer() const { return vertices_; }
    gpu::BufferHandle indexBuffer() const { return indices_; }
    gpu::BufferHandle instanceBuffer() const { return instances_; }
    gpu::BufferHandle materialBuffer() const { return materials_; }
    gpu::TextureTableHandle textureTable() const { return textureTable_; }
    // The GPU culling pass's view (cull_structs.h): per instance its bounds and mesh slot, per mesh
    // with geometry its draw and where its instances go in a tile's visible list.
    gpu::BufferHandle cullInstanceBuffer() const { return cullInstances_; }
    gpu::BufferHandle cullMeshBuffer() const { return cullMeshes_; }
    uint32_t instanceCount() const { return instanceCount_; }
    uint32_t meshSlotCount() const { return meshSlotCount_; }
    // The meshlets of every mesh (cull_structs.h Meshlet; CullMesh.firstMeshlet is a mesh's first); each
    // mesh's triangles lie in the index buffer meshlet by meshlet.
    gpu::BufferHandle meshletBuffer() const { return meshlets_; }
    // The scene buffers the shaders read through bindings 1-3 (vertices, instances, materials), as
    // frame graph uses of the given kind.
    void addSceneReads(std::vector<gpu::ResourceUse>& uses, gpu::Usage usage) const;
    uint32_t meshletCount() const { return meshletCount_; }
    // The compute rasterizer's pass 1 work items per tile: every instance x its mesh's meshlets.
    uint32_t rasterWorkItems() const { return rasterWorkItems_; }
    // Whether some mesh's instances are rasterized several to a work item (CullMesh.packedInstances > 1).
    bool hasPackedMeshes() const { return hasPackedMeshes_; }
    uint64_t triangleCount() const { return triangles_; }
    // The main view's compute rasterizer: the bits a triangle index takes in a visibility payload
    // (visibility_structs.h); visibilityIdsFit() says whether instance and triangle fit 32 bits.
    uint32_t triangleIdBits() const { return triangleIdBits_; }
    // The instances the visibility buffer may draw: with geometry and an opaque or alpha-tested material.
    // Counted once and again only after a material changed (not a walk over the instances per frame).
    uint32_t viewInstanceCount(const Scene& scene) const;
    bool visibilityIdsFit() const { return visibilityIdsFit_; }
    const std::vector<std::string>& warnings() const { return warnings_; }

    // Marks an instance or material as changed; recordUpdates uploads it.
    void instanceChanged(uint32_t instance) {
        if (instance >= instanceDirty_.size() || instanceDirty_[instance]) return;  // listed once, unsorted
        instanceDirty_[instance] = 1;
        dirtyInstances_.push_back(instance);
    }
    void materialChanged(uint32_t material) {
        dirtyMaterials_.push_back(material);
        viewInstances_.reset();  // its alpha mode may have moved instances in or out of the visibility buffer
    }
    bool hasPendingUpdates() const { return !dirtyInstances_.empty() || !dirtyMaterials_.empty(); }
    // Copies the changed entries of `scene` (between beginFrame and submitFrame); returns the bytes
    // copied. They stay marked until updatesSubmitted(), so a frame abandoned after an error loses none.
    uint64_t recordUpdates(gpu::CommandList& commands, const Scene& scene);
    void updatesSubmitted();

private:
    void create(const Scene& scene);
    uint64_t scatterInstances(gpu::CommandList& commands, const Scene& scene);
    void destroyAll();

    gpu::Device& device_;
    std::vector<DrawItem> draws_;
    uint64_t triangles_ = 0;
    gpu::BufferHandle vertices_, indices_, instances_, materials_, cullInstances_, cullMeshes_, meshlets_;
    std::vector<uint32_t> meshSlotOfMesh_;  // per Scene::meshes entry: its CullMesh slot, ~0u without geometry
    uint32_t instanceCount_ = 0, meshSlotCount_ = 0, meshletCount_ = 0, rasterWorkItems_ = 0, triangleIdBits_ = 0;
    bool visibilityIdsFit_ = true, hasPackedMeshes_ = false;
    std::vector<gpu::TextureHandle> textures_;
    std::vector<gpu::SamplerHandle> samplers_;  // one per distinct glTF sampler
    gpu::TextureTableHandle textureTable_;
    std::vector<uint32_t> dirtyInstances_, dirtyMaterials_;
    std::vector<uint8_t> instanceDirty_;  // per instance: in dirtyInstances_ (no sort per frame to drop repeats)
    std::vector<gpu::BufferCopyRegion> materialCopies_;  // recordUpdates' scratch
    gpu::PipelineHandle scatter_;  // scene_scatter.comp: the changed instances to their places
    mutable std::optional<uint32_t> viewInstances_;  // viewInstanceCount's last count
    std::vector<std::string> warnings_;
};

}  // namespace penumbra
