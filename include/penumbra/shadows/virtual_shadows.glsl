// Directional shadows from the lights' virtual shadow maps (shadows.directional.mode = virtual), for the
// lit pass, the visibility resolve and the screen-space resolve (and the bindings of the spot and point
// lights' faces, whose page table and pool the lookup's reads pick by the lookup data's faceCount): the level a receiver reads, the biases
// of bias.glsl, the tent filters of tent.glsl and PCSS (pcss.glsl), each tap a
// compare of virtual texels through the page table (virtual_shadow_lookup.glsl), so filters read across
// page borders and fall back to a coarser level where a page is missing, never into a hole.
//
// A level is treated as one shadow map whose "atlas" coordinates are its global virtual texels
// (virtualLevelFromWorld: texel x, texel y, depth; atlas size 1), so the bias and filter code is the
// cascades' own. The level is the one the marking pass requested for the pixel: levelForFootprint of
// view depth x wsFootprintPerDepth x the slot's footprint scale, or the first coarser one whose page
// holding the receiver is ready (Unreal Engine's "Virtual Shadow Maps" documentation: a clipmap level picked by the pixel's footprint).
#ifndef PENUMBRA_VIRTUAL_SHADOWS_GLSL
#define PENUMBRA_VIRTUAL_SHADOWS_GLSL
#extension GL_EXT_control_flow_attributes : require
#include "bindings.h"
#include "bias.glsl"
#include "pcss.glsl"
#include "tent.glsl"
#include "virtual_lit_structs.h"

layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtual, std140) uniform VirtualShadowBlock {
    VirtualDirectionalShadowData virtualShadows;
};
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtualPool) uniform sampler2D virtualShadowPool;
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtualPages, std430) readonly buffer VirtualPageBlock {
    VirtualPageEntry virtualPageEntries[];
};
// The spot and point lights' faces (virtual_face_shadows.glsl): their own table and pool.
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtualFaces, std140) uniform VirtualFaceBlock {
    VirtualFaceShadowData virtualFaces;
};
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtualFacePool) uniform sampler2D virtualFacePool;
layout(set = PENUMBRA_SHADOW_SET, binding = PENUMBRA_SHADOW_BINDING_BASE + kShadowBindingVirtualFacePages, std430) readonly buffer VirtualFacePageBlock {
    VirtualPageEntry virtualFacePageEntries[];
};

VirtualPageEntry virtualShadowEntry(bool faces, uint entry) {
    if (faces) {
        if (entry < uint(virtualFacePageEntries.length())) return virtualFacePageEntries[entry];
    } else if (entry < uint(virtualPageEntries.length())) {
        return virtualPageEntries[entry];
    }
    return VirtualPageEntry(kVirtualPageNone, 0u, 0, 0, 0u, 0.0, 0.0, 0u);
}

float virtualShadowPoolTexel(bool faces, ivec2 poolTexel) {
    return faces ? texelFetch(virtualFacePool, poolTexel, 0).r : texelFetch(virtualShadowPool, poolTexel, 0).r;
}

// The stored depths of the 2 x 2 pool texels from poolTexel (its lower corner) to poolTexel + 1, in the
// order (0,0) (1,0) (0,1) (1,1), of one page whose entry's range is depthRange: one gather of their
// values (textureGather gives them as (0,1) (1,1) (1,0) (0,0)), each decoded.
vec4 virtualShadowPoolGather(bool faces, ivec2 poolTexel, vec2 depthRange) {
    vec4 v;  // (0,0) (1,0) (0,1) (1,1)
    if (faces) v = textureGather(virtualFacePool, vec2(poolTexel + 1) / vec2(textureSize(virtualFacePool, 0)), 0).wzxy;
    else v = textureGather(virtualShadowPool, vec2(poolTexel + 1) / vec2(textureSize(virtualShadowPool, 0)), 0).wzxy;
    return vec4(virtualPageDecodeDepth(virtualPageCodeOfTexel(v.x), depthRange.x, depthRange.y),
                virtualPageDecodeDepth(virtualPageCodeOfTexel(v.y), depthRange.x, depthRange.y),
                virtualPageDecodeDepth(virtualPageCodeOfTexel(v.z), depthRange.x, depthRange.y),
                virtualPageDecodeDepth(virtualPageCodeOfTexel(v.w), depthRange.x, depthRange.y));
}

#include "virtual_shadow_lookup.glsl"

// The level that serves a receiver at light-space lsPosition: its footprint's level, or the first
// coarser one whose page holding it is ready (sampleVirtualShadow's rule); -1 when none is.
int virtualReceiverLevel(VirtualShadowLookupData data, vec3 lsPosition, float wsFootprint) {
    vec2 texel0 = lsPosition.xy * data.texelsPerMetre;
    ClipmapConfig config = ClipmapConfig(data.resolution, data.pagesPerSide, data.levelCount, data.firstLevelSize);
    for (uint level = levelForFootprint(config, wsFootprint); level < data.levelCount; ++level) {
        vec2 t = ldexp(texel0, ivec2(-int(level)));
        if (any(greaterThan(abs(t), vec2(kVirtualShadowMaxTexel)))) continue;
        if (virtualShadowReadyPage(data, level, virtualShadowPageOfTexel(data, ivec2(floor(t)))) >= 0) return int(level);
    }
    return -1;
}

// World -> (virtual texel x, texel y of `level`, depth in [0, 1]): the level as an orthographic shadow map
// whose atlas size is 1 (its uv are texels).
mat4 virtualLevelFromWorld(VirtualShadowLookupData data, uint level) {
    float s = ldexp(data.texelsPerMetre, -int(level)), d = data.depthPerMetre;
    mat4 texelsFromLight = mat4(vec4(s, 0.0, 0.0, 0.0), vec4(0.0, s, 0.0, 0.0), vec4(0.0, 0.0, -d, 0.0),
                                vec4(0.0, 0.0, d * data.lsDepthNear, 1.0));
    return texelsFromLight * data.lightRotationFromWorld;
}

// The bilinear-weighted depth test of the 2 x 2 texels around q (texel units), as tent.glsl's
// penumbraCompareBilinear: against one depth, or (receiver plane) against the plane's depth at each
// texel's centre (u: where the plane's depth is uvDepth.z, g: its gradient per texel).
float virtualCompareBilinear(VirtualShadowLookupData data, uint level, vec2 q, vec3 uvDepth, vec2 u, vec2 g,
                             bool perTexelPlane) {
    vec2 first = floor(q - 0.5);
    vec2 f = q - 0.5 - first;
    vec4 lit;  // (0,0) (1,0) (0,1) (1,1)
    [[dont_unroll]] for (int i = 0; i < 4; ++i) {
        ivec2 offset = ivec2(i & 1, i >> 1);
        float stored;
        if (!virtualShadowTexelDepth(data, level, ivec2(first) + offset, stored)) {
            lit[i] = 1.0;  // no level holds it: nothing cast
            continue;
        }
        float z = perTexelPlane ? uvDepth.z + dot(g, first + vec2(offset) + 0.5 - u) : uvDepth.z;
        lit[i] = z <= stored ? 1.0 : 0.0;
    }
    return mix(mix(lit.x, lit.y, f.x), mix(lit.z, lit.w, f.x), f.y);
}

// virtualCompareBilinear where every texel of the block lies in one ready page of the level, whose pool
// texel is texel + poolFromTexel and whose entry's range is depthRange: one gather, no page lookup; the
// same texels, so the same result.
float virtualCompareGathered(bool faces, ivec2 poolFromTexel, vec2 depthRange, vec2 q, vec3 uvDepth, vec2 u, vec2 g,
                             bool perTexelPlane) {
    vec2 first = floor(q - 0.5);
    vec2 f = q - 0.5 - first;
    vec4 stored = virtualShadowPoolGather(faces, ivec2(first) + poolFromTexel, depthRange);
    vec4 lit;  // (0,0) (1,0) (0,1) (1,1)
    for (int i = 0; i < 4; ++i) {
        vec2 offset = vec2(float(i & 1), float(i >> 1));
        float z = perTexelPlane ? uvDepth.z + dot(g, first + offset + 0.5 - u) : uvDepth.z;
        lit[i] = z <= stored[i] ? 1.0 : 0.0;
    }
    return mix(mix(lit.x, lit.y, f.x), mix(lit.z, lit.w, f.x), f.y);
}

// Whether a filter that reads the texels within `reach` of the one nearest u (on both axes) reads one
// ready page of the level (most receivers: a kernel of a few texels in a page of 128), and where that
// page's texels are in the pool (pool texel = texel + poolFromTexel) and its entry's depthRange.
bool virtualKernelInOnePage(VirtualShadowLookupData data, uint level, vec2 u, int reach, out ivec2 poolFromTexel,
                            out vec2 depthRange) {
    poolFromTexel = ivec2(0);
    depthRange = vec2(0.0);
    if (any(greaterThan(abs(u), vec2(kVirtualShadowMaxTexel)))) return false;
    ivec2 centre = ivec2(floor(u + 0.5));
    ivec2 page = virtualShadowPageOfTexel(data, centre - reach);
    if (page != virtualShadowPageOfTexel(data, centre + reach)) return false;
    int physical = virtualShadowReadyPage(data, level, page, depthRange);
    if (physical < 0) return false;
    poolFromTexel = virtualShadowPoolTexelOf(data, physical, page, ivec2(0));
    return true;
}

// The light's filter at uvDepth (texels, depth): one bilinear block (PCF2x2) or the tent of
// tent.glsl, whose fetch positions and weights are the cascades'. A kernel inside one ready page
// (virtualKernelInOnePage) gathers its blocks from that page; one that crosses a page border or needs a
// coarser level's texels looks every texel up.
float virtualShadowFiltered(VirtualShadowLookupData data, uint level, vec3 uvDepth, uint filterMode, vec2 g,
                            bool perTexelPlane) {
    vec2 u = uvDepth.xy;
    bool faces = data.faceCount > 0u;
    int pairs = filterMode == kShadowFilterPcf2x2 ? 0 : int(filterMode) + 1;
    ivec2 poolFromTexel;
    vec2 depthRange;
    bool onePage = virtualKernelInOnePage(data, level, u, max(pairs, 1) + 1, poolFromTexel, depthRange);
    if (pairs == 0)
        return onePage ? virtualCompareGathered(faces, poolFromTexel, depthRange, u, uvDepth, u, g, perTexelPlane)
                       : virtualCompareBilinear(data, level, u, uvDepth, u, g, perTexelPlane);
    vec4 px, wx, py, wy;
    penumbraTentFetches1D(u.x, pairs, px, wx);
    penumbraTentFetches1D(u.y, pairs, py, wy);
    float shadow = 0.0;
    if (onePage) {
        for (int y = 0; y < pairs; ++y)
            for (int x = 0; x < pairs; ++x)
                shadow += wx[x] * wy[y] * virtualCompareGathered(faces, poolFromTexel, depthRange, vec2(px[x], py[y]),
                                                                 uvDepth, u, g, perTexelPlane);
        return shadow;
    }
    // Across a page border (few receivers): the per-texel lookups, kept a loop. Unrolled, its 16 blocks of
    // 4 page-table walks were most of the lit shader's code (minutes of compiling on a CPU device).
    [[dont_unroll]] for (int i = 0; i < pairs * pairs; ++i) {
        int x = i % pairs, y = i / pairs;
        shadow += wx[x] * wy[y] * virtualCompareBilinear(data, level, vec2(px[x], py[y]), uvDepth, u, g, perTexelPlane);
    }
    return shadow;
}

// PCSS (pcss.glsl's pcssShadow) over a level: the blocker search and the filter disk read
// virtual texels; `light` turns the level's depths into distances (a clipmap's orthographic, a face's
// perspective).
float virtualShadowPcss(VirtualShadowLookupData data, uint level, ShadowLookup lookup, PcssLight light) {
    vec2 u = lookup.uvDepth.xy, g = lookup.depthGradient;
    float z = lookup.uvDepth.z;
    float searchRadius = clamp(0.5 * pcssPenumbraTexels(light, z, 0.0), 1.0, kPcssMaxRadiusTexels);
    float blockerSum = 0.0, blockers = 0.0;
    [[dont_unroll]] for (int i = 0; i < kPcssSearchSamples; ++i) {
        vec2 texel = floor(u + pcssDisk(i, kPcssSearchSamples) * searchRadius);
        float stored;
        if (!virtualShadowTexelDepth(data, level, ivec2(texel), stored)) continue;
        float isBlocker = stored < z + dot(g, texel + 0.5 - u) ? 1.0 : 0.0;
        blockerSum += isBlocker * stored;
        blockers += isBlocker;
    }
    if (blockers == 0.0) return 1.0;
    float radius = clamp(0.5 * pcssPenumbraTexels(light, z, blockerSum / blockers), 0.5, kPcssMaxRadiusTexels);
    float lit = 0.0;
    [[dont_unroll]] for (int i = 0; i < kPcssFilterSamples; ++i)
        lit += virtualCompareBilinear(data, level, u + pcssDisk(i, kPcssFilterSamples) * radius, lookup.uvDepth, u, g, true);
    return lit / float(kPcssFilterSamples);
}

// The shadow term (1 lit, 0 shadowed; before strength and fades) of directional shadow slot `slot` at
// a receiver `viewDepth` from the camera; `level` is the level that served it (-1: none, lit). filterMode:
// the light's (or the specialized constant); pcssCompiled: a constant, false where no light uses pcss
// (its blocker search and disk are then not compiled).
float sampleDirectionalVirtual(uint slot, DirectionalShadowLight light, uint biasMode, ShadowReceiver receiver,
                               float viewDepth, uint filterMode, bool pcssCompiled, out int level) {
    level = -1;
    if (slot >= virtualShadows.mapCount) return 1.0;  // a light with no map this frame: nothing cast
    VirtualShadowLookupData data = virtualShadows.maps[slot];
    vec3 lsPosition = (data.lightRotationFromWorld * vec4(receiver.wsPosition, 1.0)).xyz;
    level = virtualReceiverLevel(data, lsPosition, viewDepth * virtualShadows.wsFootprintPerDepth * virtualShadows.footprintScales[slot]);
    if (level < 0) return 1.0;
    float wsTexel = ldexp(data.firstLevelSize / float(data.resolution), level);
    ShadowBiasParams bias = ShadowBiasParams(biasMode, light.normalBias, light.slopeBias, wsTexel,
                                             normalOffsetFootprint(light.filterMode), 0.0);
    vec3 wsToLight = light.wsToLight.xyz;
    vec3 wsLookup = biasedLookupPosition(receiver, wsToLight, bias);
    ShadowLookup lookup = shadowLookup(virtualLevelFromWorld(data, uint(level)), receiver, wsLookup, wsToLight, bias, 1.0);
    if (pcssCompiled && light.pcssTanRadius > 0.0) {  // metres per unit of depth: 1 / depthPerMetre
        PcssLight pcss = PcssLight(0.0, vec4(1.0 / data.depthPerMetre, light.pcssTanRadius, wsTexel, 0.0));
        return virtualShadowPcss(data, uint(level), lookup, pcss);
    }
    return virtualShadowFiltered(data, uint(level), lookup.uvDepth, filterMode, lookup.depthGradient,
                                 lookup.perTexelPlane);
}
#endif
