// Directional virtual shadow maps sharing one pool texture and one entry buffer (render/
// virtual_page_storage.h), as a lit pass that samples several lights binds them: two maps of the demo scene
// with different lights, recorded in one frame into a VirtualPageStorageSet, at 320 x 180 with the clipmap
// of virtual_shadow_map_test.cpp, lavapipe with validation.
//
// What they must do: each map's lookups through the shared texture and buffer (the probe, with the map's
// lookupData: its poolOriginY and firstEntry) equal, point for point, those of the same map with storage
// of its own, and agree with the CPU reference on the shared storage read back (virtual_shadow_lookup_test.
// cpp's tolerance); drawing, updating and resetting one map leaves the other's square of the texture and
// range of the buffer bit for bit as they were.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "penumbra/scene_loading.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/virtual_page_storage.h"
#include "render/virtual_shadow_map.h"
#include "render_test_support.h"
#include "shadows/cascades.h"
#include "shadows/virtual_shadow_lookup.h"
#include "virtual_shadow_test_support.h"

namespace penumbra::test {
namespace {

using gpu_data::VirtualPageEntry;
using gpu_data::VirtualPageStats;
using gpu_data::VirtualShadowProbePoint;
using gpu_data::VirtualShadowProbeResult;

constexpr float kMarginTexels = 2.0f;

// The scene's light turned by `degrees` about the vertical.
glm::vec3 turnedLight(const glm::vec3& light, float degrees) {
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::vec3(turn * glm::vec4(light, 0.0f));
}

// Ground points a view sees, with the ray tracer's answer for one light.
struct LightPoints {
    std::vector<VirtualShadowProbePoint> points;
    std::vector<bool> shadowed;
};

// What the lookups of a map read, copied back: the whole entry buffer and pool texture.
struct StorageCopy {
    std::vector<VirtualPageEntry> entries;
    std::vector<uint16_t> pool;  // the pool texture's depth codes, row by row, poolSide a row
};

// One map drawn in a frame: which map, for which light.
struct MapRecord {
    VirtualShadowMap* map = nullptr;
    glm::vec3 wsLight{0.0f};
};

// Two maps sharing a VirtualPageStorageSet and two with storage of their own, over the demo scene.
class SharedRig {
public:
    explicit SharedRig(gpu::Device& gpu)
        : gpu_(gpu), scene_(makeDemoScene()), gpuScene_(gpu, scene_), raster_(gpu, gpuScene_),
          storage_(gpu, mapConfig().clipmap, mapConfig().poolPagesPerSide, 2), probe_(gpu) {
        for (uint32_t i = 0; i < 2; ++i) {
            const VirtualPageStorage place = storage_.storageFor(i);
            shared_[i] = std::make_unique<VirtualShadowMap>(gpu, gpuScene_, raster_, mapConfig(), &place);
            alone_[i] = std::make_unique<VirtualShadowMap>(gpu, gpuScene_, raster_, mapConfig());
        }
    }
    ~SharedRig() {
        for (gpu::TextureHandle depth : depths_) gpu_.destroy(depth);
    }

    const Scene& scene() const { return scene_; }
    const VirtualPageStorageSet& storage() const { return storage_; }
    VirtualShadowMap& shared(uint32_t i) { return *shared_[i]; }
    VirtualShadowMap& alone(uint32_t i) { return *alone_[i]; }

    // The view's depth (kept until the rig goes), for its frames.
    gpu::TextureHandle depth(const CameraView& view) {
        depths_.push_back(renderSceneDepth(gpu_, scene_, view).texture);
        return depths_.back();
    }
    LightPoints points(const CameraView& view, const glm::vec3& wsLight, uint32_t stride = 1) const {
        LightPoints p;
        clearViewGroundPoints(scene_, view, lightRotationFromWorld(wsLight), wsLight, stride, p.points, p.shadowed);
        return p;
    }

    // One frame recording the maps in order in one command list; their stats, read back at its end.
    std::vector<VirtualPageStats> frame(gpu::TextureHandle depth, const CameraView& view, std::span<const MapRecord> records) {
        gpu::CommandList commands = gpu_.beginFrame();
        std::vector<uint64_t> at;
        for (const MapRecord& r : records) {
            r.map->record(commands, VirtualPageDepthSource::texture(depth), view, r.wsLight, scene_.wsBounds, kMarginTexels);
            at.push_back(gpu_.readBackAtFrameEnd(commands, r.map->stats()));
        }
        const uint64_t index = gpu_.submitFrame(commands);
        gpu_.waitFrame(index);
        std::vector<VirtualPageStats> stats(records.size());
        for (const gpu::CompletedFrame& done : gpu_.completedFrames())
            if (done.frameIndex == index)
                for (size_t i = 0; i < records.size(); ++i) stats[i] = VirtualShadowMap::statsFromReadback(done.readback.data() + at[i]);
        gpu_.releaseCompletedFrames();
        return stats;
    }

    // The lookups a lit pass makes with the map's bindings: its whole entry buffer, pool texture and lookupData.
    std::vector<VirtualShadowProbeResult> lookups(const VirtualShadowMap& map, const std::vector<VirtualShadowProbePoint>& points) {
        const uint32_t records = uint32_t(gpu_.bufferSize(map.pageEntries()) / sizeof(VirtualPageEntry));
        return probe_.run(map.lookupData(), map.pageEntries(), records, map.poolTexture(), points);
    }

    StorageCopy copy(const VirtualShadowMap& map) {
        StorageCopy c;
        const std::vector<uint8_t> bytes = gpu_.readBuffer(map.pageEntries());
        c.entries.resize(bytes.size() / sizeof(VirtualPageEntry));
        std::memcpy(c.entries.data(), bytes.data(), c.entries.size() * sizeof(VirtualPageEntry));
        c.pool = probe_.readPool(map.poolTexture());
        return c;
    }

private:
    gpu::Device& gpu_;
    Scene scene_;
    GpuScene gpuScene_;
    ComputeRasterPass raster_;
    VirtualPageStorageSet storage_;
    std::unique_ptr<VirtualShadowMap> shared_[2], alone_[2];
    ShadowProbe probe_;
    std::vector<gpu::TextureHandle> depths_;
};

// The points where two lookups differ in their shadow term or serving level.
size_t differences(const std::vector<VirtualShadowProbeResult>& a, const std::vector<VirtualShadowProbeResult>& b) {
    EXPECT_EQ(a.size(), b.size());
    size_t differ = 0;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) differ += a[i].lit != b[i].lit || a[i].level != b[i].level;
    return differ;
}

// Map `map`'s codes of a shared pool copy (its square, rows from poolOriginY) and entries (from firstEntry).
std::vector<uint16_t> poolSquare(const StorageCopy& c, const VirtualShadowMap& map) {
    const VirtualPageStorage at = map.storage();
    const size_t side = mapConfig().poolPagesPerSide * mapConfig().clipmap.pageSize;
    const auto first = c.pool.begin() + std::ptrdiff_t(at.poolOriginY * side);
    return {first, first + std::ptrdiff_t(side * side)};
}
std::vector<uint8_t> entryBytes(const StorageCopy& c, const VirtualShadowMap& map) {
    const auto* first = reinterpret_cast<const uint8_t*>(c.entries.data() + map.storage().firstEntry);
    return {first, first + map.pageEntryCount() * sizeof(VirtualPageEntry)};
}

class VirtualPageStorageTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }
};

TEST_F(VirtualPageStorageTest, TheSetPlacesEachMapInItsOwnAlignedRangeAndSquare) {
    const VirtualShadowMapConfig config = mapConfig();
    VirtualPageStorageSet set(gpu(), config.clipmap, config.poolPagesPerSide, 3);
    const uint32_t side = config.poolPagesPerSide * config.clipmap.pageSize;
    EXPECT_EQ(set.poolSide(), side);
    EXPECT_EQ(gpu().textureDesc(set.poolTexture()).width, side);
    EXPECT_EQ(gpu().textureDesc(set.poolTexture()).format, virtualPoolFormat(gpu()));
    EXPECT_EQ(gpu().textureDesc(set.poolTexture()).height, 3 * side);
    EXPECT_EQ(set.entriesPerMap(), config.clipmap.levelCount * 128u * 128u);
    EXPECT_GE(gpu().bufferSize(set.entries()), uint64_t(set.entryCount()) * sizeof(VirtualPageEntry));
    for (uint32_t i = 0; i < 3; ++i) {
        const VirtualPageStorage at = set.storageFor(i);
        EXPECT_EQ(at.poolOriginY, i * side);
        EXPECT_EQ(at.firstEntry * sizeof(VirtualPageEntry) % kVirtualPageEntryAlignment, 0u);
        EXPECT_GE(at.firstEntry, i * set.entriesPerMap());
    }
    // An odd entry count is padded: 3 levels of 5 x 5 pages, 75 entries, 80 a map (2560 bytes).
    VirtualPageStorageSet odd(gpu(), {.resolution = 160, .pageSize = 32, .levelCount = 3, .firstLevelSize = 8.0f}, 2, 2);
    EXPECT_EQ(odd.entriesPerMap(), 75u);
    EXPECT_EQ(odd.storageFor(1).firstEntry, 80u);
    // A map whose range would be misaligned, or whose square lies outside the texture, is refused.
    GpuScene gpuScene(gpu(), makeDemoScene());
    ComputeRasterPass raster(gpu(), gpuScene);
    VirtualPageStorage misaligned = set.storageFor(1);
    misaligned.firstEntry += 1;
    EXPECT_THROW((VirtualShadowMap(gpu(), gpuScene, raster, config, &misaligned)), Error);
    VirtualPageStorage outside = set.storageFor(2);
    outside.poolOriginY += 1;
    EXPECT_THROW((VirtualShadowMap(gpu(), gpuScene, raster, config, &outside)), Error);
}

TEST_F(VirtualPageStorageTest, TwoMapsSharingStorageLookUpAsEachAloneAndAsTheCpuReference) {
    SharedRig rig(gpu());
    const glm::vec3 lights[2] = {sceneLight(rig.scene()), turnedLight(sceneLight(rig.scene()), 40.0f)};
    const CameraView view = demoView();
    const gpu::TextureHandle depth = rig.depth(view);
    const MapRecord shared[] = {{&rig.shared(0), lights[0]}, {&rig.shared(1), lights[1]}};
    const MapRecord alone[] = {{&rig.alone(0), lights[0]}, {&rig.alone(1), lights[1]}};
    const std::vector<VirtualPageStats> sharedStats = rig.frame(depth, view, shared);
    const std::vector<VirtualPageStats> aloneStats = rig.frame(depth, view, alone);
    EXPECT_EQ(rig.shared(0).lookupData().poolOriginY, 0u);
    EXPECT_EQ(rig.shared(0).lookupData().firstEntry, 0u);
    EXPECT_EQ(rig.shared(1).lookupData().poolOriginY, rig.storage().poolSide());
    EXPECT_EQ(rig.shared(1).lookupData().firstEntry, rig.storage().entryStride());
    EXPECT_EQ(rig.shared(1).pageEntries().id, rig.shared(0).pageEntries().id);
    EXPECT_EQ(rig.shared(1).poolTexture().id, rig.shared(0).poolTexture().id);
    const StorageCopy storage = rig.copy(rig.shared(0));
    for (uint32_t i = 0; i < 2; ++i) {
        const LightPoints p = rig.points(view, lights[i]);
        const std::vector<VirtualShadowProbeResult> results = rig.lookups(rig.shared(i), p.points);
        size_t shadowed = 0, wrong = 0;
        for (size_t k = 0; k < results.size(); ++k) {
            shadowed += results[k].lit < 0.5f;
            wrong += p.shadowed[k] != (results[k].lit < 0.5f);
        }
        std::printf("map %u: %u pages drawn (alone %u); %zu ground points, %zu shadowed, %zu disagree with the ray tracer\n", i,
                    sharedStats[i].toDraw, aloneStats[i].toDraw, p.points.size(), shadowed, wrong);
        EXPECT_GT(sharedStats[i].toDraw, 50u);
        EXPECT_EQ(sharedStats[i].toDraw, aloneStats[i].toDraw);
        EXPECT_GT(shadowed, 500u) << "map " << i << ": the comparisons see shadows";
        EXPECT_LE(wrong, p.points.size() / 100) << "map " << i << ": at most 1 % disagree with the ray tracer";
        EXPECT_EQ(differences(results, rig.lookups(rig.alone(i), p.points)), 0u) << "map " << i << " shared as alone";
        const Agreement a = compareWithCpu(rig.shared(i).lookupData(), {storage.entries, storage.pool}, p.points, results);
        EXPECT_EQ(a.differ, 0u) << "map " << i << ": the GPU lookup equals the CPU reference on the shared storage";
    }
}

// Map 1 drawn again for another light and a moved camera, and then reset, while map 0 is not recorded:
// map 0's square, entries and lookups stay bit for bit (map 1's change, which shows the test would see it).
TEST_F(VirtualPageStorageTest, DrawingUpdatingAndResettingOneMapLeavesTheOthersStorageAlone) {
    SharedRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    const CameraView view = demoView(), moved = translatedCameraView(view, glm::vec3(1.5f, 0.0f, -1.0f));
    const gpu::TextureHandle depth = rig.depth(view), movedDepth = rig.depth(moved);
    const MapRecord both[] = {{&rig.shared(0), light}, {&rig.shared(1), turnedLight(light, 40.0f)}};
    rig.frame(depth, view, both);
    const LightPoints p = rig.points(view, light, 2);
    const std::vector<VirtualShadowProbeResult> before = rig.lookups(rig.shared(0), p.points);
    const StorageCopy first = rig.copy(rig.shared(0));
    const MapRecord turned[] = {{&rig.shared(1), turnedLight(light, -30.0f)}};
    const VirtualPageStats redrawn = rig.frame(movedDepth, moved, turned)[0];
    const StorageCopy second = rig.copy(rig.shared(0));
    rig.shared(1).table().reset();  // the next record empties map 1's table first
    const VirtualPageStats afterReset = rig.frame(depth, view, turned)[0];
    const StorageCopy third = rig.copy(rig.shared(0));
    std::printf("map 1: %u pages drawn for the turned light and moved camera, %u after its reset\n", redrawn.toDraw,
                afterReset.toDraw);
    EXPECT_GT(redrawn.toDraw, 50u);
    EXPECT_EQ(afterReset.toDraw, afterReset.requested) << "an emptied table draws every requested page";
    VirtualShadowMap& map0 = rig.shared(0);
    VirtualShadowMap& map1 = rig.shared(1);
    EXPECT_TRUE(poolSquare(second, map0) == poolSquare(first, map0)) << "map 1's drawing left map 0's square";
    EXPECT_TRUE(entryBytes(second, map0) == entryBytes(first, map0)) << "map 1's update left map 0's entries";
    EXPECT_TRUE(poolSquare(third, map0) == poolSquare(first, map0)) << "map 1's reset left map 0's square";
    EXPECT_TRUE(entryBytes(third, map0) == entryBytes(first, map0)) << "map 1's reset left map 0's entries";
    EXPECT_FALSE(poolSquare(second, map1) == poolSquare(first, map1)) << "map 1 drew into its own square";
    EXPECT_FALSE(entryBytes(second, map1) == entryBytes(first, map1)) << "map 1 updated its own entries";
    EXPECT_EQ(differences(rig.lookups(map0, p.points), before), 0u) << "map 0 looks up as before";
}

// The frame-graph declarations of two maps sharing storage in one frame leave no hazard, on a device with
// synchronization validation: frames that draw both maps' pages, none, and one map's after its light turned.
TEST_F(VirtualPageStorageTest, FramesOfTwoMapsSharingStoragePassSynchronizationValidation) {
    DeviceOptions options = testDeviceOptions();
    options.synchronizationValidation = true;
    Device syncDevice(options);
    gpu::Device& gpu = gpu::backend(syncDevice);
    {
        SharedRig rig(gpu);
        const glm::vec3 light = sceneLight(rig.scene()), other = turnedLight(light, 40.0f);
        const CameraView view = demoView(160, 90);
        const gpu::TextureHandle depth = rig.depth(view);
        const LightPoints p = rig.points(view, light, 4);
        for (const glm::vec3& second : {other, other, turnedLight(light, -30.0f)}) {
            const MapRecord records[] = {{&rig.shared(0), light}, {&rig.shared(1), second}};
            rig.frame(depth, view, records);
            for (uint32_t i = 0; i < 2; ++i) EXPECT_EQ(rig.lookups(rig.shared(i), p.points).size(), p.points.size());
        }
    }
    gpu.waitIdle();
    const uint32_t messages = syncDevice.validationMessageCount();
    EXPECT_EQ(messages, 0u) << (messages ? syncDevice.validationMessages()[0] : "");
}

}  // namespace
}  // namespace penumbra::test
