// The frame-end readback (render/frame_readback.h): each piece the GPU counted is read at the offset
// Device::readBackAtFrameEnd gave it, whatever the order the frame recorded them in, and a piece the
// frame did not read back leaves its stats at zero.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>

#include "cull_structs.h"
#include "light_cluster_structs.h"
#include "render/frame_readback.h"
#include "shadow_test_scene.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

// A frame's readback: pieces appended as the device does, each at the offset returned.
struct Readback {
    std::vector<uint8_t> bytes;
    template <typename T>
    uint64_t append(const T* values, size_t count = 1) {
        const uint64_t offset = bytes.size();
        bytes.resize(bytes.size() + count * sizeof(T));
        std::memcpy(bytes.data() + offset, values, count * sizeof(T));
        return offset;
    }
};

FrameStats statsWithAtlases() {
    FrameStats stats;
    stats.atlases = {{"shadows.directional", 0, 0, 0}, {"shadows.other", 0, 0, 0}};
    return stats;
}

gpu_data::RasterCounters rasterCounters(uint32_t large, uint32_t chunks, uint32_t dropped, uint32_t meshletsOutside) {
    gpu_data::RasterCounters counters{};
    counters.largeQueued = large;
    counters.chunksQueued = chunks;
    counters.largeDropped = dropped;
    counters.meshletsOutside = meshletsOutside;
    return counters;
}

}  // namespace

TEST(FrameReadback, CullTileCountsGoToTheirAtlasAndTheStatsJson) {
    const ShadowFrame plan = groundAndBoxPlan(2);
    ASSERT_EQ(plan.directional.tiles.size(), 2u);
    const gpu_data::CullTileStats tiles[2] = {{3, 5, 700, 0}, {4, 6, 900, 0}};
    Readback readback;
    const uint32_t padding[4] = {99, 99, 99, 99};  // another piece first: the tiles are not at offset 0
    readback.append(padding, 4);
    FrameReadbackLayout layout;
    layout.cullTiles = readback.append(tiles, 2);
    FrameStats stats = statsWithAtlases();
    glm::uvec3 needed{0};
    applyFrameReadback(stats, plan, layout, readback.bytes, needed);
    EXPECT_EQ(stats.atlases[0].draws, 7u);
    EXPECT_EQ(stats.atlases[0].triangles, 1600u);
    EXPECT_EQ(stats.atlases[1].draws, 0u) << "no spot or point tile";
    const nlohmann::json json = nlohmann::json::parse(toJson(stats.shadows));
    EXPECT_EQ(json["directional"]["castersPerTile"], nlohmann::json({5, 6}));
    EXPECT_EQ(json["directional"]["trianglesPerTile"], nlohmann::json({700, 900}));
}

TEST(FrameReadback, PiecesAreReadAtTheirOffsetsInAnyOrder) {
    const ShadowFrame plan = groundAndBoxPlan(1);
    Readback readback;
    FrameReadbackLayout layout;
    // The reverse of the order a frame records them in.
    const gpu_data::LightClusterStats clusters{2 * gpu_data::kClusterCount, 9, 0, 0};
    layout.lightClusters = readback.append(&clusters);
    const glm::uvec4 meshlets(11, 12, 0, 0);
    layout.viewMeshlets = readback.append(&meshlets);
    const gpu_data::CullTileStats lists[2] = {{0, 20, 3000, 0}, {0, 4, 500, 0}};
    layout.viewLists = readback.append(lists, 2);
    const gpu_data::CullTileStats tile{1, 1, 10, 0};
    layout.cullTiles = readback.append(&tile);
    FrameStats stats = statsWithAtlases();
    glm::uvec3 needed{0};
    applyFrameReadback(stats, plan, layout, readback.bytes, needed);
    EXPECT_DOUBLE_EQ(stats.lightsPerClusterMean, 2.0);
    EXPECT_EQ(stats.lightsPerClusterMax, 9u);
    EXPECT_EQ(stats.viewMeshletsOutside, 11u);
    EXPECT_EQ(stats.viewMeshletsFacingAway, 12u);
    EXPECT_EQ(stats.viewInstancesEarly, 20u);
    EXPECT_EQ(stats.viewInstancesLate, 4u);
    EXPECT_EQ(stats.viewTriangles, 3500u);
    EXPECT_EQ(stats.atlases[0].triangles, 10u);
}

TEST(FrameReadback, BothAtlasPassesRasterCountersAddUpAndSizeTheQueues) {
    const ShadowFrame plan = groundAndBoxPlan(1);
    Readback readback;
    FrameReadbackLayout layout;
    const gpu_data::RasterCounters directional = rasterCounters(100, 2000, 0, 7);
    const gpu_data::RasterCounters other = rasterCounters(300, 500, 0, 1);
    layout.rasterCounters[0] = readback.append(&directional);
    layout.rasterCounters[1] = readback.append(&other);
    FrameStats stats = statsWithAtlases();
    glm::uvec3 needed{50, 4000, 0};
    applyFrameReadback(stats, plan, layout, readback.bytes, needed);
    EXPECT_EQ(stats.rasterLargeTriangles, 400u);
    EXPECT_EQ(stats.rasterChunks, 2500u);
    EXPECT_EQ(stats.shadowMeshletsOutside, 8u);
    EXPECT_EQ(stats.rasterDropped, 0u);
    EXPECT_TRUE(stats.warnings.empty());
    EXPECT_EQ(needed, glm::uvec3(300, 4000, 0)) << "the most one pass asked for, never less than before";
}

TEST(FrameReadback, DroppedRasterPiecesAreCountedAndWarned) {
    const ShadowFrame plan = groundAndBoxPlan(1);
    Readback readback;
    FrameReadbackLayout layout;
    gpu_data::RasterCounters counters = rasterCounters(10, 20, 3, 0);
    counters.chunksDropped = 4;
    layout.rasterCounters[1] = readback.append(&counters);
    FrameStats stats = statsWithAtlases();
    stats.frameIndex = 42;
    glm::uvec3 needed{0};
    applyFrameReadback(stats, plan, layout, readback.bytes, needed);
    EXPECT_EQ(stats.rasterDropped, 7u);
    ASSERT_EQ(stats.warnings.size(), 1u);
    EXPECT_NE(stats.warnings[0].find("7 large pieces, chunks or work items were not drawn in frame 42"), std::string::npos)
        << stats.warnings[0];
}

TEST(FrameReadback, AVirtualMapsDroppedWorkItemsAreCountedAndGrowTheWorkQueue) {
    const ShadowFrame plan = groundAndBoxPlan(1);
    Readback readback;
    FrameReadbackLayout layout;
    gpu_data::RasterCounters atlas = rasterCounters(0, 0, 0, 0);
    atlas.workQueued = 900;
    gpu_data::RasterCounters pages = rasterCounters(0, 0, 0, 0);
    pages.workQueued = 5000;
    pages.workDropped = 1000;
    layout.rasterCounters[0] = readback.append(&atlas);
    layout.rasterCounters[3] = readback.append(&pages);  // the second directional light's virtual map
    FrameStats stats = statsWithAtlases();
    glm::uvec3 needed{0};
    applyFrameReadback(stats, plan, layout, readback.bytes, needed);
    EXPECT_EQ(stats.rasterDropped, 1000u) << "the pages drew without those items: the renderer redraws them";
    EXPECT_EQ(needed.z, 5000u) << "the queue grows to what the largest pass asked for";
}

TEST(FrameReadback, PiecesTheFrameDidNotReadBackLeaveTheirStatsAtZero) {
    const ShadowFrame plan = groundAndBoxPlan(1);
    Readback readback;
    const gpu_data::LightClusterStats clusters{5000, 9, 0, 0};
    readback.append(&clusters);  // in the bytes, but the layout does not name it
    FrameStats stats = statsWithAtlases();
    glm::uvec3 needed{0};
    applyFrameReadback(stats, plan, FrameReadbackLayout{}, readback.bytes, needed);
    EXPECT_EQ(stats.lightsPerClusterMax, 0u);
    EXPECT_EQ(stats.viewInstancesEarly, 0u);
    EXPECT_EQ(stats.rasterChunks, 0u);
    EXPECT_EQ(stats.atlases[0].draws, 0u);
    EXPECT_EQ(needed, glm::uvec3(0));
    EXPECT_EQ(stats.shadows.directional.tileStats.size(), plan.directional.tiles.size())
        << "the plan's part of the shadow stats is written anyway";
}

TEST(FrameReadback, TimedMillisecondsSumsTheNamedPasses) {
    FrameStats stats;
    stats.gpuTimings = {{"shadows.directional", 1.5}, {"main", 0.25}, {"shadows.other", 0.5}};
    EXPECT_DOUBLE_EQ(timedMilliseconds(stats, {"shadows.directional", "shadows.other"}), 2.0);
    EXPECT_DOUBLE_EQ(timedMilliseconds(stats, {"main"}), 0.25);
    EXPECT_DOUBLE_EQ(timedMilliseconds(stats, {"lightClusters"}), 0.0);
}
