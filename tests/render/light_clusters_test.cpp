// Clustered light culling on the GPU (render.lightCulling = clustered): the cluster pass's masks equal the
// CPU reference's, and the clustered lit pass gives the unculled image on every canonical scene and on a
// scene of 400 point lights, while each pixel loops over a small share of the lights.
#include <algorithm>
#include <cstdlib>

#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "render/light_cluster_pass.h"
#include "render/light_clusters.h"
#include "render/light_packing.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"

namespace penumbra::test {
namespace {

class LightClustersTest : public RenderTest {
protected:
    RenderResult renderColor(Renderer& renderer, LightCulling culling, uint32_t width = 320, uint32_t height = 180) {
        Settings settings;
        settings.render.lightCulling = culling;
        settings.shadows.directional.atlasSize = 512;  // lavapipe: keep the shadow passes small
        settings.shadows.spot.atlasSize = 512;
        RenderRequest request;
        request.width = width;
        request.height = height;
        return renderer.render(request, settings);
    }


    // Clustered and unculled colour of `scene`: at most 2 levels apart in 99.5 % of pixels (the
    // same bar as visibility_view_test.cpp); returns the share of pixels that differ at all.
    double expectSameImage(const Scene& scene, const std::string& what) {
        Renderer renderer(device(), scene);
        const RenderResult clustered = renderColor(renderer, LightCulling::Clustered, 160, 90);
        const RenderResult unculled = renderColor(renderer, LightCulling::None, 160, 90);
        EXPECT_LE(shareOfPixelsOver(clustered.image, unculled.image, 2), 0.005) << what;
        EXPECT_EQ(unculled.stats.lightsPerClusterMax, 0u) << what << ": culling off counts nothing";
        return shareOfPixelsOver(clustered.image, unculled.image, 0);
    }
};

// gen:boxes:100:400 and 40 spot lights of assorted cones over it.
Scene pointsAndSpots() {
    Scene scene = loadScene("gen:boxes:100:400");
    for (uint32_t i = 0; i < 40; ++i) {
        const glm::vec3 position(float(i % 8) * 1.6f - 6.0f, 2.5f, float(i / 8) * 2.4f - 6.0f);
        const glm::vec3 direction = glm::normalize(glm::vec3(0.3f * float(i % 3) - 0.3f, -1.0f, 0.2f * float(i % 5) - 0.4f));
        Light spot = makeSpotLight(position, direction, 8.0f, 3.0f + float(i % 4), 0.15f + 0.03f * float(i), 0.1f);
        spot.shadows = LightShadows::None;
        scene.lights.push_back(spot);
    }
    return scene;
}

TEST_F(LightClustersTest, GpuMasksEqualTheCpuReference) {
    const Scene scene = pointsAndSpots();
    const CameraView view = resolveCameraView(scene, 320, 180);
    const PackedLights packed = packLights(scene, [](uint32_t) { return kNoShadowSlot; });
    const gpu_data::LightClusterData clusters =
        makeLightClusterData(view, scene.wsBounds, packed.directionalCount, packed.otherCount, true);
    ASSERT_EQ(packed.otherCount, 440u);
    gpu::Device& gpu = gpu::backend(device());
    LightClusterPass pass(gpu);
    const gpu::BufferHandle clusterBuffer = gpu.createBuffer(sizeof(clusters), gpu::kBufferUniform,
                                                             gpu::MemoryKind::HostVisible, &clusters, "test clusters");
    const uint64_t lightBytes = packed.lights.size() * sizeof(gpu_data::LightData);
    const gpu::BufferHandle lightBuffer = gpu.createBuffer(lightBytes, gpu::kBufferStorage, gpu::MemoryKind::HostVisible,
                                                           packed.lights.data(), "test lights");
    gpu::CommandList commands = gpu.beginCommands();
    pass.record(commands, {clusterBuffer, 0, sizeof(clusters)}, {lightBuffer, 0, lightBytes}, true);
    gpu.submitAndWait(commands);
    const std::vector<uint32_t> gpuMasks = pass.readMasks(clusters.wordsPerCluster);
    const std::vector<uint32_t> cpuMasks = clusterLightMasks(clusters, packed.lights);
    ASSERT_EQ(gpuMasks.size(), cpuMasks.size());
    size_t differentBits = 0, setBits = 0;
    for (size_t i = 0; i < cpuMasks.size(); ++i) {
        differentBits += size_t(__builtin_popcount(gpuMasks[i] ^ cpuMasks[i]));
        setBits += size_t(__builtin_popcount(cpuMasks[i]));
    }
    EXPECT_GT(setBits, 1000u);
    // exp, log and acos of the driver and of libm may round differently right at a box's edge.
    EXPECT_LE(double(differentBits), 0.001 * double(setBits)) << differentBits << " of " << setBits << " bits differ";
    std::printf("GPU vs CPU cluster masks: %zu of %zu set bits differ\n", differentBits, setBits);
    gpu.destroy(clusterBuffer);
    gpu.destroy(lightBuffer);
}

TEST_F(LightClustersTest, ClusteredImageEqualsTheUnculledOneOnEveryCanonicalScene) {
    double worst = 0.0;
    for (const CanonicalSceneInfo& info : canonicalScenes())
        worst = std::max(worst, expectSameImage(makeCanonicalScene(info.name), info.name));
    worst = std::max(worst, expectSameImage(makeDemoScene(), "demo"));
    std::printf("canonical scenes: at most %.4f %% of pixels differ at all between clustered and unculled\n", 100.0 * worst);
}

TEST_F(LightClustersTest, ClusteredImageEqualsTheUnculledOneWith400PointLights) {
    const double differ = expectSameImage(loadScene("gen:boxes:100:400"), "gen:boxes:100:400");
    std::printf("400 point lights: %.4f %% of pixels differ at all between clustered and unculled\n", 100.0 * differ);
    const double withSpots = expectSameImage(pointsAndSpots(), "400 point and 40 spot lights");
    std::printf("and 40 spot lights: %.4f %% of pixels differ at all\n", 100.0 * withSpots);
}

TEST_F(LightClustersTest, EachClusterHoldsASmallShareOf400PointLights) {
    Renderer renderer(device(), loadScene("gen:boxes:100:400"));
    const FrameStats stats = renderColor(renderer, LightCulling::Clustered).stats;
    EXPECT_GT(stats.lightsPerClusterMax, 0u);
    EXPECT_GT(stats.lightsPerClusterMean, 0.1);
    EXPECT_LT(stats.lightsPerClusterMean, 20.0) << "of 400";
    EXPECT_LT(stats.lightsPerClusterMax, 200u) << "of 400 (the far slices' clusters are large)";
    std::printf("400 point lights: %.2f lights per cluster on average, %u at most\n", stats.lightsPerClusterMean,
                stats.lightsPerClusterMax);
}

TEST_F(LightClustersTest, TheLightsOfEveryPixelAreCountedOncePerCluster) {
    // A point light without range reaches every cluster: the mean and the most are both exactly one.
    Scene scene = loadScene("gen:boxes:4");
    Light point = makePointLight({0.0f, 2.0f, 0.0f}, 3.0f, 0.0f);
    point.shadows = LightShadows::None;
    scene.lights.push_back(point);
    Renderer renderer(device(), scene);
    const FrameStats stats = renderColor(renderer, LightCulling::Clustered, 160, 90).stats;
    EXPECT_DOUBLE_EQ(stats.lightsPerClusterMean, 1.0);
    EXPECT_EQ(stats.lightsPerClusterMax, 1u);
}

}  // namespace
}  // namespace penumbra::test
