// A directional light's virtual shadow map clipmap in GLSL: mirrors src/shadows/virtual_clipmap.h
// (VirtualClipmapConfig, placeClipmapLevel, pageOf, pageTableSlot, levelForFootprint, receiverPages,
// levelForReceiver) function for function, with the same float operations, so the GPU page marking
// agrees with its CPU reference (shadows/virtual_page_marking.h). Change both together.
//
// Levels are squares of `resolution` texels in the light's rotation-only space, level i firstLevelSize
// * 2^i metres wide, cut into pagesPerSide^2 pages; a level's window is the pagesPerSide pages a side
// centred on the camera's page, and a page's table slot is its coordinate modulo pagesPerSide
// (Unreal Engine's "Virtual Shadow Maps" clipmaps; Timberdoodle's wrap-around page tables, GPU Zen 3).
#ifndef PENUMBRA_VIRTUAL_CLIPMAP_GLSL
#define PENUMBRA_VIRTUAL_CLIPMAP_GLSL

struct ClipmapConfig {
    uint resolution;
    uint pagesPerSide;
    uint levelCount;
    float firstLevelSize;
};

struct ClipmapLevel {
    float lsTexelSize;  // metres per texel
    float lsPageSize;   // metres per page
    ivec2 windowMin;    // the window's first page; it spans pagesPerSide pages a side
    ivec2 windowMax;
};

// A rectangle of pages, min and max inclusive (global page coordinates).
struct PageRect {
    ivec2 minPage;
    ivec2 maxPage;
};

ivec2 pageOf(ClipmapLevel level, vec2 lsPosition) {
    return ivec2(floor(lsPosition.x / level.lsPageSize), floor(lsPosition.y / level.lsPageSize));
}

ClipmapLevel placeClipmapLevel(ClipmapConfig config, uint level, vec2 lsCamera) {
    ClipmapLevel placed;
    const float lsSize = ldexp(config.firstLevelSize, int(level));
    placed.lsTexelSize = lsSize / float(config.resolution);
    placed.lsPageSize = lsSize / float(config.pagesPerSide);
    const int halfWindow = int(config.pagesPerSide / 2u);
    placed.windowMin = pageOf(placed, lsCamera) - halfWindow;
    placed.windowMax = placed.windowMin + int(config.pagesPerSide) - 1;
    return placed;
}

// a mod n in [0, n) for negative a too (GLSL leaves % of a negative operand undefined).
uint wrapPage(int a, uint n) {
    const uint r = uint(abs(a)) % n;
    return a < 0 && r != 0u ? n - r : r;
}

// Coordinates modulo pagesPerSide, in [0, pagesPerSide), negative pages too.
uvec2 pageTableSlot(ClipmapConfig config, ivec2 page) {
    return uvec2(wrapPage(page.x, config.pagesPerSide), wrapPage(page.y, config.pagesPerSide));
}

// The finest level whose texels are no smaller than the footprint: floor(log2(footprint / level 0's
// texel)), clamped to the levels. frexp gives that exponent exactly where log2 might round.
uint levelForFootprint(ClipmapConfig config, float wsPixelFootprint) {
    const float firstTexel = config.firstLevelSize / float(config.resolution);
    if (!(wsPixelFootprint > firstTexel)) return 0u;
    int exponent;
    frexp(wsPixelFootprint / firstTexel, exponent);  // ratio = m * 2^exponent, m in [0.5, 1)
    return uint(min(exponent - 1, int(config.levelCount) - 1));
}

// The pages a filter of marginTexels around lsPosition reads.
PageRect receiverPages(ClipmapLevel level, vec2 lsPosition, float marginTexels) {
    const vec2 margin = vec2(marginTexels * level.lsTexelSize);
    return PageRect(pageOf(level, lsPosition - margin), pageOf(level, lsPosition + margin));
}

bool windowContains(ClipmapLevel level, PageRect pages) {
    return all(greaterThanEqual(pages.minPage, level.windowMin)) && all(lessThanEqual(pages.maxPage, level.windowMax));
}

// The level a receiver samples, or -1 when no level's window holds its pages.
int levelForReceiver(ClipmapConfig config, vec2 lsCamera, vec2 lsReceiver, float wsPixelFootprint, float marginTexels) {
    for (uint level = levelForFootprint(config, wsPixelFootprint); level < config.levelCount; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        if (windowContains(placed, receiverPages(placed, lsReceiver, marginTexels))) return int(level);
    }
    return -1;
}

#endif
