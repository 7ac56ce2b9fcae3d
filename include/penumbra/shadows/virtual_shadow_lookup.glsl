// The shadow lookup into a directional light's virtual shadow map: mirrors src/shadows/
// virtual_shadow_lookup.h (sampleVirtualShadow and its helpers) function for function, with the same
// float and integer operations, so the GPU agrees with its CPU reference. Change both together.
//
// The includer supplies, before the include, its two reads of the page table and the pool:
//   VirtualPageEntry virtualShadowEntry(bool faces, uint record);  // record of the bound entry buffer:
//                       // data.firstEntry + (level * pagesPerSide + slotY) * pagesPerSide + slotX
//   float virtualShadowPoolTexel(bool faces, ivec2 poolTexel);     // the pool texture's value: a 16-bit
//                       // depth code's (virtual_page_structs.h, "The pool's texels")
// `faces` (data.faceCount > 0) names the table: the spot and point lights' faces, or the directional
// lights' clipmaps, so that a shader reading both binds two tables and two pools.
// Several maps may share the entry buffer and the pool texture (render/virtual_page_storage.h): a map's
// entries start at record data.firstEntry, its pool at pool texture texel (0, data.poolOriginY).
//
// The rules (shaders/shared/virtual_shadow_structs.h has the spaces):
// - the level: levelForFootprint of the pixel's footprint, or the first coarser level whose page holding
//   the receiver is ready (resident, drawn: not dirty, and its slot holds that very page); a coarser level
//   serves, never a hole (Unreal Engine's "Virtual Shadow Maps" documentation: the clipmap falls back to a
//   coarser resident page; Timberdoodle, GPU Zen 3 "Virtual Shadow Maps");
// - the compare: the 2 x 2 texels around the receiver at that level, each compared with the receiver's
//   depth (lit when depth <= stored, as the cascades' compare) and weighted bilinearly, what
//   hardware 2 x 2 PCF does; the pool holds depth codes, so each texel is fetched, decoded with its page's
//   depth range (the page's entry) and compared here. Each texel looks
//   up its own page, so the four may come from different pages (a filter reads across page borders); a
//   texel whose page is not ready reads the texel of the first coarser ready level holding its centre;
// - conventions: a texel no level holds has nothing cast (lit); a receiver whose page no level holds is
//   lit, level kVirtualShadowNoLevel.
#ifndef PENUMBRA_VIRTUAL_SHADOW_LOOKUP_GLSL
#define PENUMBRA_VIRTUAL_SHADOW_LOOKUP_GLSL
#include "virtual_clipmap.glsl"
#include "virtual_page_structs.h"
#include "virtual_shadow_structs.h"

struct VirtualShadowSample {
    float lit;  // 1 lit, 0 shadowed, bilinear in between
    int level;  // the level that served the receiver, or kVirtualShadowNoLevel
};

// Texel coordinates beyond this are in no window (and would not fit an int).
const float kVirtualShadowMaxTexel = 1073741824.0;

// floor(a / b) for b > 0, negative a too (GLSL leaves / of negative operands loosely defined).
int virtualShadowFloorDiv(int a, int b) { return a >= 0 ? a / b : -int((uint(-a) + uint(b) - 1u) / uint(b)); }

ivec2 virtualShadowPageOfTexel(VirtualShadowLookupData data, ivec2 texel) {
    const int size = int(data.pageSize);
    return ivec2(virtualShadowFloorDiv(texel.x, size), virtualShadowFloorDiv(texel.y, size));
}

// The entry of global page `page` of `level` (virtual_page_table.glsl entryOfWindowPage), or -1 when the
// page lies outside the level's window.
int virtualShadowEntryIndex(VirtualShadowLookupData data, uint level, ivec2 page) {
    const int n = int(data.pagesPerSide);
    if (data.faceCount > 0u) {  // a faces' table of fixed windows: slot = page
        if (any(lessThan(page, ivec2(0))) || any(greaterThanEqual(page, ivec2(n)))) return -1;
        return int((level * data.pagesPerSide + uint(page.y)) * data.pagesPerSide + uint(page.x));
    }
    const VirtualPageLevelWindow window = data.levels[level];
    const ivec2 offset = page - ivec2(window.minPageX, window.minPageY);
    if (any(lessThan(offset, ivec2(0))) || any(greaterThanEqual(offset, ivec2(n)))) return -1;
    const uvec2 slot = (uvec2(offset) + uvec2(window.minSlotX, window.minSlotY)) % data.pagesPerSide;
    return int((level * data.pagesPerSide + slot.y) * data.pagesPerSide + slot.x);
}

// The physical page holding page `page` of `level` ready to sample, or -1; depthRange: its entry's
// (depthMin, depthStep), what decodes its texels.
int virtualShadowReadyPage(VirtualShadowLookupData data, uint level, ivec2 page, out vec2 depthRange) {
    depthRange = vec2(0.0);
    const int index = virtualShadowEntryIndex(data, level, page);
    if (index < 0) return -1;
    const VirtualPageEntry entry = virtualShadowEntry(data.faceCount > 0u, data.firstEntry + uint(index));
    const bool ready = (entry.flags & (kVirtualPageResident | kVirtualPageDirty)) == kVirtualPageResident &&
                       entry.pageX == page.x && entry.pageY == page.y &&
                       entry.physicalPage < data.poolPagesPerSide * data.poolPagesPerSide;
    depthRange = vec2(entry.depthMin, entry.depthStep);
    return ready ? int(entry.physicalPage) : -1;
}

int virtualShadowReadyPage(VirtualShadowLookupData data, uint level, ivec2 page) {
    vec2 depthRange;
    return virtualShadowReadyPage(data, level, page, depthRange);
}

// The pool texel of texel `texel` of global page `page` held by physical page `physical`.
ivec2 virtualShadowPoolTexelOf(VirtualShadowLookupData data, int physical, ivec2 page, ivec2 texel) {
    const int pool = int(data.poolPagesPerSide), size = int(data.pageSize);
    return ivec2(physical % pool, physical / pool) * size + ivec2(0, int(data.poolOriginY)) + texel - page * size;
}

// The stored depth of pool texel `poolTexel` of a page whose entry's range is depthRange.
float virtualShadowPoolDepth(bool faces, ivec2 poolTexel, vec2 depthRange) {
    const uint code = virtualPageCodeOfTexel(virtualShadowPoolTexel(faces, poolTexel));
    return virtualPageDecodeDepth(code, depthRange.x, depthRange.y);
}

// The stored depth of virtual texel `texel` of `level`: from its page, else from the texel holding its
// centre in the first coarser ready level (texel >> k: levels halve the texel count, and the arithmetic
// shift floors negative texels too), else nothing cast.
bool virtualShadowTexelDepth(VirtualShadowLookupData data, uint level, ivec2 texel, out float depth) {
    const uint stride = data.faceCount > 0u ? data.faceCount : 1u;  // the next coarser level (a faces' mip)
    for (uint coarser = level; coarser < data.levelCount; coarser += stride) {
        const ivec2 t = texel >> int((coarser - level) / stride);
        const ivec2 page = virtualShadowPageOfTexel(data, t);
        vec2 depthRange;
        const int physical = virtualShadowReadyPage(data, coarser, page, depthRange);
        if (physical < 0) continue;
        depth = virtualShadowPoolDepth(data.faceCount > 0u, virtualShadowPoolTexelOf(data, physical, page, t), depthRange);
        return true;
    }
    return false;
}

// 1 when the receiver at `depth` is lit by texel `texel` of `level` (depth <= stored), else 0.
float virtualShadowTexelLit(VirtualShadowLookupData data, uint level, ivec2 texel, float depth) {
    float stored;
    if (!virtualShadowTexelDepth(data, level, texel, stored)) return 1.0;
    return depth <= stored ? 1.0 : 0.0;
}

// The bilinear-weighted compare of the 2 x 2 texels of `level` around t (texel units, centres at i + 0.5).
float virtualShadowBilinearLit(VirtualShadowLookupData data, uint level, vec2 t, float depth) {
    const vec2 corner = floor(t - 0.5);  // texel (i, j) of the 2 x 2 block
    const vec2 f = t - 0.5 - corner;
    const ivec2 c = ivec2(corner);
    const float lit00 = virtualShadowTexelLit(data, level, c, depth);
    const float lit10 = virtualShadowTexelLit(data, level, c + ivec2(1, 0), depth);
    const float lit01 = virtualShadowTexelLit(data, level, c + ivec2(0, 1), depth);
    const float lit11 = virtualShadowTexelLit(data, level, c + ivec2(1, 1), depth);
    return mix(mix(lit00, lit10, f.x), mix(lit01, lit11, f.x), f.y);
}

// The receiver's light-space depth in the pages' [0, 1] (lsDepthNear to lsDepthFar).
float virtualShadowDepth(VirtualShadowLookupData data, vec3 lsPosition) {
    return (data.lsDepthNear - lsPosition.z) * data.depthPerMetre;
}

// The lookup at receiver wsPosition (the caller's biases applied) whose pixel covers wsFootprint metres.
VirtualShadowSample sampleVirtualShadow(VirtualShadowLookupData data, vec3 wsPosition, float wsFootprint) {
    const vec3 lsPosition = (data.lightRotationFromWorld * vec4(wsPosition, 1.0)).xyz;
    const float depth = virtualShadowDepth(data, lsPosition);
    const vec2 texel0 = lsPosition.xy * data.texelsPerMetre;  // level 0's texel units
    const ClipmapConfig config = ClipmapConfig(data.resolution, data.pagesPerSide, data.levelCount, data.firstLevelSize);
    for (uint level = levelForFootprint(config, wsFootprint); level < data.levelCount; ++level) {
        const vec2 t = ldexp(texel0, ivec2(-int(level)));  // exact: a power of two
        if (any(greaterThan(abs(t), vec2(kVirtualShadowMaxTexel)))) continue;
        if (virtualShadowReadyPage(data, level, virtualShadowPageOfTexel(data, ivec2(floor(t)))) < 0) continue;
        return VirtualShadowSample(virtualShadowBilinearLit(data, level, t, depth), int(level));
    }
    return VirtualShadowSample(1.0, kVirtualShadowNoLevel);
}

#endif
