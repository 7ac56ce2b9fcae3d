// Virtual shadow map page marking's per-pixel rule, shared by virtual_page_mark.comp (the main view's
// depth texture) and virtual_page_mark_visibility.comp (the visibility buffer's depth): the includer
// declares its depth source, then calls markPixel with a pixel's reversed-Z depth.
// The CPU reference, shadows/virtual_page_marking.cpp, does the same per pixel; the float operations
// here follow it one for one. As in the published virtual shadow maps (Unreal Engine's "Virtual Shadow
// Maps" documentation; Timberdoodle's, GPU Zen 3), the bits are set with atomic ORs into a buffer the
// pass cleared first.
#ifndef PENUMBRA_VIRTUAL_PAGE_MARK_GLSL
#define PENUMBRA_VIRTUAL_PAGE_MARK_GLSL
#include "pass_bindings.h"
#include "virtual_page_structs.h"
#include "pixel_position.glsl"
#include "penumbra/shadows/virtual_clipmap.glsl"

layout(set = kPassSet, binding = kPageMarkBindingFrame, std140) uniform PageMarkBlock { VirtualPageMarkData mark; };
layout(set = kPassSet, binding = kPageMarkBindingRequests, std430) buffer PageRequestBlock { uint requestWords[]; };

void requestPage(uint level, uvec2 slot) {
    const uint bit = virtualPageBit(level, mark.pagesPerSide, slot.x, slot.y);
    const uint word = bit / 32u, mask = 1u << (bit % 32u);
    if (word >= mark.requestWordCount || (requestWords[word] & mask) != 0u) return;  // most pixels find it set
    atomicOr(requestWords[word], mask);
}

// The pages of `level` a filter around lsPosition reads, within the level's window.
void requestReceiverPages(ClipmapConfig config, uint level, vec2 lsPosition) {
    const ClipmapLevel placed = placeClipmapLevel(config, level, mark.lsCamera);
    PageRect pages = receiverPages(placed, lsPosition, mark.marginTexels);
    pages.minPage = max(pages.minPage, placed.windowMin);
    pages.maxPage = min(pages.maxPage, placed.windowMax);
    for (int y = pages.minPage.y; y <= pages.maxPage.y; ++y)
        for (int x = pages.minPage.x; x <= pages.maxPage.x; ++x) requestPage(level, pageTableSlot(config, ivec2(x, y)));
}

// Pixel p (inside mark.width x mark.height) whose reversed-Z depth is `depth` (0: nothing drawn).
void markPixel(uvec2 p, float depth) {
    if (!(depth > 0.0)) return;  // reversed Z: 0 = nothing drawn
    const vec3 wsPosition = wsPositionOfPixel(mark.worldFromClip, p, mark.width, mark.height, depth);
    const float vsDepth = -(mark.viewFromWorld * vec4(wsPosition, 1.0)).z;
    const vec2 lsPosition = (mark.lightFromWorld * vec4(wsPosition, 1.0)).xy;
    const float wsFootprint = vsDepth * mark.wsFootprintPerDepth;

    const ClipmapConfig config = ClipmapConfig(mark.resolution, mark.pagesPerSide, mark.levelCount, mark.firstLevelSize);
    const int level = levelForReceiver(config, mark.lsCamera, lsPosition, wsFootprint, mark.marginTexels);
    if (level < 0) return;  // outside the clipmap
    requestReceiverPages(config, uint(level), lsPosition);
    const uint fallback = min(uint(level) + kVirtualPageFallbackLevels, mark.levelCount - 1u);
    if (fallback != uint(level)) requestReceiverPages(config, fallback, lsPosition);  // what serves it on overflow
}
#endif
