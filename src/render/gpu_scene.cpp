#include "render/gpu_scene.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/error.h"
#include "cull_structs.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"
#include "penumbra/image.h"
#include "scene/meshlets.h"
#include "scene_structs.h"

namespace penumbra {

namespace {

// MaterialData.alphaMode and .shadowMode carry these enums as integers (scene_structs.h kAlpha*, kShadowMode*).
static_assert(uint32_t(AlphaMode::Opaque) == gpu_data::kAlphaOpaque && uint32_t(AlphaMode::Mask) == gpu_data::kAlphaMask &&
              uint32_t(AlphaMode::Blend) == gpu_data::kAlphaBlend);
static_assert(uint32_t(MaterialShadowMode::On) == gpu_data::kShadowModeOn &&
              uint32_t(MaterialShadowMode::Clip) == gpu_data::kShadowModeClip &&
              uint32_t(MaterialShadowMode::Dither) == gpu_data::kShadowModeDither &&
              uint32_t(MaterialShadowMode::Off) == gpu_data::kShadowModeOff);

gpu_data::InstanceData packInstance(const Scene& scene, const Instance& instance) {
    return packInstanceData(instance.worldFromObject, scene.meshes.at(instance.meshIndex).materialIndex);
}

gpu_data::MaterialData packMaterial(const Material& m) {
    gpu_data::MaterialData data{};
    data.baseColorFactor = m.baseColorFactor;
    data.metallic = m.metallic;
    data.roughness = m.roughness;
    data.alphaCutoff = m.alphaCutoff;
    uint32_t bits = 0;
    if (m.unlit) bits |= gpu_data::kMaterialUnlit;
    if (m.doubleSided) bits |= gpu_data::kMaterialDoubleSided;
    if (m.receiveShadows) bits |= gpu_data::kMaterialReceiveShadows;
    data.baseColorTexture = m.baseColorTexture >= 0 ? uint32_t(m.baseColorTexture) + 1 : 0u;
    data.flags = bits;
    data.alphaMode = uint32_t(m.alphaMode);
    data.shadowMode = uint32_t(m.shadows);
    return data;
}

gpu_data::Meshlet packMeshlet(const Meshlet& meshlet) {
    gpu_data::Meshlet packed{};
    packed.osMin = glm::vec4(meshlet.osMin, 0.0f);
    packed.osMax = glm::vec4(meshlet.osMax, 0.0f);
    packed.coneApex = glm::vec4(meshlet.coneApex, 0.0f);
    packed.coneAxis = meshlet.coneAxis;
    packed.coneCutoff = meshlet.coneCutoff;
    packed.firstTriangle = meshlet.firstTriangle;
    packed.triangleCount = meshlet.triangleCount;
    return packed;
}

// The instances a rasterizer work item takes of a mesh (cull_structs.h kRasterPackTriangles): many of a
// mesh of one small meshlet, else 1 (its items are meshlets of one instance).
uint32_t packedInstances(const MeshletMesh& mesh) {
    if (mesh.meshlets.size() != 1 || mesh.meshlets[0].triangleCount == 0) return 1;
    return std::clamp(gpu_data::kRasterPackTriangles / mesh.meshlets[0].triangleCount, 1u, gpu_data::kRasterPackInstances);
}

// The mesh's simplified levels (their meshlets after its full mesh's, from mesh.firstMeshlet) and the
// bounding sphere the rasterizer projects their errors at.
void packShadowLods(const MeshletMesh& meshlets, const Aabb& osBounds, gpu_data::CullMesh& mesh) {
    mesh.lodCount = uint32_t(std::min<size_t>(meshlets.lods.size(), gpu_data::kMaxShadowLods));
    if (osBounds.valid()) mesh.osSphere = glm::vec4(osBounds.center(), 0.5f * glm::length(osBounds.max - osBounds.min));
    for (uint32_t l = 0; l < mesh.lodCount; ++l) {
        mesh.lodFirstMeshlet[l] = mesh.firstMeshlet + meshlets.lods[l].firstMeshlet;
        mesh.lodMeshletCount[l] = meshlets.lods[l].meshletCount;
        mesh.lodError[l] = meshlets.lods[l].osError;
    }
}

gpu_data::CullInstance packCullInstance(const Instance& instance, uint32_t meshSlot) {
    gpu_data::CullInstance data{};
    // Every instance with geometry keeps its slot and bounds (the main view's rasterizer and resolve
    // read them); only casters carry the cast bit the shadow culling tests.
    const bool bounded = instance.wsBounds.valid() && meshSlot != ~0u;
    const bool casts = instance.castShadows && bounded;
    data.wsMin = glm::vec4(bounded ? instance.wsBounds.min : glm::vec3(0.0f), 0.0f);
    data.wsMax = glm::vec4(bounded ? instance.wsBounds.max : glm::vec3(0.0f), 0.0f);
    const uint32_t bits = (casts ? gpu_data::kCullInstanceCasts : 0u) | (bounded ? gpu_data::kCullInstanceBounded : 0u) |
                          (meshSlot != ~0u ? gpu_data::kCullInstanceHasMesh : 0u);
    data.meshSlot = meshSlot != ~0u ? meshSlot : 0u;
    data.flags = bits;
    return data;
}

// Sorted, deduplicated indices (sortUnique) as runs of consecutive entries: visit(position of the
// run's first index in the list, that index, run length), one copy region per run.
template <typename Visit>
void forEachRun(const std::vector<uint32_t>& sortedUnique, Visit&& visit) {
    for (size_t begin = 0; begin < sortedUnique.size();) {
        size_t end = begin + 1;
        while (end < sortedUnique.size() && sortedUnique[end] == sortedUnique[end - 1] + 1) ++end;
        visit(uint32_t(begin), sortedUnique[begin], uint32_t(end - begin));
        begin = end;
    }
}

void sortUnique(std::vector<uint32_t>& indices) {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
}

std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

void checkBufferSize(const char* what, uint64_t bytes, uint64_t maxStorageBufferRange) {
    if (bytes > maxStorageBufferRange)
        throw Error(std::string("the scene does not fit on this GPU: its ") + what + " take " + mib(bytes) +
                    ", more than the device's largest storage buffer (" + mib(maxStorageBufferRange) + ")");
}

gpu::AddressMode addressMode(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge: return gpu::AddressMode::ClampToEdge;
        case TextureWrap::MirroredRepeat: return gpu::AddressMode::MirroredRepeat;
        case TextureWrap::Repeat: break;
    }
    return gpu::AddressMode::Repeat;
}

gpu::Filter filter(TextureFilter f) { return f == TextureFilter::Nearest ? gpu::Filter::Nearest : gpu::Filter::Linear; }

}  // namespace

gpu_data::InstanceData packInstanceData(const glm::mat4& worldFromObject, uint32_t materialIndex) {
    const glm::mat4 rows = glm::transpose(worldFromObject);
    gpu_data::InstanceData data{};
    data.worldFromObjectRow0 = rows[0];
    data.worldFromObjectRow1 = rows[1];
    data.worldFromObjectRow2 = rows[2];
    data.materialIndex = materialIndex;
    return data;
}

// The Vulkan sampler that applies scene/texture_sampler.h's rule: the hardware's texel addressing is
// that rule; mipmaps only when the glTF minFilter asks for them (maxLod 0 otherwise).
gpu::SamplerDesc samplerDesc(const TextureSampler& sampler) {
    gpu::SamplerDesc desc;
    desc.filter = filter(sampler.magFilter);
    desc.minFilter = filter(sampler.minFilter);
    desc.mipmaps = sampler.mipmaps != MipmapMode::None;
    desc.mipmapFilter = sampler.mipmaps == MipmapMode::Nearest ? gpu::Filter::Nearest : gpu::Filter::Linear;
    desc.addressMode = addressMode(sampler.wrapS);
    desc.addressModeV = addressMode(sampler.wrapT);
    return desc;
}

uint64_t maxVisibleLists(uint64_t instanceCount, uint64_t maxStorageBufferRange, uint32_t maxBuffers) {
    return maxStorageBufferRange / (std::max<uint64_t>(instanceCount, 1) * sizeof(uint32_t)) * maxBuffers;
}

uint32_t visibleListBuffersOn(const gpu::Device& device) {
    return device.hasStorageBufferArrayIndexing() ? gpu_data::kVisibleListBuffers : 1u;
}

VisibleListSplit splitVisibleLists(uint64_t instanceCount, uint32_t listCount, uint64_t maxStorageBufferRange,
                                   uint32_t maxBuffers) {
    const uint64_t listBytes = std::max<uint64_t>(instanceCount, 1) * sizeof(uint32_t);
    const uint64_t perBuffer = std::min<uint64_t>(std::max(listCount, 1u), maxStorageBufferRange / listBytes);
    const uint64_t buffers = perBuffer > 0 ? (listCount + perBuffer - 1) / perBuffer : 0;
    if (std::max(listCount, 1u) > maxVisibleLists(instanceCount, maxStorageBufferRange, maxBuffers))
        throw Error("the scene does not fit on this GPU: its " + std::to_string(instanceCount) + " instances need " +
                    std::to_string(listCount) + " culling lists of " + mib(listBytes) + ", more than " +
                    std::to_string(maxBuffers) + " of the device's largest storage buffers (" +
                    mib(maxStorageBufferRange) + ") hold");
    return {uint32_t(perBuffer), uint32_t(std::max<uint64_t>(buffers, 1))};
}

void checkGpuSceneLimits(const GpuSceneTotals& totals, uint64_t maxStorageBufferRange, uint32_t visibleListBuffers) {
    if (totals.indices > UINT32_MAX)
        throw Error("the scene does not fit on the GPU: it has " + std::to_string(totals.indices) +
                    " triangle indices, more than the 2^32 - 1 that 32-bit indices address");
    if (totals.vertices > uint64_t(INT32_MAX))
        throw Error("the scene does not fit on the GPU: it has " + std::to_string(totals.vertices) +
                    " vertices, more than the 2^31 - 1 that a draw's vertex offset addresses");
    checkBufferSize("vertices", totals.vertices * sizeof(gpu_data::VertexData), maxStorageBufferRange);
    checkBufferSize("indices", totals.indices * sizeof(uint32_t), maxStorageBufferRange);
    checkBufferSize("instances", totals.instances * sizeof(gpu_data::InstanceData), maxStorageBufferRange);
    checkBufferSize("instances' culling records", totals.instances * sizeof(gpu_data::CullInstance), maxStorageBufferRange);
    checkBufferSize("materials", totals.materials * sizeof(gpu_data::MaterialData), maxStorageBufferRange);
    splitVisibleLists(totals.instances, gpu_data::kCullListCount, maxStorageBufferRange, visibleListBuffers);
}

GpuScene::GpuScene(gpu::Device& device, const Scene& scene) : device_(device) {
    try {
        create(scene);
    } catch (...) {
        destroyAll();  // no destructor runs for a half-made object
        throw;
    }
}

void GpuScene::create(const Scene& scene) {
    GpuSceneTotals totals;
    for (const Mesh& mesh : scene.meshes) {
        totals.vertices += mesh.vertices.size();
        totals.indices += mesh.indices.size();
    }
    totals.instances = scene.instances.size();
    totals.materials = std::max<size_t>(scene.materials.size(), 1);
    checkGpuSceneLimits(totals, device_.maxStorageBufferRange(), visibleListBuffersOn(device_));

    gpu::Device& device = device_;
    gpu::ComputePipelineDesc scatter;
    scatter.shader = "scene_scatter.comp";
    scatter.bindings = sceneScatterBindings();
    scatter.pushConstantSize = sizeof(gpu_data::ScatterConstants);
    scatter.debugName = "scene scatter";
    scatter_ = device.createComputePipeline(scatter);
    std::vector<gpu_data::VertexData> vertices;
    std::vector<uint32_t> indices;
    struct MeshRange { uint32_t firstIndex, indexCount; int32_t vertexOffset; };
    std::vector<MeshRange> ranges;
    // Each mesh's triangles in meshlet order (the compute rasterizers' work items; every pass draws the
    // same triangles, in this order).
    std::vector<MeshletMesh> meshletMeshes;
    for (const Mesh& mesh : scene.meshes) {
        meshletMeshes.push_back(buildMeshlets(mesh, gpu_data::kRasterBatch));
        addShadowLods(mesh, gpu_data::kRasterBatch, gpu_data::kMaxShadowLods, meshletMeshes.back());
        const std::vector<uint32_t>& meshIndices = meshletMeshes.back().indices;  // the full mesh's, then its levels'
        ranges.push_back({uint32_t(indices.size()), meshletMeshes.back().fullIndexCount, int32_t(vertices.size())});
        for (const Vertex& v : mesh.vertices)
            vertices.push_back({v.osPosition, v.uv.x, v.osNormal, v.uv.y});
        indices.insert(indices.end(), meshIndices.begin(), meshIndices.end());
    }
    checkBufferSize("indices with the shadow levels of detail", indices.size() * sizeof(uint32_t), device.maxStorageBufferRange());
    std::vector<gpu_data::InstanceData> instances;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        instances.push_back(packInstance(scene, instance));
        const MeshRange& r = ranges[instance.meshIndex];
        if (r.indexCount == 0) continue;
        draws_.push_back({i, r.firstIndex, r.indexCount, r.vertexOffset, scene.meshes[instance.meshIndex].materialIndex});
        triangles_ += r.indexCount / 3;
    }
    // Culling: a slot per mesh with geometry; its instances get consecutive places in a tile's list.
    std::vector<gpu_data::CullMesh> cullMeshes;
    std::vector<gpu_data::Meshlet> meshlets;
    meshSlotOfMesh_.assign(scene.meshes.size(), ~0u);
    for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
        if (ranges[m].indexCount == 0) continue;
        meshSlotOfMesh_[m] = uint32_t(cullMeshes.size());
        gpu_data::CullMesh mesh{};
        mesh.indexCount = ranges[m].indexCount;
        mesh.firstIndex = ranges[m].firstIndex;
        mesh.vertexOffset = int32_t(ranges[m].vertexOffset);
        mesh.materialIndex = scene.meshes[m].materialIndex;
        mesh.firstMeshlet = uint32_t(meshlets.size());
        const MeshletMesh& meshletMesh = meshletMeshes[m];
        mesh.meshletCount = uint32_t(meshletMesh.lods.empty() ? meshletMesh.meshlets.size() : meshletMesh.lods[0].firstMeshlet);
        mesh.packedInstances = packedInstances(meshletMesh);
        packShadowLods(meshletMesh, scene.meshes[m].osBounds, mesh);
        for (const Meshlet& meshlet : meshletMesh.meshlets) meshlets.push_back(packMeshlet(meshlet));
        cullMeshes.push_back(mesh);
    }
    meshletCount_ = uint32_t(meshlets.size());
    std::vector<gpu_data::CullInstance> cullInstances;
    for (const Instance& instance : scene.instances) {
        const uint32_t slot = meshSlotOfMesh_[instance.meshIndex];
        if (slot != ~0u) ++cullMeshes[slot].instanceCount;
        cullInstances.push_back(packCullInstance(instance, slot));
    }
    uint32_t firstSlot = 0;
    for (gpu_data::CullMesh& mesh : cullMeshes) {
        mesh.firstListSlot = firstSlot;
        firstSlot += mesh.instanceCount;
        mesh.firstRasterItem = rasterWorkItems_;
        hasPackedMeshes_ |= mesh.packedInstances > 1 && mesh.instanceCount > 0;
        rasterWorkItems_ += mesh.packedInstances > 1 ? (mesh.instanceCount + mesh.packedInstances - 1) / mesh.packedInstances
                                                     : mesh.instanceCount * mesh.meshletCount;
    }
    uint32_t maxTriangles = 1;
    for (const gpu_data::CullMesh& mesh : cullMeshes) maxTriangles = std::max(maxTriangles, mesh.indexCount / 3);
    triangleIdBits_ = uint32_t(std::bit_width(maxTriangles - 1u));
    const uint64_t largestId = (uint64_t(scene.instances.size()) << triangleIdBits_) + 1;
    visibilityIdsFit_ = largestId <= UINT32_MAX;
    if (cullMeshes.empty()) cullMeshes.push_back({});
    if (meshlets.empty()) meshlets.push_back({});
    if (cullInstances.empty()) cullInstances.push_back({});
    instanceCount_ = uint32_t(scene.instances.size());
    instanceDirty_.assign(scene.instances.size(), 0);
    meshSlotCount_ = uint32_t(cullMeshes.size());

    std::vector<gpu_data::MaterialData> materials;
    for (const Material& m : scene.materials) materials.push_back(packMaterial(m));
    if (materials.empty()) materials.push_back(packMaterial(Material{}));

    using gpu::MemoryKind;
    vertices_ = device.createBuffer(vertices.size() * sizeof(vertices[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                    vertices.data(), "vertices");
    indices_ = device.createBuffer(indices.size() * sizeof(uint32_t), gpu::kBufferIndex | gpu::kBufferStorage,
                                   MemoryKind::DeviceLocal, indices.data(), "indices");
    instances_ = device.createBuffer(instances.size() * sizeof(instances[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                     instances.data(), "instances");
    materials_ = device.createBuffer(materials.size() * sizeof(materials[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                     materials.data(), "materials");
    cullInstances_ = device.createBuffer(cullInstances.size() * sizeof(cullInstances[0]), gpu::kBufferStorage,
                                         MemoryKind::DeviceLocal, cullInstances.data(), "cull instances");
    cullMeshes_ = device.createBuffer(cullMeshes.size() * sizeof(cullMeshes[0]), gpu::kBufferStorage,
                                      MemoryKind::DeviceLocal, cullMeshes.data(), "cull meshes");
    meshlets_ = device.createBuffer(meshlets.size() * sizeof(meshlets[0]), gpu::kBufferStorage, MemoryKind::DeviceLocal,
                                    meshlets.data(), "meshlets");

    // Base-colour textures (sRGB, full mip chain), each with its glTF sampler. An empty scene still gets
    // one white texel so the table is never empty.
    std::vector<gpu::SamplerHandle> samplerOfTexture;
    std::vector<TextureSampler> made;  // one VkSampler per distinct sampler, samplers_[i] for made[i]
    auto upload = [&](const Image& rgba, const TextureSampler& sampler, const std::string& name) {
        gpu::TextureDesc desc{rgba.width, rgba.height, gpu::Format::RGBA8Srgb, gpu::kTextureSampled, 0,
                              "baseColor " + name};
        const gpu::TextureHandle texture = device.createTexture(desc);
        textures_.push_back(texture);  // before the upload, so a failed upload still destroys it
        device.uploadTexture(texture, rgba.pixels);
        const auto found = std::find(made.begin(), made.end(), sampler);
        if (found == made.end()) {
            made.push_back(sampler);
            samplers_.push_back(device.createSampler(samplerDesc(sampler)));
        }
        samplerOfTexture.push_back(samplers_[size_t(std::find(made.begin(), made.end(), sampler) - made.begin())]);
    };
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        const uint32_t limit = device.maxImageSize();
        if (t.rgba.width <= limit && t.rgba.height <= limit) {
            upload(t.rgba, t.sampler, t.name);
            continue;
        }
        const Image fitted = downscaleToFit(t.rgba, limit);
        warnings_.push_back("texture " + std::to_string(i) + (t.name.empty() ? "" : " '" + t.name + "'") + " is " +
                            std::to_string(t.rgba.width) + "x" + std::to_string(t.rgba.height) +
                            ", larger than the device's " + std::to_string(limit) + " texel limit: downscaled to " +
                            std::to_string(fitted.width) + "x" + std::to_string(fitted.height));
        upload(fitted, t.sampler, t.name);
    }
    if (textures_.empty()) upload(Image(1, 1, 4, 255), TextureSampler{}, "white");
    textureTable_ = device.createTextureTable(textures_, samplerOfTexture);
}

void GpuScene::destroyAll() {
    device_.destroy(textureTable_);
    for (gpu::SamplerHandle sampler : samplers_) device_.destroy(sampler);
    for (gpu::TextureHandle t : textures_) device_.destroy(t);
    for (gpu::BufferHandle b : {vertices_, indices_, instances_, materials_, cullInstances_, cullMeshes_, meshlets_})
        device_.destroy(b);
    device_.destroy(scatter_);
    scatter_ = {};
    textureTable_ = {};
    samplers_.clear();
    textures_.clear();
    vertices_ = indices_ = instances_ = materials_ = cullInstances_ = cullMeshes_ = meshlets_ = {};
}

GpuScene::~GpuScene() { destroyAll(); }

void GpuScene::updatesSubmitted() {
    for (uint32_t instance : dirtyInstances_) instanceDirty_[instance] = 0;
    dirtyInstances_.clear();
    dirtyMaterials_.clear();
}

uint64_t GpuScene::recordUpdates(gpu::CommandList& commands, const Scene& scene) {
    if (dirtyInstances_.empty() && dirtyMaterials_.empty()) return 0;
    uint64_t bytes = 0;
    // After the earlier frames' reads; the passes that read these next wait for the copies.
    gpu::ResourceUse writes[3];
    size_t count = 0;
    if (!dirtyInstances_.empty()) {
        writes[count++] = gpu::use(instances_, gpu::Usage::ComputeWrite);
        writes[count++] = gpu::use(cullInstances_, gpu::Usage::ComputeWrite);
    }
    if (!dirtyMaterials_.empty()) writes[count++] = gpu::use(materials_, gpu::Usage::TransferWrite);
    commands.pass("scene updates", std::span<const gpu::ResourceUse>(writes, count));
    if (!dirtyInstances_.empty()) bytes += scatterInstances(commands, scene);
    if (!dirtyMaterials_.empty()) {
        sortUnique(dirtyMaterials_);
        const gpu::FrameAllocation staging =
            device_.allocateFrameData(dirtyMaterials_.size() * sizeof(gpu_data::MaterialData), 16);
        auto* out = static_cast<gpu_data::MaterialData*>(staging.mapped);
        materialCopies_.clear();
        forEachRun(dirtyMaterials_, [&](uint32_t at, uint32_t first, uint32_t count) {
            for (uint32_t i = 0; i < count; ++i) out[at + i] = packMaterial(scene.materials[first + i]);
            materialCopies_.push_back({staging.slice.offset + uint64_t(at) * sizeof(gpu_data::MaterialData),
                                       uint64_t(first) * sizeof(gpu_data::MaterialData),
                                       uint64_t(count) * sizeof(gpu_data::MaterialData)});
        });
        commands.copyBufferRegions(staging.slice.buffer, materials_, materialCopies_);
        bytes += dirtyMaterials_.size() * sizeof(gpu_data::MaterialData);
    }
    return bytes;
}

// The changed instances' indices and packed records in one staging allocation (each part at a
// 256-byte offset, as descriptors bind them), written to their places by scene_scatter.comp: the CPU
// packs each changed entry once and records one dispatch, however scattered the entries are.
uint64_t GpuScene::scatterInstances(gpu::CommandList& commands, const Scene& scene) {
    const uint64_t changed = dirtyInstances_.size();
    auto aligned = [](uint64_t bytes) { return (bytes + gpu::kPortableBufferOffsetAlignment - 1) & ~(gpu::kPortableBufferOffsetAlignment - 1); };
    const uint64_t indexBytes = changed * sizeof(uint32_t), instanceBytes = changed * sizeof(gpu_data::InstanceData);
    const uint64_t cullBytes = changed * sizeof(gpu_data::CullInstance);
    const uint64_t instanceOffset = aligned(indexBytes), cullOffset = instanceOffset + aligned(instanceBytes);
    const gpu::FrameAllocation staging = device_.allocateFrameData(cullOffset + cullBytes, gpu::kPortableBufferOffsetAlignment);
    auto* base = static_cast<uint8_t*>(staging.mapped);
    std::memcpy(base, dirtyInstances_.data(), indexBytes);
    auto* instanceOut = reinterpret_cast<gpu_data::InstanceData*>(base + instanceOffset);
    auto* cullOut = reinterpret_cast<gpu_data::CullInstance*>(base + cullOffset);
    for (uint64_t i = 0; i < changed; ++i) {
        const Instance& instance = scene.instances[dirtyInstances_[i]];
        instanceOut[i] = packInstance(scene, instance);
        cullOut[i] = packCullInstance(instance, meshSlotOfMesh_[instance.meshIndex]);
    }
    using gpu::DescriptorWrite;
    const gpu::BufferSlice& slice = staging.slice;
    const DescriptorWrite writes[5] = {
        DescriptorWrite(gpu_data::kScatterBindingIndices, {slice.buffer, slice.offset, indexBytes}),
        DescriptorWrite(gpu_data::kScatterBindingInstanceData, {slice.buffer, slice.offset + instanceOffset, instanceBytes}),
        DescriptorWrite(gpu_data::kScatterBindingCullData, {slice.buffer, slice.offset + cullOffset, cullBytes}),
        DescriptorWrite(gpu_data::kScatterBindingInstances, instances_, {}, {}),
        DescriptorWrite(gpu_data::kScatterBindingCullInstances, cullInstances_, {}, {})};
    commands.bindPipeline(scatter_);
    commands.pushDescriptors(writes);
    // A dispatch covers at most 65535 groups of 64 (Vulkan's guaranteed maxComputeWorkGroupCount).
    constexpr uint64_t kPerDispatch = 65535ull * 64ull;
    for (uint64_t first = 0; first < changed; first += kPerDispatch) {
        const gpu_data::ScatterConstants constants{uint32_t(first), uint32_t(changed)};
        commands.pushConstants(&constants, sizeof(constants));
        commands.dispatch(uint32_t((std::min(changed - first, kPerDispatch) + 63) / 64), 1);
    }
    return changed * (sizeof(uint32_t) + sizeof(gpu_data::InstanceData) + sizeof(gpu_data::CullInstance));
}

void GpuScene::addSceneReads(std::vector<gpu::ResourceUse>& uses, gpu::Usage usage) const {
    for (gpu::BufferHandle buffer : {vertices_, instances_, materials_}) uses.push_back(gpu::use(buffer, usage));
}

uint32_t GpuScene::viewInstanceCount(const Scene& scene) const {
    if (viewInstances_) return *viewInstances_;
    uint32_t count = 0;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.meshIndex];
        count += meshSlotOfMesh_[instance.meshIndex] != ~0u && scene.materials[mesh.materialIndex].alphaMode != AlphaMode::Blend;
    }
    viewInstances_ = count;
    return count;
}

}  // namespace penumbra
