#pragma once
// The shadow lookup into a directional light's virtual shadow map, on the CPU: the reference of
// penumbra/shadows/virtual_shadow_lookup.glsl, function for function with the same float and integer operations
// (the render tests compare the two on the same page table and pool). Change both together.
//
// Given a receiver's world position (the caller's biases applied) and its pixel's world footprint:
// - the level: levelForFootprint (shadows/virtual_clipmap.h), or the first coarser level whose page
//   holding the receiver is ready (resident, drawn: not dirty, and its slot holds that very page): a coarser
//   level serves, never a hole;
// - the shadow term: the 2 x 2 virtual texels around the receiver at that level, each compared with the
//   receiver's depth (lit when depth <= stored, the cascades' LESS_OR_EQUAL) and weighted bilinearly, as
//   hardware 2 x 2 PCF does; each texel looks up its own page, so the four may lie in different pages, and
//   a texel whose page is not ready reads the first coarser ready level's texel holding its centre;
// - conventions: a texel no level holds has nothing cast (lit); a receiver whose page no level holds (it
//   is outside every window, or no page of its levels is ready) is lit, level kVirtualShadowNoLevel.
// The spaces are shaders/shared/virtual_shadow_structs.h's (and virtual_page_draw_structs.h's, which
// draws the pages). The design follows the published virtual shadow maps: Unreal Engine's ("Virtual
// Shadow Maps" documentation: clipmap levels chosen by the pixel's footprint, a coarser resident page
// where a fine one is missing) and Timberdoodle's (GPU Zen 3, "Virtual Shadow Maps": wrap-around page
// tables read per texel).
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "shadows/virtual_clipmap.h"
#include "shadows/virtual_faces.h"
#include "virtual_page_structs.h"
#include "virtual_shadow_structs.h"

namespace penumbra {

// A CPU copy of what the lookup reads: the bound entry buffer and the pool texture, which may hold several
// maps' (render/virtual_page_storage.h): the lookup data's firstEntry and poolOriginY place this map's.
struct VirtualShadowPages {
    // At least firstEntry + levelCount * pagesPerSide^2 records; this map's by (level, slot) from firstEntry.
    std::span<const gpu_data::VirtualPageEntry> entries;
    // The pool texture's 16-bit depth codes (shadows/virtual_page_depth.h), row by row, poolPagesPerSide *
    // pageSize a row; this map's pool is the poolPagesPerSide * pageSize rows from row poolOriginY. A ready
    // page's entry holds the range that decodes its codes.
    std::span<const uint16_t> poolCodes;
};

struct VirtualShadowSample {
    float lit = 1.0f;                                 // 1 lit, 0 shadowed, bilinear in between
    int32_t level = gpu_data::kVirtualShadowNoLevel;  // the level that served the receiver
};

// The lookup's uniform data: the clipmap `config` with its windows around lsCamera (the same windows as
// packVirtualPageTable), the light's rotation, the pages' depth range, the pool's side in pages and where
// the map lies in shared storage: its pool from pool texture row poolOriginY (texels), its entries from
// record firstEntry of the entry buffer (0 and 0: a map with storage of its own).
gpu_data::VirtualShadowLookupData packVirtualShadowLookup(const VirtualClipmapConfig& config,
                                                          const glm::mat4& lightRotationFromWorld, float lsDepthNear,
                                                          float lsDepthFar, const glm::vec2& lsCamera,
                                                          uint32_t poolPagesPerSide, uint32_t poolOriginY = 0,
                                                          uint32_t firstEntry = 0);

// The entry of global page `page` of `level`, or -1 when the page is outside the level's window.
int32_t virtualShadowEntryIndex(const gpu_data::VirtualShadowLookupData& data, uint32_t level, const glm::ivec2& page);
// The physical page holding page `page` of `level` ready to sample (its entry: record data.firstEntry +
// virtualShadowEntryIndex of pages.entries), or -1.
int32_t virtualShadowReadyPage(const gpu_data::VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                               uint32_t level, const glm::ivec2& page);
// The global page holding virtual texel `texel` (floor division by pageSize, negative texels too).
glm::ivec2 virtualShadowPageOfTexel(const gpu_data::VirtualShadowLookupData& data, const glm::ivec2& texel);

// The lookup at receiver wsPosition whose pixel covers wsFootprint metres.
VirtualShadowSample sampleVirtualShadow(const gpu_data::VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                                        const glm::vec3& wsPosition, float wsFootprint);

// ---- Spot and point lights' faces (shadows/virtual_faces.h): one table of fixed windows for all of them,
// level = mip * faceCount + face. The same rules per receiver: the face that holds it (a point light's
// face of the major axis), its footprint's mip or the first coarser ready one, the 2 x 2 bilinear compare
// of that mip's texels around it (a texel of a page not ready reads the next coarser ready mip's), the
// receiver's depth the face's perspective depth; behind the light or outside the face: lit, no level.

// The lookup data of a faces' table of faceCount faces (faceCount > 0; its own storage).
gpu_data::VirtualShadowLookupData packVirtualFaceLookup(const VirtualFaceConfig& config, uint32_t faceCount,
                                                        uint32_t poolPagesPerSide);
// The lookup at receiver wsPosition (biases applied) of `light`, whose pixel covers wsFootprint metres.
VirtualShadowSample sampleVirtualFace(const gpu_data::VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                                      std::span<const VirtualFace> faces, const VirtualFaceLight& light,
                                      const glm::vec3& wsPosition, float wsFootprint);

}  // namespace penumbra
