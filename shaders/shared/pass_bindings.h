// The set-0 binding number of every descriptor of every pass, by name, shared by C++ (render/pass_layouts.cpp
// declares each pass's bindings with these, its descriptor types and stage masks; the passes write their
// descriptors with them) and GLSL (`layout(set = kPassSet, binding = kSceneBindingFrame)`). Pipeline creation
// checks each declaration against the shaders' SPIR-V (src/gpu/shader_interface.h).
//
// Set 0 is pushed per pass (VK_KHR_push_descriptor); set 1 is the scene's texture table. A number means
// one thing within a pass; passes that share shader code (bindings.glsl's scene, penumbra/shadows.glsl's lighting,
// raster_mesh.glsl's rasterizer) share its numbers. The push-constant blocks are the *Constants structs of
// the other shared headers.
#ifndef PENUMBRA_PASS_BINDINGS_H
#define PENUMBRA_PASS_BINDINGS_H
#include "gpu_shared.h"
#include "penumbra/shadows/bindings.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// Descriptor sets: every pass's own bindings are pushed in set kPassSet (VK_KHR_push_descriptor); the
// scene's texture table is set kTextureTableSet (= gpu::kPassDescriptorSet / kTextureTableDescriptorSet).
PENUMBRA_CONST(uint, kPassSet, 0u)
PENUMBRA_CONST(uint, kTextureTableSet, 1u)

// The texture table (set kTextureTableSet): base colour textures, an array sized by specialization constant 0.
PENUMBRA_CONST(uint, kTextureTableBinding, 0u)

// The scene (bindings.glsl): the lit pass, its depth + normal prepass, the shadow casters, both compute
// rasterizers and the visibility resolve.
PENUMBRA_CONST(uint, kSceneBindingFrame, 0u)      // uniform FrameData (also background.frag)
PENUMBRA_CONST(uint, kSceneBindingVertices, 1u)   // VertexData[]
PENUMBRA_CONST(uint, kSceneBindingInstances, 2u)  // InstanceData[]
PENUMBRA_CONST(uint, kSceneBindingMaterials, 3u)  // MaterialData[]
PENUMBRA_CONST(uint, kSceneBindingLights, 4u)     // LightData[] (also the light cluster pass)

// Lighting (penumbra/shadows.glsl, shade_surface.glsl, light_clusters.glsl): the lit pass, the
// visibility resolve and, in part, the screen-space shadow resolve.
PENUMBRA_CONST(uint, kLitBindingScreenSpaceShadows, 9u)    // sampler2D, the screen-space resolve's output
PENUMBRA_CONST(uint, kLitBindingLightClusters, 14u)        // uniform LightClusterData (also the cluster pass)
PENUMBRA_CONST(uint, kLitBindingClusterMasks, 15u)         // the mask words (also the cluster pass)
// The shadow sampling's descriptors (penumbra/shadows/bindings.h, the installed GLSL's) from binding
// kLitShadowBindingBase on: PENUMBRA_SHADOW_BINDING_BASE of the passes that include penumbra/shadows.glsl.
PENUMBRA_CONST(uint, kLitShadowBindingBase, 32u)
PENUMBRA_CONST(uint, kLitBindingShadowView, kLitShadowBindingBase + kShadowBindingView)
PENUMBRA_CONST(uint, kLitBindingDirectionalShadows, kLitShadowBindingBase + kShadowBindingDirectional)
PENUMBRA_CONST(uint, kLitBindingDirectionalAtlas, kLitShadowBindingBase + kShadowBindingDirectionalAtlas)
PENUMBRA_CONST(uint, kLitBindingOtherShadows, kLitShadowBindingBase + kShadowBindingOther)
PENUMBRA_CONST(uint, kLitBindingOtherAtlas, kLitShadowBindingBase + kShadowBindingOtherAtlas)
// The directional lights' virtual shadow maps (shadows.directional.mode = virtual).
PENUMBRA_CONST(uint, kLitBindingVirtualShadows, kLitShadowBindingBase + kShadowBindingVirtual)
PENUMBRA_CONST(uint, kLitBindingVirtualPool, kLitShadowBindingBase + kShadowBindingVirtualPool)
PENUMBRA_CONST(uint, kLitBindingVirtualPages, kLitShadowBindingBase + kShadowBindingVirtualPages)
// The spot and point lights' virtual shadow maps (shadows.spot.mode = virtual).
PENUMBRA_CONST(uint, kLitBindingVirtualFaces, kLitShadowBindingBase + kShadowBindingVirtualFaces)
PENUMBRA_CONST(uint, kLitBindingVirtualFacePool, kLitShadowBindingBase + kShadowBindingVirtualFacePool)
PENUMBRA_CONST(uint, kLitBindingVirtualFacePages, kLitShadowBindingBase + kShadowBindingVirtualFacePages)

// The light cluster pass (light_cluster.comp), beyond the lights (4) and clusters (14, 15) above.
PENUMBRA_CONST(uint, kClusterBindingStats, 16u)  // LightClusterStats

// The screen-space shadow resolve (screen_space_shadows.frag), beyond the frame and directional lighting.
PENUMBRA_CONST(uint, kScreenShadowBindingSceneDepth, 10u)    // the prepass's depth
PENUMBRA_CONST(uint, kScreenShadowBindingSceneNormals, 11u)  // the prepass's normals

// The shadow casters (shadow_caster.vert), beyond the scene.
PENUMBRA_CONST(uint, kCasterBindingVisibleInstances, 12u)  // the culling pass's lists: the drawn tile's buffer

// Shadow-caster and main-view culling (shadow_cull.comp).
PENUMBRA_CONST(uint, kCullBindingFrame, 0u)             // uniform CullFrame
PENUMBRA_CONST(uint, kCullBindingInstances, 1u)         // CullInstance[]
PENUMBRA_CONST(uint, kCullBindingMeshes, 2u)            // CullMesh[]
PENUMBRA_CONST(uint, kCullBindingMaterials, 3u)         // MaterialData[]
PENUMBRA_CONST(uint, kCullBindingListCounts, 4u)        // per (list, mesh)
PENUMBRA_CONST(uint, kCullBindingVisibleInstances, 5u)  // the lists: kVisibleListBuffers buffers
PENUMBRA_CONST(uint, kCullBindingViewHistory, 9u)       // kView* bits per instance
PENUMBRA_CONST(uint, kCullBindingPyramid, 10u)          // the main view's depth pyramid
PENUMBRA_CONST(uint, kCullBindingTileStats, 11u)        // CullTileStats[]
PENUMBRA_CONST(uint, kCullBindingTiles, 12u)            // CullTileListHeader + CullTile[] (also shadow_draws.comp)
// The draw lists (shadow_draws.comp): the culling pass's numbers where they hold the same buffer.
PENUMBRA_CONST(uint, kDrawsBindingDrawCommands, 6u)  // VkDrawIndexedIndirectCommand[]
PENUMBRA_CONST(uint, kDrawsBindingDrawCounts, 7u)    // per (tile, caster kind)
PENUMBRA_CONST(uint, kDrawsBindingTileStats, 8u)     // CullTileStats[]

// Both compute rasterizers (raster_mesh.glsl), beyond the scene.
PENUMBRA_CONST(uint, kRasterBindingMeshes, 6u)            // CullMesh[]
PENUMBRA_CONST(uint, kRasterBindingIndices, 7u)           // the scene's index buffer
PENUMBRA_CONST(uint, kRasterBindingCounters, 9u)          // RasterCounters (also the dispatch-size pass)
PENUMBRA_CONST(uint, kRasterBindingLargePieces, 10u)      // RasterPiece[]
PENUMBRA_CONST(uint, kRasterBindingChunks, 11u)           // (large piece, chunk x | y << 16)
PENUMBRA_CONST(uint, kRasterBindingListCounts, 12u)       // the culling pass's list counts
PENUMBRA_CONST(uint, kRasterBindingVisibleInstances, 13u) // and lists (kVisibleListBuffers buffers)
PENUMBRA_CONST(uint, kRasterBindingMeshlets, 14u)         // Meshlet[]
// The shadow rasterizer (shadow_raster.glsl).
PENUMBRA_CONST(uint, kShadowRasterBindingCullFrame, 5u)   // uniform CullFrame (instance and mesh counts)
PENUMBRA_CONST(uint, kShadowRasterBindingAtlasDepth, 8u)  // depthSide^2 float bits
PENUMBRA_CONST(uint, kShadowRasterBindingTiles, 15u)      // the culling pass's CullTileListHeader + CullTile[]
PENUMBRA_CONST(uint, kShadowRasterBindingRasterList, 16u) // RasterTileListHeader + the tiles this pass draws
PENUMBRA_CONST(uint, kShadowRasterBindingWork, 17u)       // RasterWorkItem[] (pass 1's work, shadow_raster_expand.comp's)

// shadow_atlas_copy.comp (the compute rasterizer's depth buffer) and shadow_atlas_resolve.comp (the
// hardware rasterizer's depth image) -> the sampled R32F atlas, one rect per dispatch.
PENUMBRA_CONST(uint, kAtlasCopyBindingDepth, 0u)   // depthSide^2 float bits (shadow_atlas_copy.comp)
PENUMBRA_CONST(uint, kAtlasCopyBindingSource, 1u)  // sampler2D of the D32 depth target (shadow_atlas_resolve.comp)
PENUMBRA_CONST(uint, kAtlasCopyBindingAtlas, 2u)   // the atlas's R32F image (storage)
// The visibility rasterizer (visibility_raster.glsl).
PENUMBRA_CONST(uint, kVisibilityRasterBindingVisibility, 8u)  // uint64 per pixel

// The visibility resolve (visibility_surface.glsl, visibility_resolve.comp), beyond the scene and lighting.
PENUMBRA_CONST(uint, kResolveBindingVisibility, 16u)
PENUMBRA_CONST(uint, kResolveBindingIndices, 17u)
PENUMBRA_CONST(uint, kResolveBindingMeshes, 18u)     // CullMesh[]
PENUMBRA_CONST(uint, kResolveBindingInstances, 19u)  // CullInstance[] (their mesh slots)
PENUMBRA_CONST(uint, kResolveBindingColor, 20u)      // RGBA8 storage image, copied into the colour target (compute only)
PENUMBRA_CONST(uint, kResolveBindingDepth, 21u)      // float per pixel, copied into the depth target (compute only)

// The main view's depth pyramid (depth_pyramid.comp).
PENUMBRA_CONST(uint, kPyramidBindingVisibility, 0u)
PENUMBRA_CONST(uint, kPyramidBindingTexels, 1u)

// Scattered scene updates (scene_scatter.comp): the changed instances' packed records from the
// frame's staging to their places.
PENUMBRA_CONST(uint, kScatterBindingIndices, 0u)       // uint per changed instance: its index in the scene
PENUMBRA_CONST(uint, kScatterBindingInstanceData, 1u)  // InstanceData per changed instance (staging)
PENUMBRA_CONST(uint, kScatterBindingCullData, 2u)      // CullInstance per changed instance (staging)
PENUMBRA_CONST(uint, kScatterBindingInstances, 3u)     // the scene's InstanceData[]
PENUMBRA_CONST(uint, kScatterBindingCullInstances, 4u) // the scene's CullInstance[]

// The tight fit's visible-surface bounds (visible_bounds.comp, visible_bounds_structs.h).
PENUMBRA_CONST(uint, kVisibleBoundsBindingData, 0u)   // uniform VisibleBoundsData
PENUMBRA_CONST(uint, kVisibleBoundsBindingDepth, 1u)  // sampler2D, the view's depth
PENUMBRA_CONST(uint, kVisibleBoundsBindingWords, 2u)  // the kVisibleBoundsWords keys (atomics)

// Virtual shadow map page marking (virtual_page_mark.comp).
PENUMBRA_CONST(uint, kPageMarkBindingFrame, 0u)     // uniform VirtualPageMarkData
PENUMBRA_CONST(uint, kPageMarkBindingDepth, 1u)     // sampler2D, the main view's depth
PENUMBRA_CONST(uint, kPageMarkBindingRequests, 2u)  // the request bits (virtual_page_structs.h)
PENUMBRA_CONST(uint, kPageMarkBindingVisibility, 3u)  // virtual_page_mark_visibility.comp: the visibility buffer

// Spot and point lights' virtual page marking (virtual_face_mark.comp, virtual_face_mark_visibility.comp).
PENUMBRA_CONST(uint, kFaceMarkBindingFrame, 0u)       // uniform VirtualFaceMarkData
PENUMBRA_CONST(uint, kFaceMarkBindingDepth, 1u)       // sampler2D, the main view's depth
PENUMBRA_CONST(uint, kFaceMarkBindingRequests, 2u)    // the request bits of the faces' table
PENUMBRA_CONST(uint, kFaceMarkBindingVisibility, 3u)  // the visibility buffer (the _visibility variant)
PENUMBRA_CONST(uint, kFaceMarkBindingFaces, 4u)       // VirtualFaceData[]
PENUMBRA_CONST(uint, kFaceMarkBindingLights, 5u)      // VirtualFaceLightData[]

// The virtual page table and physical page allocator (virtual_page_table.glsl, virtual_page_*.comp);
// each of its shaders reads a subset (render/pass_layouts.cpp virtualPageTableBindings).
PENUMBRA_CONST(uint, kPageTableBindingFrame, 0u)          // uniform VirtualPageTableData
PENUMBRA_CONST(uint, kPageTableBindingRequests, 1u)       // the marking pass's request bits
PENUMBRA_CONST(uint, kPageTableBindingEntries, 2u)        // VirtualPageEntry per (level, slot)
PENUMBRA_CONST(uint, kPageTableBindingOwners, 3u)         // per physical page: its entry or kVirtualPageNone
PENUMBRA_CONST(uint, kPageTableBindingPool, 4u)           // VirtualPagePoolHeader + the free pages
PENUMBRA_CONST(uint, kPageTableBindingCounters, 5u)       // VirtualPageCounters of the update
PENUMBRA_CONST(uint, kPageTableBindingCandidates, 6u)     // the eviction order: entries, oldest first
PENUMBRA_CONST(uint, kPageTableBindingDrawList, 7u)       // VirtualPageDrawHeader + VirtualPageDraw[]
PENUMBRA_CONST(uint, kPageTableBindingInvalidations, 8u)  // VirtualPageInvalidation[]
PENUMBRA_CONST(uint, kPageTableBindingMissing, 9u)        // the requested entries not resident, this update

// Virtual page drawing (virtual_page_tiles.comp, virtual_page_copy.comp; render/virtual_page_draw_pass.h).
PENUMBRA_CONST(uint, kPageDrawBindingDrawList, 0u)     // VirtualPageDrawHeader + VirtualPageDraw[]
PENUMBRA_CONST(uint, kPageDrawBindingTiles, 1u)        // CullTileListHeader + CullTile[] (written)
PENUMBRA_CONST(uint, kPageDrawBindingRasterList, 2u)   // RasterTileListHeader + entries (written)
PENUMBRA_CONST(uint, kPageDrawBindingTargetDepth, 3u)  // the record's depth target, float bits per texel
PENUMBRA_CONST(uint, kPageDrawBindingPoolTexture, 4u)  // the pool's image of depth codes (R16_UNORM or R32_SFLOAT storage), sampled later
PENUMBRA_CONST(uint, kPageDrawBindingFaces, 5u)        // virtual_face_tiles.comp: VirtualFaceData[]
PENUMBRA_CONST(uint, kPageDrawBindingEntries, 6u)      // virtual_page_copy.comp: the table's entries (a drawn page's depth range)

// The virtual shadow map lookup's test probe (virtual_shadow_probe.comp, driven by
// tests/render/virtual_shadow_lookup_test.cpp).
PENUMBRA_CONST(uint, kShadowProbeBindingLookup, 0u)   // uniform VirtualShadowLookupData
PENUMBRA_CONST(uint, kShadowProbeBindingEntries, 1u)  // VirtualPageEntry per (level, slot)
PENUMBRA_CONST(uint, kShadowProbeBindingPool, 2u)     // sampler2D, the pool's R32F image (texelFetch)
PENUMBRA_CONST(uint, kShadowProbeBindingPoints, 3u)   // VirtualShadowProbePoint[]
PENUMBRA_CONST(uint, kShadowProbeBindingResults, 4u)  // VirtualShadowProbeResult[] (written)
PENUMBRA_CONST(uint, kShadowProbeBindingFaces, 5u)    // virtual_face_probe.comp: VirtualFaceData[]

// Push constants of the passes whose data has no header of its own.
struct CasterConstants {  // shadow_caster.vert
    mat4 clipFromWorld;   // the tile's
};
PENUMBRA_CHECK_SIZE(CasterConstants, 64)

struct ScreenShadowConstants {  // screen_space_shadows.frag
    uint lightSlot;             // the main light's shadowed directional slot
};
PENUMBRA_CHECK_SIZE(ScreenShadowConstants, 4)

struct ScatterConstants {  // scene_scatter.comp
    uint first;             // the first changed instance of this dispatch
    uint count;             // changed instances in all
};
PENUMBRA_CHECK_SIZE(ScatterConstants, 8)

PENUMBRA_GPU_NAMESPACE_END
#endif
