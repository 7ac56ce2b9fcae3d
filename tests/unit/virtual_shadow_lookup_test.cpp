// The virtual shadow map lookup's CPU reference (src/shadows/virtual_shadow_lookup.h), on hand-made page
// tables whose answers are known analytically: a constant depth plane lit above and shadowed below, the
// fallback to a coarser level where the fine page is missing, dirty or stale, a 2 x 2 compare straddling
// two pages, single-texel occluders that pin down the texel addressing, wrap-around slots of negative
// pages, and the lit convention outside every window.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

#include "render/virtual_page_table_pass.h"
#include "shadows/virtual_page_depth.h"
#include "shadows/virtual_shadow_lookup.h"

namespace penumbra {
namespace {

using gpu_data::kVirtualPageDirty;
using gpu_data::kVirtualPageNone;
using gpu_data::kVirtualPageResident;
using gpu_data::kVirtualShadowNoLevel;

constexpr uint32_t kPoolPagesPerSide = 2;  // 4 physical pages of 8 x 8 texels
constexpr float kNear = 10.0f, kFar = -10.0f;  // light-space z of depth 0 and 1: depth = (10 - z) / 20
constexpr float kFine = 0.01f;  // a footprint finer than level 0's texels

// 8 x 8 pages of 8 texels a level; level 0 is 8 m (pages of 1 m, texels of 0.125 m), level 1 16 m, level 2 32 m.
VirtualClipmapConfig testClipmap() { return {.resolution = 64, .pageSize = 8, .levelCount = 3, .firstLevelSize = 8.0f}; }

float depthOfZ(float lsZ) { return (kNear - lsZ) / (kNear - kFar); }

// A page table and pool on the CPU, light space = world space (the light travels along -z).
struct PageRig {
    explicit PageRig(const glm::vec2& lsCamera = glm::vec2(0.5f))
        : data(packVirtualShadowLookup(testClipmap(), glm::mat4(1.0f), kNear, kFar, lsCamera, kPoolPagesPerSide)),
          entries(size_t(data.levelCount) * data.pagesPerSide * data.pagesPerSide,
                  gpu_data::VirtualPageEntry{kVirtualPageNone, 0, 0, 0, 0, 0.0f, 0.0f, 0}),
          pool(size_t(kPoolPagesPerSide * 8) * kPoolPagesPerSide * 8, 1.0f) {}

    // Global page `page` of `level` in physical page `physical`, texel (tx, ty) holding depth(tx, ty).
    void place(uint32_t level, const glm::ivec2& page, uint32_t physical, const std::function<float(int, int)>& depth,
               uint32_t flags = kVirtualPageResident) {
        const int32_t entry = virtualShadowEntryIndex(data, level, page);
        ASSERT_GE(entry, 0) << "the page is in its level's window";
        entries[size_t(entry)] = {physical, flags, page.x, page.y, 0, 0.0f, 0.0f, 0};
        const uint32_t side = kPoolPagesPerSide * 8, x0 = physical % kPoolPagesPerSide * 8, y0 = physical / kPoolPagesPerSide * 8;
        for (int ty = 0; ty < 8; ++ty)
            for (int tx = 0; tx < 8; ++tx) pool[size_t(y0 + ty) * side + x0 + tx] = depth(tx, ty);
        // As the copy pass stores a drawn page: codes of its own depth range, the range in its entry.
        codes = encodeVirtualPool(pool, side, 8);
        setVirtualPageRanges(entries, codes, kPoolPagesPerSide, 0);
    }
    void placePlane(uint32_t level, const glm::ivec2& page, uint32_t physical, float lsZ, uint32_t flags = kVirtualPageResident) {
        place(level, page, physical, [&](int, int) { return depthOfZ(lsZ); }, flags);
    }
    VirtualShadowSample at(const glm::vec3& lsPosition, float footprint = kFine) const {
        return sampleVirtualShadow(data, {entries, codes.codes}, lsPosition, footprint);
    }

    gpu_data::VirtualShadowLookupData data;
    std::vector<gpu_data::VirtualPageEntry> entries;
    std::vector<float> pool;  // the depths placed, pool texels (kPoolPagesPerSide * 8 a row)
    VirtualPoolCodes codes = encodeVirtualPool(pool, kPoolPagesPerSide * 8, 8);
};

// Level 0 texel (tx, ty)'s centre (0.125 m texels).
glm::vec2 texelCentre(float tx, float ty) { return (glm::vec2(tx, ty) + 0.5f) * 0.125f; }

TEST(VirtualShadowLookup, AConstantDepthPlaneShadowsBelowAndLightsAbove) {
    PageRig rig;
    rig.placePlane(0, {0, 0}, 1, 0.0f);  // a caster at z = 0 over page (0, 0)
    for (const glm::vec2 xy : {glm::vec2(0.3f, 0.6f), glm::vec2(0.5f), glm::vec2(0.81f, 0.2f)}) {
        const VirtualShadowSample above = rig.at(glm::vec3(xy, 0.5f)), below = rig.at(glm::vec3(xy, -0.5f));
        EXPECT_EQ(above.lit, 1.0f);
        EXPECT_EQ(below.lit, 0.0f);
        EXPECT_EQ(above.level, 0);
        EXPECT_EQ(below.level, 0);
        EXPECT_EQ(rig.at(glm::vec3(xy, 0.0f)).lit, 1.0f) << "on the plane: depth <= stored is lit";
    }
}

TEST(VirtualShadowLookup, TheFootprintChoosesTheLevel) {
    PageRig rig;
    rig.placePlane(0, {0, 0}, 0, 5.0f);  // level 0 says shadowed, level 1 lit
    rig.placePlane(1, {0, 0}, 1, -5.0f);
    EXPECT_EQ(rig.at({0.5f, 0.5f, 0.0f}).level, 0);
    EXPECT_EQ(rig.at({0.5f, 0.5f, 0.0f}).lit, 0.0f);
    const VirtualShadowSample coarse = rig.at({0.5f, 0.5f, 0.0f}, 0.3f);  // level 1's texels are 0.25 m
    EXPECT_EQ(coarse.level, 1);
    EXPECT_EQ(coarse.lit, 1.0f);
}

TEST(VirtualShadowLookup, AMissingDirtyOrStaleFinePageFallsBackToTheCoarserResidentLevel) {
    PageRig rig;
    rig.placePlane(1, {0, 0}, 2, 0.0f);  // level 1 page (0, 0) covers 0..2 m
    const glm::vec3 below(0.5f, 0.5f, -1.0f), above(0.5f, 0.5f, 1.0f);
    EXPECT_EQ(rig.at(below).level, 1) << "level 0 missing";
    EXPECT_EQ(rig.at(below).lit, 0.0f);
    EXPECT_EQ(rig.at(above).lit, 1.0f);
    rig.placePlane(0, {0, 0}, 0, -5.0f, kVirtualPageResident | kVirtualPageDirty);
    EXPECT_EQ(rig.at(below).level, 1) << "level 0 resident but not drawn yet";
    EXPECT_EQ(rig.at(below).lit, 0.0f);
    rig.placePlane(0, {0, 0}, 0, -5.0f);
    rig.entries[size_t(virtualShadowEntryIndex(rig.data, 0, {0, 0}))].pageX = 8;  // the slot holds page (8, 0)
    EXPECT_EQ(rig.at(below).level, 1) << "the slot holds another page";
    rig.entries[size_t(virtualShadowEntryIndex(rig.data, 0, {0, 0}))].pageX = 0;
    EXPECT_EQ(rig.at(below).level, 0) << "level 0 ready";
    EXPECT_EQ(rig.at(below).lit, 1.0f) << "level 0's caster lies below the receiver";
}

TEST(VirtualShadowLookup, ALookupStraddlingTwoPagesBlendsTexelsOfBoth) {
    PageRig rig;
    rig.placePlane(0, {0, 0}, 3, -5.0f);  // nothing above z = -5 in page (0, 0): lit
    rig.placePlane(0, {1, 0}, 0, 5.0f);   // a caster at z = 5 over page (1, 0): shadowed
    // Texel 7 is page (0, 0)'s last, texel 8 page (1, 0)'s first: between their centres (7.5 and 8.5 in
    // texel units) the term falls linearly from 1 to 0, the texels of both pages weighted bilinearly.
    for (const float tx : {7.25f, 7.5f, 7.75f, 8.0f, 8.25f, 8.5f, 8.75f}) {
        const glm::vec2 xy = glm::vec2(tx, 4.5f) * 0.125f;
        const VirtualShadowSample s = rig.at(glm::vec3(xy, 0.0f));
        EXPECT_EQ(s.level, 0);
        EXPECT_NEAR(s.lit, glm::clamp(8.5f - tx, 0.0f, 1.0f), 1e-6f) << "texel coordinate " << tx;
    }
    EXPECT_EQ(rig.at(glm::vec3(texelCentre(6.0f, 4.0f), 0.0f)).lit, 1.0f);
    EXPECT_EQ(rig.at(glm::vec3(texelCentre(8.0f, 4.0f), 0.0f)).lit, 0.0f);
}

TEST(VirtualShadowLookup, ATexelWhosePageIsMissingReadsTheCoarserLevel) {
    PageRig rig;
    rig.placePlane(0, {0, 0}, 3, -5.0f);  // page (1, 0) of level 0 is missing
    rig.placePlane(1, {0, 0}, 1, 5.0f);   // level 1's page holding it: shadowed
    const VirtualShadowSample s = rig.at(glm::vec3(glm::vec2(7.75f, 4.5f) * 0.125f, 0.0f));
    EXPECT_EQ(s.level, 0) << "the receiver's own page is ready";
    EXPECT_NEAR(s.lit, 0.75f, 1e-6f) << "texel 8 from level 1: shadowed, weight 0.25";
}

TEST(VirtualShadowLookup, SingleTexelOccludersPinTheTexelAddressing) {
    PageRig rig;
    // Physical page 3 (the pool's (8, 8) corner) holds level 0 page (0, 0) with one occluding texel at (3, 5).
    rig.place(0, {0, 0}, 3, [](int tx, int ty) { return tx == 3 && ty == 5 ? 0.0f : 1.0f; });
    EXPECT_EQ(rig.at(glm::vec3(texelCentre(3, 5), 0.0f)).lit, 0.0f);
    for (const glm::vec2 neighbour : {glm::vec2(2, 5), glm::vec2(4, 5), glm::vec2(3, 4), glm::vec2(3, 6), glm::vec2(5, 3)})
        EXPECT_EQ(rig.at(glm::vec3(texelCentre(neighbour.x, neighbour.y), 0.0f)).lit, 1.0f) << neighbour.x << ", " << neighbour.y;
    // Between the occluder's centre and its +x neighbour's: bilinear along x.
    EXPECT_NEAR(rig.at(glm::vec3(glm::vec2(3.8f, 5.5f) * 0.125f, 0.0f)).lit, 0.3f, 1e-5f);
    EXPECT_NEAR(rig.at(glm::vec3(glm::vec2(3.5f, 5.1f) * 0.125f, 0.0f)).lit, 0.4f, 1e-5f);
}

TEST(VirtualShadowLookup, NegativePagesUseTheirWrapAroundSlots) {
    const glm::vec2 camera(-20.3f, -13.7f);
    PageRig rig(camera);
    const VirtualClipmapConfig config = testClipmap();
    const auto data = packVirtualPageTable(config, camera, 1, 4, 2);
    for (uint32_t level = 0; level < config.levelCount; ++level) {  // the same windows as the page table's
        EXPECT_EQ(rig.data.levels[level].minPageX, data.levels[level].minPageX);
        EXPECT_EQ(rig.data.levels[level].minSlotY, data.levels[level].minSlotY);
        const ClipmapLevel placed = placeClipmapLevel(config, level, camera);
        for (int y = placed.window.min.y; y <= placed.window.max.y; ++y)
            for (int x = placed.window.min.x; x <= placed.window.max.x; ++x) {
                const glm::uvec2 slot = pageTableSlot(placed, {x, y});
                ASSERT_EQ(virtualShadowEntryIndex(rig.data, level, {x, y}), int32_t((level * 8 + slot.y) * 8 + slot.x));
            }
        EXPECT_EQ(virtualShadowEntryIndex(rig.data, level, placed.window.min - 1), -1);
        EXPECT_EQ(virtualShadowEntryIndex(rig.data, level, placed.window.max + glm::ivec2(1, 0)), -1);
    }
    const glm::ivec2 page = glm::ivec2(glm::floor(camera));  // level 0's pages are 1 m: (-21, -14)
    rig.place(0, page, 2, [](int tx, int ty) { return tx == 2 && ty == 6 ? 0.0f : 1.0f; });
    const glm::vec2 occluder = glm::vec2(page) + (glm::vec2(2, 6) + 0.5f) * 0.125f;
    EXPECT_EQ(rig.at(glm::vec3(occluder, 0.0f)).lit, 0.0f);
    EXPECT_EQ(rig.at(glm::vec3(occluder, 0.0f)).level, 0);
    EXPECT_EQ(rig.at(glm::vec3(occluder + glm::vec2(0.125f, 0.0f), 0.0f)).lit, 1.0f);
}

TEST(VirtualShadowLookup, OutsideEveryWindowOrWithNoReadyPageTheReceiverIsLit) {
    PageRig rig;
    rig.placePlane(2, {0, 0}, 0, 5.0f);  // level 2's pages are 4 m: page (0, 0) covers 0..4 m
    EXPECT_EQ(rig.at({1.0f, 1.0f, 0.0f}).level, 2);
    EXPECT_EQ(rig.at({1.0f, 1.0f, 0.0f}).lit, 0.0f);
    for (const glm::vec3 far : {glm::vec3(1000.0f, 1.0f, 0.0f), glm::vec3(-17.0f, 1.0f, 0.0f), glm::vec3(1.0f, 3e9f, 0.0f)}) {
        const VirtualShadowSample s = rig.at(far);
        EXPECT_EQ(s.lit, 1.0f) << far.x << ", " << far.y;
        EXPECT_EQ(s.level, kVirtualShadowNoLevel) << far.x << ", " << far.y;
    }
    const VirtualShadowSample noPage = rig.at({-2.0f, -2.0f, -8.0f});  // in every window, no page ready
    EXPECT_EQ(noPage.lit, 1.0f);
    EXPECT_EQ(noPage.level, kVirtualShadowNoLevel);
    // Level 2's page edge at x = 4 m (texel 8 of 0.5 m texels): at texel coordinate 7.75, texel 7 (weight
    // 0.75) shadows, texel 8 (page (1, 0) of level 2, in no level) has nothing cast.
    EXPECT_NEAR(rig.at({3.875f, 1.0f, 0.0f}).lit, 0.25f, 1e-6f);
}

// The map as the second of three sharing one entry buffer and one pool texture (render/
// virtual_page_storage.h): its entries from record firstEntry, its pool from row poolOriginY. The first
// map holds no page and an empty pool (nothing cast: far codes), the third every page of this one over a
// pool of the nearest depths, so a lookup that read their entries or rows would differ.
TEST(VirtualShadowLookup, AMapInSharedStorageReadsItsOwnEntriesAndPoolRows) {
    PageRig rig;
    rig.placePlane(0, {0, 0}, 1, 0.0f);
    rig.place(0, {1, 0}, 3, [](int tx, int ty) { return tx == 3 && ty == 5 ? 0.0f : 1.0f; });
    rig.placePlane(1, {0, 0}, 2, -5.0f);
    rig.placePlane(2, {-1, -1}, 0, 2.0f);
    const size_t count = rig.entries.size(), side = kPoolPagesPerSide * 8;
    const uint32_t firstEntry = uint32_t(count + 8), poolOriginY = uint32_t(side);  // padding after the first map
    std::vector<gpu_data::VirtualPageEntry> entries(firstEntry, gpu_data::VirtualPageEntry{kVirtualPageNone, 0, 0, 0, 0, 0.0f, 0.0f, 0});
    entries.insert(entries.end(), rig.entries.begin(), rig.entries.end());  // this map
    entries.insert(entries.end(), rig.entries.begin(), rig.entries.end());  // the third map's
    std::vector<float> texels(3 * side * side, 0.0f);  // pool texture texels, side a row: the third map's nearest
    std::fill_n(texels.begin(), side * side, 1.0f);    // the first map's: far
    std::copy(rig.pool.begin(), rig.pool.end(), texels.begin() + std::ptrdiff_t(poolOriginY * side));
    const VirtualPoolCodes codes = encodeVirtualPool(texels, uint32_t(side), 8);
    setVirtualPageRanges(std::span(entries).subspan(firstEntry, count), codes, kPoolPagesPerSide, poolOriginY);
    setVirtualPageRanges(std::span(entries).subspan(firstEntry + count), codes, kPoolPagesPerSide, 2 * poolOriginY);
    const std::vector<uint16_t>& pool = codes.codes;
    const auto packed = [&](uint32_t originY, uint32_t first) {
        return packVirtualShadowLookup(testClipmap(), glm::mat4(1.0f), kNear, kFar, glm::vec2(0.5f), kPoolPagesPerSide, originY,
                                       first);
    };
    const gpu_data::VirtualShadowLookupData shared = packed(poolOriginY, firstEntry);
    EXPECT_EQ(shared.poolOriginY, poolOriginY);
    EXPECT_EQ(shared.firstEntry, firstEntry);
    size_t points = 0, shadowed = 0, wrongRows = 0, wrongEntries = 0;
    for (float y = -1.0f; y < 3.0f; y += 0.0937f)
        for (float x = -1.0f; x < 3.0f; x += 0.0937f)
            for (const float z : {-0.5f, 0.5f})
                for (const float footprint : {kFine, 0.3f}) {
                    const glm::vec3 p(x, y, z);
                    const VirtualShadowSample alone = rig.at(p, footprint);
                    const VirtualShadowSample s = sampleVirtualShadow(shared, {entries, pool}, p, footprint);
                    ASSERT_EQ(s.lit, alone.lit) << x << ", " << y << ", " << z;
                    ASSERT_EQ(s.level, alone.level) << x << ", " << y << ", " << z;
                    ++points;
                    shadowed += alone.lit < 1.0f;
                    const VirtualShadowSample rows0 = sampleVirtualShadow(packed(0, firstEntry), {entries, pool}, p, footprint);
                    const VirtualShadowSample entries0 = sampleVirtualShadow(packed(poolOriginY, 0), {entries, pool}, p, footprint);
                    wrongRows += rows0.lit != alone.lit;
                    wrongEntries += entries0.lit != alone.lit || entries0.level != alone.level;
                }
    EXPECT_GT(shadowed, points / 20);
    EXPECT_GT(wrongRows, shadowed / 2) << "the first map's rows would light the shadowed points";
    EXPECT_GT(wrongEntries, points / 10) << "the first map's entries hold no page";
}

}  // namespace
}  // namespace penumbra
