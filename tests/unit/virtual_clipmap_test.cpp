// The directional virtual shadow map's clipmap geometry (src/shadows/virtual_clipmap.h): level sizes,
// camera-centred windows snapped to whole pages, a texel grid fixed in light space, wrap-around page
// table slots, the level a receiver samples, the pages a filter or a caster touches, and the grid's turn
// about the light.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "shadows/virtual_clipmap.h"

namespace penumbra {
namespace {

// 8 pages a side: small enough to enumerate every slot.
VirtualClipmapConfig smallConfig() {
    VirtualClipmapConfig config;
    config.resolution = 1024;
    config.pageSize = 128;
    config.levelCount = 4;
    config.firstLevelSize = 2.0f;
    return config;
}

TEST(VirtualClipmap, AVerticalCastersShadowCrossesTheTexelsDiagonally) {
    // The last light points straight down: the cascades' frame takes another up vector there.
    for (const glm::vec3& wsLight : {glm::vec3(0.3f, -1.0f, 0.45f), glm::vec3(-0.9f, -0.2f, 0.1f), glm::vec3(0.0f, -0.5f, -1.0f),
                                     glm::vec3(0.0f, -1.0f, 0.0f)}) {
        const glm::vec3 forward = glm::normalize(wsLight);
        const glm::mat4 rotation = clipmapRotationFromWorld(forward);
        // A rotation (orthonormal, no mirror) whose z axis is the light's (the light travels along -z), as
        // the cascades' frame.
        const glm::mat3 r(rotation);
        const glm::mat3 identity = glm::transpose(r) * r;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
            EXPECT_NEAR(glm::vec3(rotation * glm::vec4(-forward, 0.0f))[i], i == 2 ? 1.0f : 0.0f, 1e-5f);
        }
        EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f);
        if (std::abs(forward.y) > 0.99f) continue;  // world up is the light's axis: no direction to turn
        // World up, the direction of a pole, and so of its shadow's sides: 45 degrees off both texel axes.
        const glm::vec2 lsUp = glm::normalize(glm::vec2(rotation * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));
        EXPECT_NEAR(std::abs(lsUp.x), std::sqrt(0.5f), 1e-5f) << wsLight.x;
        EXPECT_NEAR(std::abs(lsUp.y), std::sqrt(0.5f), 1e-5f) << wsLight.x;
    }
}

TEST(VirtualClipmap, LevelsDoubleInSizeAndKeepTheirTexelCount) {
    const VirtualClipmapConfig config;  // 16K texels, 128-texel pages, level 0 two metres wide
    const ClipmapLevel level0 = placeClipmapLevel(config, 0, glm::vec2(0.0f));
    const ClipmapLevel level3 = placeClipmapLevel(config, 3, glm::vec2(0.0f));
    EXPECT_FLOAT_EQ(level0.lsSize, 2.0f);
    EXPECT_FLOAT_EQ(level3.lsSize, 16.0f);
    EXPECT_FLOAT_EQ(level3.lsTexelSize, 16.0f / 16384.0f);
    EXPECT_FLOAT_EQ(level3.lsPageSize, 16.0f / 128.0f);
    EXPECT_EQ(level3.pagesPerSide, 128u);
    EXPECT_EQ(level3.window.pageCount(), 128u * 128u);
}

TEST(VirtualClipmap, WindowIsCentredOnTheCameraSnappedToWholePages) {
    const VirtualClipmapConfig config = smallConfig();  // level 0: pages of 0.25 m
    const ClipmapLevel level = placeClipmapLevel(config, 0, glm::vec2(0.3f, -0.7f));
    EXPECT_EQ(pageOf(level, glm::vec2(0.3f, -0.7f)), glm::ivec2(1, -3));
    EXPECT_EQ(level.window.min, glm::ivec2(1 - 4, -3 - 4));
    EXPECT_EQ(level.window.max, glm::ivec2(1 + 3, -3 + 3));
}

TEST(VirtualClipmap, TheTexelGridDoesNotMoveWithTheCamera) {
    const VirtualClipmapConfig config = smallConfig();
    const ClipmapLevel before = placeClipmapLevel(config, 1, glm::vec2(0.01f, 0.02f));
    const ClipmapLevel within = placeClipmapLevel(config, 1, glm::vec2(0.2f, 0.3f));  // same page (0.5 m pages)
    EXPECT_EQ(within.window.min, before.window.min) << "a move within a page keeps the window";
    const ClipmapLevel moved = placeClipmapLevel(config, 1, glm::vec2(1.26f, 0.02f));  // 2.5 pages along x
    EXPECT_EQ(moved.window.min - before.window.min, glm::ivec2(2, 0)) << "the window moves by whole pages";
    // A light-space point lies in the same page, at the same texel of it, wherever the camera is.
    const glm::vec2 point(0.7f, -0.35f);
    EXPECT_EQ(pageOf(before, point), pageOf(moved, point));
    EXPECT_FLOAT_EQ(before.lsTexelSize, moved.lsTexelSize);
}

TEST(VirtualClipmap, PageTableSlotsAreDistinctInAWindowAndKeptWhileAPageStaysInIt) {
    const VirtualClipmapConfig config = smallConfig();
    const ClipmapLevel before = placeClipmapLevel(config, 0, glm::vec2(-0.4f, 0.9f));
    std::set<std::pair<uint32_t, uint32_t>> slots;
    for (int32_t y = before.window.min.y; y <= before.window.max.y; ++y)
        for (int32_t x = before.window.min.x; x <= before.window.max.x; ++x) {
            const glm::uvec2 slot = pageTableSlot(before, {x, y});
            EXPECT_LT(slot.x, 8u);
            EXPECT_LT(slot.y, 8u);
            slots.insert({slot.x, slot.y});
        }
    EXPECT_EQ(slots.size(), 64u);
    const ClipmapLevel after = placeClipmapLevel(config, 0, glm::vec2(0.4f, 0.4f));  // 3 pages right, 2 down
    uint32_t shared = 0;
    for (int32_t y = after.window.min.y; y <= after.window.max.y; ++y)
        for (int32_t x = after.window.min.x; x <= after.window.max.x; ++x) {
            if (x > before.window.max.x || y < before.window.min.y) continue;  // entered the window
            ++shared;
            EXPECT_EQ(pageTableSlot(after, {x, y}), pageTableSlot(before, {x, y}));
        }
    EXPECT_EQ(shared, 5u * 6u);
}

TEST(VirtualClipmap, TheLevelForAFootprintHasTexelsNoLargerThanIt) {
    const VirtualClipmapConfig config;
    const float texel0 = 2.0f / 16384.0f;
    EXPECT_EQ(levelForFootprint(config, 8.0f * texel0), 3u);
    EXPECT_EQ(levelForFootprint(config, 7.9f * texel0), 2u);
    EXPECT_EQ(levelForFootprint(config, 0.1f * texel0), 0u);
    EXPECT_EQ(levelForFootprint(config, 1e9f), config.levelCount - 1);
}

TEST(VirtualClipmap, AFarReceiverSamplesTheFirstLevelWhoseWindowHoldsIt) {
    const VirtualClipmapConfig config;
    const glm::vec2 camera(0.0f), receiver(100.0f, 3.0f);
    // A fine footprint asks for level 0; the window of level i reaches 2^i metres from the camera.
    const std::optional<uint32_t> level = levelForReceiver(config, camera, receiver, 1e-5f, 2.0f);
    ASSERT_TRUE(level.has_value());
    EXPECT_EQ(*level, 7u);  // 256 m wide: 128 m each way
    const ClipmapLevel coarser = placeClipmapLevel(config, 7, camera), finer = placeClipmapLevel(config, 6, camera);
    EXPECT_TRUE(coarser.window.contains(receiverPages(coarser, receiver, 2.0f)));
    EXPECT_FALSE(finer.window.contains(receiverPages(finer, receiver, 2.0f)));
}

TEST(VirtualClipmap, AReceiverBeyondTheLastLevelHasNone) {
    const VirtualClipmapConfig config = smallConfig();  // levels 2, 4, 8 and 16 m wide
    EXPECT_FALSE(levelForReceiver(config, glm::vec2(0.0f), glm::vec2(20.0f, 0.0f), 1e-5f, 0.0f).has_value());
    EXPECT_EQ(levelForReceiver(config, glm::vec2(0.0f), glm::vec2(5.0f, 0.0f), 1e-5f, 0.0f), 3u);
}

TEST(VirtualClipmap, AFilterNearAPageEdgeRequestsTheNeighbouringPage) {
    const VirtualClipmapConfig config = smallConfig();
    const ClipmapLevel level = placeClipmapLevel(config, 0, glm::vec2(0.0f));  // texels of 2/1024 m
    const glm::vec2 nearEdge(0.25f - 1.0f * level.lsTexelSize, 0.1f);           // one texel inside page 0
    EXPECT_EQ(receiverPages(level, nearEdge, 0.0f).pageCount(), 1u);
    const PageRect withKernel = receiverPages(level, nearEdge, 2.0f);  // a 5x5 kernel's reach
    EXPECT_EQ(withKernel.min, glm::ivec2(0, 0));
    EXPECT_EQ(withKernel.max, glm::ivec2(1, 0));
}

TEST(VirtualClipmap, CasterBoundsTouchTheWindowPagesTheyOverlap) {
    const VirtualClipmapConfig config = smallConfig();
    const ClipmapLevel level = placeClipmapLevel(config, 0, glm::vec2(0.0f));  // window pages -4..3
    Aabb box;
    box.extend(glm::vec3(0.1f, -0.3f, -50.0f));
    box.extend(glm::vec3(0.6f, 0.2f, 50.0f));
    const PageRect touched = pagesTouchedByBounds(level, box);
    EXPECT_EQ(touched.min, glm::ivec2(0, -2));
    EXPECT_EQ(touched.max, glm::ivec2(2, 0));
    Aabb wide;
    wide.extend(glm::vec3(-10.0f, -10.0f, 0.0f));
    wide.extend(glm::vec3(0.0f, 10.0f, 0.0f));
    EXPECT_EQ(pagesTouchedByBounds(level, wide).min, glm::ivec2(-4, -4)) << "clipped to the window";
    EXPECT_EQ(pagesTouchedByBounds(level, wide).max, glm::ivec2(0, 3));
    Aabb outside;
    outside.extend(glm::vec3(5.0f, 5.0f, 0.0f));
    outside.extend(glm::vec3(6.0f, 6.0f, 0.0f));
    EXPECT_TRUE(pagesTouchedByBounds(level, outside).empty());
}

}  // namespace
}  // namespace penumbra
