#include "render/pass_layouts.h"

#include "core/error.h"
#include "cull_structs.h"
#include "pass_bindings.h"

static_assert(penumbra::gpu_data::kPassSet == penumbra::gpu::kPassDescriptorSet &&
              penumbra::gpu_data::kTextureTableSet == penumbra::gpu::kTextureTableDescriptorSet);

namespace penumbra {

namespace {

using namespace gpu_data;
using gpu::BindingDesc;
constexpr gpu::DescriptorType kUniform = gpu::DescriptorType::UniformBuffer;
constexpr gpu::DescriptorType kStorage = gpu::DescriptorType::StorageBuffer;
constexpr gpu::DescriptorType kSampled = gpu::DescriptorType::SampledTexture;
constexpr uint32_t kV = gpu::kStageVertex, kF = gpu::kStageFragment, kC = gpu::kStageCompute;

// The shadow sampling's descriptors (penumbra/shadows.glsl) at the passes' kLitShadowBindingBase, from the
// table the installed GLSL documents; the light table only serves penumbraShadow, which the passes do not call.
void appendShadowSampling(std::vector<BindingDesc>& bindings, uint32_t stage) {
    for (const ShadowDescriptor& descriptor : kShadowDescriptors) {
        if (descriptor.binding == kShadowBindingLights) continue;
        const gpu::DescriptorType type = descriptor.type == ShadowDescriptorType::UniformBuffer ? kUniform
                                         : descriptor.type == ShadowDescriptorType::StorageBuffer ? kStorage
                                                                                                  : kSampled;
        bindings.push_back({descriptor.glslName, kLitShadowBindingBase + descriptor.binding, type, stage});
    }
}

// What shade_surface.glsl reads beyond the scene: lights, shadows, clusters (all in one stage).
void appendLighting(std::vector<BindingDesc>& bindings, uint32_t stage) {
    bindings.insert(bindings.end(), {{"LightBlock", kSceneBindingLights, kStorage, stage},
                                     {"screenSpaceShadows", kLitBindingScreenSpaceShadows, kSampled, stage},
                                     {"LightClusterBlock", kLitBindingLightClusters, kUniform, stage},
                                     {"ClusterMaskBlock", kLitBindingClusterMasks, kStorage, stage}});
    appendShadowSampling(bindings, stage);
}

// raster_mesh.glsl's buffers, shared by both compute rasterizers.
void appendRasterMesh(std::vector<BindingDesc>& bindings) {
    bindings.insert(bindings.end(), {{"VertexBlock", kSceneBindingVertices, kStorage, kC},
                                     {"InstanceBlock", kSceneBindingInstances, kStorage, kC},
                                     {"MaterialBlock", kSceneBindingMaterials, kStorage, kC},
                                     {"CullMeshBlock", kRasterBindingMeshes, kStorage, kC},
                                     {"IndexBlock", kRasterBindingIndices, kStorage, kC},
                                     {"CounterBlock", kRasterBindingCounters, kStorage, kC},
                                     {"LargeBlock", kRasterBindingLargePieces, kStorage, kC},
                                     {"ChunkBlock", kRasterBindingChunks, kStorage, kC},
                                     {"ListCountBlock", kRasterBindingListCounts, kStorage, kC},
                                     {"VisibleBlock", kRasterBindingVisibleInstances, kStorage, kC, kVisibleListBuffers},
                                     {"MeshletBlock", kRasterBindingMeshlets, kStorage, kC}});
}

}  // namespace

std::vector<BindingDesc> mainPassBindings(const std::string& fragmentShader) {
    if (fragmentShader == "normal_prepass.frag")
        return {{"FrameBlock", kSceneBindingFrame, kUniform, kV},
                {"VertexBlock", kSceneBindingVertices, kStorage, kV},
                {"InstanceBlock", kSceneBindingInstances, kStorage, kV | kF},
                {"MaterialBlock", kSceneBindingMaterials, kStorage, kF}};
    if (fragmentShader != "lit.frag") throw Error("internal: no main-pass bindings for '" + fragmentShader + "'");
    std::vector<BindingDesc> bindings = {{"FrameBlock", kSceneBindingFrame, kUniform, kV | kF},
                                         {"VertexBlock", kSceneBindingVertices, kStorage, kV},
                                         {"InstanceBlock", kSceneBindingInstances, kStorage, kV | kF},
                                         {"MaterialBlock", kSceneBindingMaterials, kStorage, kF}};
    appendLighting(bindings, kF);
    return bindings;
}

std::vector<BindingDesc> backgroundBindings() { return {{"FrameBlock", kSceneBindingFrame, kUniform, kF}}; }

std::vector<BindingDesc> shadowCasterBindings() {
    return {{"VertexBlock", kSceneBindingVertices, kStorage, kV},
            {"InstanceBlock", kSceneBindingInstances, kStorage, kV | kF},
            {"MaterialBlock", kSceneBindingMaterials, kStorage, kF},
            {"VisibleBlock", kCasterBindingVisibleInstances, kStorage, kV}};
}

std::vector<BindingDesc> screenSpaceShadowBindings() {
    std::vector<BindingDesc> bindings = {{"FrameBlock", kSceneBindingFrame, kUniform, kF},
                                         {"sceneDepth", kScreenShadowBindingSceneDepth, kSampled, kF},
                                         {"sceneNormals", kScreenShadowBindingSceneNormals, kSampled, kF}};
    appendShadowSampling(bindings, kF);  // the spot and point ones, which no stage reads: allowed
    return bindings;
}

std::vector<BindingDesc> shadowCullBindings() {
    return {{"CullFrameBlock", kCullBindingFrame, kUniform, kC},
            {"CullInstanceBlock", kCullBindingInstances, kStorage, kC},
            {"CullMeshBlock", kCullBindingMeshes, kStorage, kC},
            {"MaterialBlock", kCullBindingMaterials, kStorage, kC},
            {"ListCountBlock", kCullBindingListCounts, kStorage, kC},
            {"VisibleBlock", kCullBindingVisibleInstances, kStorage, kC, kVisibleListBuffers},
            {"ViewHistoryBlock", kCullBindingViewHistory, kStorage, kC},
            {"PyramidBlock", kCullBindingPyramid, kStorage, kC},
            {"TileStatsBlock", kCullBindingTileStats, kStorage, kC},
            {"CullTileBlock", kCullBindingTiles, kStorage, kC}};
}

std::vector<BindingDesc> shadowDrawsBindings() {
    return {{"CullFrameBlock", kCullBindingFrame, kUniform, kC},
            {"CullMeshBlock", kCullBindingMeshes, kStorage, kC},
            {"MaterialBlock", kCullBindingMaterials, kStorage, kC},
            {"ListCountBlock", kCullBindingListCounts, kStorage, kC},
            {"DrawBlock", kDrawsBindingDrawCommands, kStorage, kC},
            {"DrawCountBlock", kDrawsBindingDrawCounts, kStorage, kC},
            {"StatsBlock", kDrawsBindingTileStats, kStorage, kC},
            {"CullTileBlock", kCullBindingTiles, kStorage, kC}};
}

std::vector<BindingDesc> atlasCopyBindings(const std::string& shader) {
    const BindingDesc atlas{"atlas", kAtlasCopyBindingAtlas, gpu::DescriptorType::StorageTexture, kC};
    if (shader == "shadow_atlas_copy.comp") return {{"DepthBlock", kAtlasCopyBindingDepth, kStorage, kC}, atlas};
    if (shader == "shadow_atlas_resolve.comp") return {{"source", kAtlasCopyBindingSource, gpu::DescriptorType::SampledTexture, kC}, atlas};
    throw Error("internal: no atlas copy bindings for '" + shader + "'");
}

std::vector<BindingDesc> shadowRasterBindings() {
    std::vector<BindingDesc> bindings = {{"CullFrameBlock", kShadowRasterBindingCullFrame, kUniform, kC},
                                         {"DepthBlock", kShadowRasterBindingAtlasDepth, kStorage, kC},
                                         {"CullTileBlock", kShadowRasterBindingTiles, kStorage, kC},
                                         {"RasterTileBlock", kShadowRasterBindingRasterList, kStorage, kC},
                                         {"WorkBlock", kShadowRasterBindingWork, kStorage, kC}};
    appendRasterMesh(bindings);
    return bindings;
}

std::vector<BindingDesc> visibilityRasterBindings() {
    std::vector<BindingDesc> bindings = {{"FrameBlock", kSceneBindingFrame, kUniform, kC},
                                         {"VisibilityBlock", kVisibilityRasterBindingVisibility, kStorage, kC}};
    appendRasterMesh(bindings);
    return bindings;
}

std::vector<BindingDesc> rasterArgsBindings() { return {{"CounterBlock", kRasterBindingCounters, kStorage, kC}}; }

std::vector<BindingDesc> visibilityResolveBindings(gpu::ShaderStage shading) {
    const uint32_t s = shading;
    std::vector<BindingDesc> bindings = {{"FrameBlock", kSceneBindingFrame, kUniform, s},
                                         {"VertexBlock", kSceneBindingVertices, kStorage, s},
                                         {"InstanceBlock", kSceneBindingInstances, kStorage, s},
                                         {"MaterialBlock", kSceneBindingMaterials, kStorage, s}};
    appendLighting(bindings, s);
    bindings.insert(bindings.end(), {{"VisibilityBlock", kResolveBindingVisibility, kStorage, s},
                                     {"IndexBlock", kResolveBindingIndices, kStorage, s},
                                     {"CullMeshBlock", kResolveBindingMeshes, kStorage, s},
                                     {"CullInstanceBlock", kResolveBindingInstances, kStorage, s}});
    if (shading == gpu::kStageCompute)
        bindings.insert(bindings.end(), {{"resolvedColor", kResolveBindingColor, gpu::DescriptorType::StorageTexture, kC},
                                         {"DepthBlock", kResolveBindingDepth, kStorage, kC}});
    return bindings;
}

std::vector<BindingDesc> depthPyramidBindings() {
    return {{"VisibilityBlock", kPyramidBindingVisibility, kStorage, kC},
            {"PyramidBlock", kPyramidBindingTexels, kStorage, kC}};
}

std::vector<BindingDesc> lightClusterBindings() {
    return {{"LightBlock", kSceneBindingLights, kStorage, kC},
            {"LightClusterBlock", kLitBindingLightClusters, kUniform, kC},
            {"ClusterMaskBlock", kLitBindingClusterMasks, kStorage, kC},
            {"ClusterStatsBlock", kClusterBindingStats, kStorage, kC}};
}

std::vector<BindingDesc> visibleBoundsBindings() {
    return {{"VisibleBoundsBlock", kVisibleBoundsBindingData, kUniform, kC},
            {"sceneDepth", kVisibleBoundsBindingDepth, kSampled, kC},
            {"VisibleBoundsWords", kVisibleBoundsBindingWords, kStorage, kC}};
}

std::vector<BindingDesc> sceneScatterBindings() {
    return {{"ScatterIndexBlock", kScatterBindingIndices, kStorage, kC},
            {"ScatterInstanceBlock", kScatterBindingInstanceData, kStorage, kC},
            {"ScatterCullBlock", kScatterBindingCullData, kStorage, kC},
            {"SceneInstanceBlock", kScatterBindingInstances, kStorage, kC},
            {"SceneCullInstanceBlock", kScatterBindingCullInstances, kStorage, kC}};
}

std::vector<BindingDesc> virtualPageMarkBindings() {
    return {{"PageMarkBlock", kPageMarkBindingFrame, kUniform, kC},
            {"sceneDepth", kPageMarkBindingDepth, kSampled, kC},
            {"PageRequestBlock", kPageMarkBindingRequests, kStorage, kC}};
}

std::vector<BindingDesc> virtualPageMarkVisibilityBindings() {
    return {{"PageMarkBlock", kPageMarkBindingFrame, kUniform, kC},
            {"PageMarkVisibilityBlock", kPageMarkBindingVisibility, kStorage, kC},
            {"PageRequestBlock", kPageMarkBindingRequests, kStorage, kC}};
}

std::vector<BindingDesc> virtualFaceMarkBindings(bool visibility) {
    std::vector<BindingDesc> bindings = {{"FaceMarkBlock", kFaceMarkBindingFrame, kUniform, kC},
                                         {"FaceRequestBlock", kFaceMarkBindingRequests, kStorage, kC},
                                         {"FaceBlock", kFaceMarkBindingFaces, kStorage, kC},
                                         {"FaceLightBlock", kFaceMarkBindingLights, kStorage, kC}};
    if (visibility) bindings.push_back({"FaceMarkVisibilityBlock", kFaceMarkBindingVisibility, kStorage, kC});
    else bindings.push_back({"sceneDepth", kFaceMarkBindingDepth, kSampled, kC});
    return bindings;
}

std::vector<BindingDesc> virtualPageTableBindings(const std::string& shader) {
    const BindingDesc table{"PageTableBlock", kPageTableBindingFrame, kUniform, kC};
    const BindingDesc requests{"PageRequestBlock", kPageTableBindingRequests, kStorage, kC};
    const BindingDesc entries{"PageEntryBlock", kPageTableBindingEntries, kStorage, kC};
    const BindingDesc owners{"PageOwnerBlock", kPageTableBindingOwners, kStorage, kC};
    const BindingDesc pool{"PagePoolBlock", kPageTableBindingPool, kStorage, kC};
    const BindingDesc counters{"PageCounterBlock", kPageTableBindingCounters, kStorage, kC};
    const BindingDesc candidates{"PageCandidateBlock", kPageTableBindingCandidates, kStorage, kC};
    const BindingDesc draws{"PageDrawBlock", kPageTableBindingDrawList, kStorage, kC};
    const BindingDesc invalidations{"PageInvalidationBlock", kPageTableBindingInvalidations, kStorage, kC};
    const BindingDesc missing{"PageMissingBlock", kPageTableBindingMissing, kStorage, kC};
    if (shader == "virtual_page_reset.comp") return {table, entries, owners, pool};
    if (shader == "virtual_page_invalidate.comp") return {table, entries, invalidations};
    if (shader == "virtual_page_update.comp") return {table, requests, entries, owners, pool, counters, draws};
    if (shader == "virtual_page_plan.comp") return {table, pool, counters};
    if (shader == "virtual_page_requests.comp") return {table, requests, entries, counters, missing};
    if (shader == "virtual_page_candidates.comp") return {table, requests, entries, owners, counters, candidates};
    if (shader == "virtual_page_allocate.comp") return {table, entries, owners, pool, counters, candidates, draws, missing};
    if (shader == "virtual_page_finish.comp") return {table, pool, counters, draws};
    if (shader == "virtual_page_order.comp") return {table, counters, draws};
    if (shader == "virtual_page_drawn.comp") return {entries, draws};
    throw Error("internal: no virtual page table bindings for '" + shader + "'");
}

std::vector<BindingDesc> virtualPageDrawBindings(const std::string& shader) {
    const BindingDesc draws{"PageDrawBlock", kPageDrawBindingDrawList, kStorage, kC};
    const BindingDesc tiles{"CullTileBlock", kPageDrawBindingTiles, kStorage, kC};
    const BindingDesc rasterList{"RasterTileBlock", kPageDrawBindingRasterList, kStorage, kC};
    if (shader == "virtual_page_tiles.comp") return {draws, tiles, rasterList};
    if (shader == "virtual_face_tiles.comp") return {draws, tiles, rasterList, {"FaceBlock", kPageDrawBindingFaces, kStorage, kC}};
    if (shader == "virtual_page_copy.comp" || shader == "virtual_page_copy_r32f.comp")
        return {draws, {"TargetDepthBlock", kPageDrawBindingTargetDepth, kStorage, kC},
                {"poolTexture", kPageDrawBindingPoolTexture, gpu::DescriptorType::StorageTexture, kC},
                {"EntryBlock", kPageDrawBindingEntries, kStorage, kC}};
    throw Error("internal: no virtual page drawing bindings for '" + shader + "'");
}

std::vector<BindingDesc> virtualShadowProbeBindings(bool faces) {
    std::vector<BindingDesc> bindings = {{"ShadowProbeLookupBlock", kShadowProbeBindingLookup, kUniform, kC},
                                         {"ShadowProbeEntryBlock", kShadowProbeBindingEntries, kStorage, kC},
                                         {"pool", kShadowProbeBindingPool, kSampled, kC},
                                         {"ShadowProbePointBlock", kShadowProbeBindingPoints, kStorage, kC},
                                         {"ShadowProbeResultBlock", kShadowProbeBindingResults, kStorage, kC}};
    if (faces) bindings.push_back({"ShadowProbeFaceBlock", kShadowProbeBindingFaces, kStorage, kC});
    return bindings;
}

}  // namespace penumbra
