// GPU shadow-caster culling against the CPU planner's culling, its reference: on every
// canonical scene, the demo and the built-in scale scenes, every tile keeps the same instances.
#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "penumbra/scene_loading.h"
#include "render/gpu_scene.h"
#include "render/shadow_culling_pass.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"
#include "shadows/cull_packing.h"
#include "shadows/visible_surfaces.h"

namespace penumbra::test {
namespace {

class ShadowCullingTest : public RenderTest {
protected:
    // Per tile of the plan (directional, then spot/point): the GPU's visible instances and the CPU's.
    struct Lists {
        std::vector<std::vector<uint32_t>> gpu, cpu;
        uint32_t visibleBuffers = 0;  // the storage buffers the GPU's lists were split over
    };
    static constexpr uint32_t kWidth = 160, kHeight = 90;
    Lists cull(const Scene& scene, const Settings& settings, Device* on = nullptr, const VisibleSurfaces* visible = nullptr) {
        gpu::Device& gpu = gpu::backend(on ? *on : device());
        const CameraView view = resolveCameraView(scene, kWidth, kHeight);
        const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows, visible);  // CPU lists kept
        GpuScene gpuScene(gpu, scene);
        ShadowCullingPass culling(gpu, gpuScene);
        const gpu_data::CullFrame packed = packCullFrame(plan, gpuScene.instanceCount(), gpuScene.meshSlotCount());
        const gpu::BufferHandle frame = gpu.createBuffer(sizeof(packed), gpu::kBufferUniform, gpu::MemoryKind::HostVisible,
                                                         &packed, "test cull frame");
        CullTileUpload tileList;
        packCullTiles(plan, gpuScene.instanceCount(), gpuScene.meshSlotCount(), tileList);
        const gpu::BufferHandle tileBuffer = gpu.createBuffer(tileList.bytes(), gpu::kBufferStorage | gpu::kBufferIndirect,
                                                              gpu::MemoryKind::HostVisible, &tileList, "test cull tiles");
        const uint32_t tiles = uint32_t(plan.directional.tiles.size() + plan.other.tiles.size());
        gpu::CommandList commands = gpu.beginCommands();
        culling.record(commands, {frame, 0, sizeof(packed)}, {tileBuffer, 0, tileList.bytes()});
        gpu.submitAndWait(commands);
        Lists lists;
        lists.gpu = culling.readVisibleLists(tiles);
        lists.visibleBuffers = culling.visibleBufferCount();
        for (const auto* tileList : {&plan.directional.tiles, &plan.other.tiles})
            for (const ShadowTile& tile : *tileList) {
                std::vector<uint32_t> instances = tile.casterInstances;
                std::sort(instances.begin(), instances.end());
                lists.cpu.push_back(instances);
            }
        gpu.destroy(frame);
        gpu.destroy(tileBuffer);
        return lists;
    }

    // Leaves the lists compared in last_.
    void expectSameLists(const Scene& scene, const Settings& settings, const std::string& what, Device* on = nullptr,
                         const VisibleSurfaces* visible = nullptr) {
        last_ = cull(scene, settings, on, visible);
        const Lists& lists = last_;
        ASSERT_EQ(lists.gpu.size(), lists.cpu.size()) << what;
        ASSERT_FALSE(lists.cpu.empty()) << what << ": no shadow tile to compare";
        size_t kept = 0;
        for (size_t tile = 0; tile < lists.cpu.size(); ++tile) {
            EXPECT_EQ(lists.gpu[tile], lists.cpu[tile]) << what << ", tile " << tile;
            kept += lists.cpu[tile].size();
        }
        EXPECT_GT(kept, 0u) << what;
    }
    Lists last_;
};

TEST_F(ShadowCullingTest, GpuListsEqualTheCpuListsOnEveryCanonicalScene) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        Settings settings;
        settings.shadows.maxDistance = 150.0f;
        expectSameLists(makeCanonicalScene(info.name), settings, info.name);
    }
}

// The tight fit narrows receiver culling to each slice's view depth (the sphere fit above: to its
// sphere): with the ground plane y = 0 as the visible surfaces, the GPU keeps what the CPU keeps.
TEST_F(ShadowCullingTest, GpuListsEqualTheCpuListsWithTightCascades) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        const CameraView view = resolveCameraView(scene, kWidth, kHeight);
        Image depth(kWidth, kHeight, 4, 0);
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                const glm::vec3 dir = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
                if (dir.y >= -1e-4f) continue;
                const glm::vec4 clip = view.clipFromWorld * glm::vec4(view.wsPosition + dir * (-view.wsPosition.y / dir.y), 1.0f);
                const float d = clip.z / clip.w;
                std::memcpy(&depth.pixels[(size_t(y) * kWidth + x) * 4], &d, sizeof(float));
            }
        const VisibleSurfaces visible = visibleSurfacesFromDepth(depth, view);
        if (visible.empty()) continue;
        Settings settings;
        settings.shadows.maxDistance = 150.0f;
        settings.shadows.directional.fit = CascadeFit::Tight;
        expectSameLists(scene, settings, info.name + ", tight", nullptr, &visible);
    }
}

TEST_F(ShadowCullingTest, GpuListsEqualTheCpuListsWithEveryCascadeCountAndBlendCulling) {
    const Scene scene = makeDemoScene();
    for (uint32_t cascades = 1; cascades <= 4; ++cascades) {
        for (float fade : {0.05f, 0.1f, 0.5f}) {
            Settings settings;
            settings.shadows.directional.cascadeCount = cascades;
            settings.shadows.directional.cascadeFade = fade;  // blend culling factor 0.75, 0.7, 0.3
            expectSameLists(scene, settings, "demo, " + std::to_string(cascades) + " cascades, fade " + std::to_string(fade));
        }
    }
}

TEST_F(ShadowCullingTest, GpuListsEqualTheCpuListsOnManyObjects) {
    Settings settings;
    settings.shadows.maxDistance = 300.0f;
    expectSameLists(loadScene("gen:boxes:3000"), settings, "gen:boxes:3000");
    expectSameLists(loadScene("gen:field:9:6"), Settings{}, "gen:field:9:6");
}

// On a device whose storage buffers seem to hold 16 of the 34 lists, the lists are split over three
// buffers; every one of 18 tiles, in whichever buffer, keeps what the CPU keeps.
TEST_F(ShadowCullingTest, GpuListsSplitOverStorageBuffersEqualTheCpuLists) {
    const Scene scene = boxesWithEighteenShadowTiles(kSplitListBoxes);
    gpu::DeviceFaultInjection faults;
    faults.maxStorageBufferRange = kSplitListsPerBuffer * sizeof(uint32_t) * scene.instances.size();
    Device split = DeviceAccess::makeDevice({testDeviceOptions(), faults});
    expectSameLists(scene, Settings{}, "boxes, 18 tiles, lists split", &split);
    EXPECT_EQ(last_.cpu.size(), kSplitListTiles);
    EXPECT_EQ(last_.visibleBuffers, 3u);
    EXPECT_EQ(split.validationMessageCount(), 0u);
}

TEST_F(ShadowCullingTest, NonCastingNodesAndShadowlessMaterialsAreNeverListed) {
    Scene scene = makeDemoScene();
    for (uint32_t i = 0; i < scene.instances.size(); i += 2) scene.instances[i].castShadows = false;
    scene.materials[0].shadows = MaterialShadowMode::Off;
    expectSameLists(scene, Settings{}, "demo with half the casters off");
}

// The stats (--stats, the viewer's stats panel) count the triangles each tile drew: with every caster a
// box of one triangle count, a tile's triangles are its casters times that count, and the tiles of an
// atlas add up to the atlas's triangles.
TEST_F(ShadowCullingTest, StatsCountTheTrianglesEachTileDrew) {
    Scene scene = loadScene("gen:boxes:100:0");
    uint32_t boxTriangles = 0;
    for (Instance& instance : scene.instances) {
        const uint32_t triangles = uint32_t(scene.meshes[instance.meshIndex].indices.size() / 3);
        if (instance.nodeName == "ground") instance.castShadows = false;
        else boxTriangles = triangles;
    }
    ASSERT_GT(boxTriangles, 2u);
    Settings settings;
    settings.shadows.directional.cascadeCount = 3;
    RenderRequest request;
    request.width = 96;
    request.height = 54;
    const RenderResult result = renderScene(scene, request, settings);
    const nlohmann::json stats = nlohmann::json::parse(toJson(result.stats.shadows))["directional"];
    ASSERT_TRUE(stats.contains("trianglesPerTile"));
    ASSERT_EQ(stats["trianglesPerTile"].size(), 3u);
    uint64_t total = 0, casters = 0;
    for (size_t tile = 0; tile < 3; ++tile) {
        const uint64_t triangles = stats["trianglesPerTile"][tile];
        EXPECT_EQ(triangles, uint64_t(stats["castersPerTile"][tile]) * boxTriangles) << "tile " << tile;
        total += triangles;
        casters += uint64_t(stats["castersPerTile"][tile]);
    }
    EXPECT_GT(casters, 0u);
    EXPECT_EQ(total, result.stats.atlases[0].triangles);
    // Three tiles of a 2 x 2 split: three quarters of the atlas.
    EXPECT_DOUBLE_EQ(double(stats["occupancy"]), 0.75);
}

}  // namespace
}  // namespace penumbra::test
