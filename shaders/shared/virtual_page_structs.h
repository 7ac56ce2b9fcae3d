// Virtual shadow map page marking, shared by C++ (shadows/virtual_page_marking.h, the CPU reference,
// and render/virtual_page_mark_pass) and GLSL (virtual_page_mark.comp, penumbra/shadows/virtual_clipmap.glsl); and the
// GPU page table and physical page allocator (render/virtual_page_table_pass.h, virtual_page_*.comp,
// virtual_page_table.glsl), whose CPU reference is shadows/virtual_page_pool.h.
//
// Request bits: one bit per page-table slot of every level of a directional light's clipmap
// (shadows/virtual_clipmap.h), level after level, and within a level by wrap-around slot
// y * pagesPerSide + x. Bit b lives in word b / 32 at bit b % 32.
#ifndef PENUMBRA_VIRTUAL_PAGE_STRUCTS_H
#define PENUMBRA_VIRTUAL_PAGE_STRUCTS_H
#include "gpu_shared.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

// The request bit of slot (slotX, slotY) of `level`.
PENUMBRA_INLINE uint virtualPageBit(uint level, uint pagesPerSide, uint slotX, uint slotY) {
    return (level * pagesPerSide + slotY) * pagesPerSide + slotX;
}

// What the marking pass needs of the camera, the light and the clipmap (a uniform buffer).
struct VirtualPageMarkData {
    mat4 worldFromClip;   // inverse of the camera's clipFromWorld: pixels back to world space
    mat4 viewFromWorld;   // the camera's: view depth of a pixel
    mat4 lightFromWorld;  // the light's rotation (clipmapRotationFromWorld): the clipmap's space
    vec2 lsCamera;              // (lightFromWorld * camera position).xy: where the levels are centred
    float marginTexels;         // the filter's reach around a receiver, in texels of its level
    float wsFootprintPerDepth;  // a pixel's world footprint per metre of view depth
    uint width;                 // the depth texture's size
    uint height;
    uint pagesPerSide;          // VirtualClipmapConfig: resolution / pageSize
    uint levelCount;
    float firstLevelSize;       // metres along level 0's side
    uint resolution;            // virtual texels along a level's side
    uint requestWordCount;      // words of the request bits
    uint reserved;
};
PENUMBRA_CHECK_SIZE(VirtualPageMarkData, 240)
PENUMBRA_CHECK_LAYOUT(VirtualPageMarkData, lsCamera, 192)
PENUMBRA_CHECK_LAYOUT(VirtualPageMarkData, marginTexels, 200)
PENUMBRA_CHECK_LAYOUT(VirtualPageMarkData, width, 208)
PENUMBRA_CHECK_LAYOUT(VirtualPageMarkData, firstLevelSize, 224)
PENUMBRA_CHECK_LAYOUT(VirtualPageMarkData, reserved, 236)

// ---- The page table and the physical page allocator of one directional light's clipmap.
// Entries: one per (level, wrap-around slot), indexed like the request bits (virtualPageBit). A slot
// holds whichever global page of the level's window maps to it this frame; when the window moves, the
// slot's old page is freed and the slot serves the new one (Timberdoodle's wrap-around page tables,
// GPU Zen 3 "Virtual Shadow Maps"). Storage buffers (std430) only, except VirtualPageTableData.
PENUMBRA_CONST(uint, kVirtualPageMaxLevels, 16u)      // levels of a clipmap the table holds
// Each receiver also requests its pages this many levels coarser (or in the last level): 1/64 more pages,
// allocated first (coarse levels before fine ones), so a receiver whose own page overflows the pool
// reads 8x coarser texels instead of nothing.
PENUMBRA_CONST(uint, kVirtualPageFallbackLevels, 3u)
PENUMBRA_CONST(uint, kVirtualPageMaxKeepFrames, 32u)  // keepFrames limit: one eviction age bucket per frame
PENUMBRA_CONST(uint, kVirtualPageNone, 0xFFFFFFFFu)   // no physical page, no owner entry
PENUMBRA_CONST(uint, kVirtualPageGroupSize, 64u)      // local_size_x of the passes over entries and lists
// VirtualPageEntry::flags.
PENUMBRA_CONST(uint, kVirtualPageResident, 1u)   // physicalPage holds the page (pageX, pageY)
PENUMBRA_CONST(uint, kVirtualPageDirty, 2u)      // resident, its contents must be drawn before sampling
PENUMBRA_CONST(uint, kVirtualPageRequested, 4u)  // requested this frame (the marking pass's bit)

struct VirtualPageEntry {
    uint physicalPage;   // kVirtualPageNone when not resident
    uint flags;          // kVirtualPage* bits
    int pageX;           // the global page (level's page coordinates) the slot holds or was requested for
    int pageY;
    uint lastRequested;  // the frame (VirtualPageTableData::frame) that last requested it
    float depthMin;      // the drawn page's depth codes (virtualPageDecodeDepth): written when it is drawn
    float depthStep;
    uint reserved0;
};
PENUMBRA_CHECK_SIZE(VirtualPageEntry, 32)
PENUMBRA_CHECK_LAYOUT(VirtualPageEntry, pageX, 8)
PENUMBRA_CHECK_LAYOUT(VirtualPageEntry, lastRequested, 16)
PENUMBRA_CHECK_LAYOUT(VirtualPageEntry, depthMin, 20)

// ---- The pool's texels: 16-bit depth codes relative to their page's own depth range. The pool image is
// R16_UNORM (2 bytes a texel) where the device has shaderStorageImageExtendedFormats, else R32_SFLOAT
// holding the same values (4 bytes a texel); either way texel value v stands for code round(v * 65535)
// (virtualPageCodeOfTexel), and the copy pass stores virtualPageTexelOfCode(code). When a page is drawn,
// its texels nearer than far (depth < 1) span [depthMin, depthMax]; code c in [0, kVirtualPageDepthCodeMax]
// stands for depthMin + c * depthStep, depthStep = (depthMax - depthMin) / kVirtualPageDepthCodeMax,
// rounded up (away from the light): a stored depth is never nearer than the drawn one, so quantization
// never shadows a surface that the float depths light. The error is at most one step: a 1/65534 of the
// page's own depth range (a page of casters within 10 m: 0.15 mm), not of the map's. Far texels (nothing
// cast) take kVirtualPageDepthCodeFar (texel value 1) and decode to exactly 1.
PENUMBRA_CONST(uint, kVirtualPageDepthCodeMax, 65534u)
PENUMBRA_CONST(uint, kVirtualPageDepthCodeFar, 65535u)

PENUMBRA_INLINE float virtualPageDecodeDepth(uint code, float depthMin, float depthStep) {
    return code == kVirtualPageDepthCodeFar ? 1.0f : depthMin + float(code) * depthStep;
}

// The code a pool texel's value stands for, and the value that stores a code: a quarter step above the
// code (far: exactly 1), so that an R16_UNORM store gives the code whether the conversion rounds to
// nearest (Vulkan's preference) or truncates; an R32_SFLOAT texel keeps the value, which reads back as
// the code too.
PENUMBRA_INLINE uint virtualPageCodeOfTexel(float texel) { return uint(texel * 65535.0f + 0.5f); }
PENUMBRA_INLINE float virtualPageTexelOfCode(uint code) {
    return code >= kVirtualPageDepthCodeFar ? 1.0f : (float(code) + 0.25f) / 65535.0f;
}

// A level's window this frame (ClipmapLevel::window): its first page and that page's slot.
struct VirtualPageLevelWindow {
    int minPageX;
    int minPageY;
    uint minSlotX;
    uint minSlotY;
};
PENUMBRA_CHECK_SIZE(VirtualPageLevelWindow, 16)

// One update of the table (a uniform buffer): the clipmap's windows, the pool's rules, invalidations.
//
// Two kinds of table share the steps. A clipmap's (a directional light): levelCount <= kVirtualPageMaxLevels
// levels, each with its moving window (levels[]), one level per bucket. A table of fixed windows (the mip
// chains of spot and point light faces: fixedWindows = 1): every level's window is its pages [0,
// pagesPerSide) on both axes, slot = page, levels[] unused, and up to kVirtualPageMaxLevels buckets of
// levelsPerBucket levels each (a mip of every face: level = mip * faces + face, bucket = mip).
// Counters, stats and the allocation order go by bucket (coarsest, the highest, first).
struct VirtualPageTableData {
    uint frame;              // increases by one per update; ages are frame - lastRequested
    uint levelCount;
    uint pagesPerSide;
    uint keepFrames;         // unrequested resident pages live this many frames, <= kVirtualPageMaxKeepFrames
    uint capacity;           // physical pages in the pool
    uint invalidateAll;      // 1: every resident page becomes dirty (the light changed)
    uint invalidationCount;  // VirtualPageInvalidation rectangles this update
    uint entryCount;         // levelCount * pagesPerSide^2
    uint levelsPerBucket;    // 1 for a clipmap
    uint fixedWindows;       // 1: no windows, slot = page (levels[] unused)
    uint drawBudget;         // pages one update may give the draw list (the drawing pass's lists), 1..capacity
    uint reserved1;
    VirtualPageLevelWindow levels[kVirtualPageMaxLevels];
};
PENUMBRA_CHECK_SIZE(VirtualPageTableData, 304)
PENUMBRA_CHECK_LAYOUT(VirtualPageTableData, capacity, 16)
PENUMBRA_CHECK_LAYOUT(VirtualPageTableData, levelsPerBucket, 32)
PENUMBRA_CHECK_LAYOUT(VirtualPageTableData, levels, 48)

// The resident pages of a level inside a rectangle of global pages (min and max inclusive) become
// dirty: a caster's old or new bounds (pagesTouchedByBounds).
struct VirtualPageInvalidation {
    int minPageX;
    int minPageY;
    int maxPageX;
    int maxPageY;
    uint level;
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(VirtualPageInvalidation, 32)

// What one update did: shadows/virtual_page_pool.h's VirtualPageFrame, field for field, but for the draw
// budget, which the CPU reference does not model: its toDraw is toDraw + deferred here.
struct VirtualPageStats {
    uint requested;   // pages requested
    uint cached;      // requested and already resident
    uint allocated;   // requested, not resident, given a physical page
    uint evicted;     // resident pages freed (left the window, idle past keepFrames) or given to another
    uint overflowed;  // requested pages that found no physical page (a coarser level serves them)
    uint toDraw;      // requested dirty pages on the draw list (its length): at most the draw budget
    uint resident;    // resident pages after the update
    uint deferred;    // requested dirty pages past the draw budget: they stay dirty (a coarser level serves)
};
PENUMBRA_CHECK_SIZE(VirtualPageStats, 32)

// What one update did per level: the tail of VirtualPageCounters, read back as one piece.
struct VirtualPageLevelStats {
    uint requested[kVirtualPageMaxLevels];
    uint cached[kVirtualPageMaxLevels];
    uint drawn[kVirtualPageMaxLevels];
};
PENUMBRA_CHECK_SIZE(VirtualPageLevelStats, 3 * 64)

// The counters of one update, zeroed before it. Per level bucket (coarsest first; a clipmap's buckets are
// its levels) and per eviction age
// (oldest first): how many, a cursor, and where their run starts in the allocation / eviction order.
// levelCursor and levelFirst serve the allocation (steps 2 and 4), then the draw list's order (steps 5
// and 6: the dirty pages, coarsest bucket first); levelDrawn counts a bucket's dirty pages as they are
// appended and, from step 5 on, those of them the draw list holds.
struct VirtualPageCounters {
    VirtualPageStats stats;
    uint missing;    // requested pages not resident (every level)
    uint evictable;  // resident pages not requested this frame, after freeing
    uint freeAtAllocation;  // free pages when the allocation starts (after the frees of this update)
    uint reserved;
    uint levelMissing[kVirtualPageMaxLevels];
    uint levelCursor[kVirtualPageMaxLevels];
    uint levelFirst[kVirtualPageMaxLevels];
    uint ageCount[kVirtualPageMaxKeepFrames];  // by age - 1
    uint ageCursor[kVirtualPageMaxKeepFrames];
    uint ageFirst[kVirtualPageMaxKeepFrames];
    // Per level, for the page view (VirtualPageLevelStats): requested, of them already resident, drawn.
    uint levelRequested[kVirtualPageMaxLevels];
    uint levelCached[kVirtualPageMaxLevels];
    uint levelDrawn[kVirtualPageMaxLevels];
    uvec4 allocateDispatch;  // virtual_page_allocate.comp over the missing entries (written by the plan)
};
PENUMBRA_CHECK_SIZE(VirtualPageCounters, 48 + 3 * 64 + 3 * 128 + 3 * 64 + 16)
PENUMBRA_CHECK_LAYOUT(VirtualPageCounters, levelRequested, 48 + 3 * 64 + 3 * 128)
PENUMBRA_CHECK_LAYOUT(VirtualPageCounters, missing, 32)
PENUMBRA_CHECK_LAYOUT(VirtualPageCounters, levelMissing, 48)
PENUMBRA_CHECK_LAYOUT(VirtualPageCounters, ageCount, 240)

// The free list's header; the free physical pages follow it (a stack: the last one is taken first).
struct VirtualPagePoolHeader {
    uint freeCount;
    uint capacity;
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(VirtualPagePoolHeader, 16)

// A page to draw this update: its entry (level = entry / pagesPerSide^2), physical page and global page.
struct VirtualPageDraw {
    uint entry;
    uint physicalPage;
    int pageX;
    int pageY;
};
PENUMBRA_CHECK_SIZE(VirtualPageDraw, 16)

// The draw list's header; 2 * capacity VirtualPageDraws follow it: the list (count pages, coarsest
// bucket first), then the dirty pages as the update appended them (appended of them, in any order),
// which step 6 sorts into the list up to the draw budget. pageDispatch: one workgroup per page of the
// list (the page-drawing pass's vkCmdDispatchIndirect); listDispatch: kVirtualPageGroupSize pages a
// group, over the appended pages (the list is no longer).
struct VirtualPageDrawHeader {
    uvec4 pageDispatch;  // x = count, y = z = 1
    uvec4 listDispatch;  // x = ceil(appended / kVirtualPageGroupSize), y = z = 1
    uint count;          // pages on the list: min(appended, drawBudget)
    uint appended;       // requested dirty pages this update
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(VirtualPageDrawHeader, 48)
PENUMBRA_CHECK_LAYOUT(VirtualPageDrawHeader, listDispatch, 16)
PENUMBRA_CHECK_LAYOUT(VirtualPageDrawHeader, count, 32)

PENUMBRA_GPU_NAMESPACE_END
#endif
