// The compute rasterizer of shadow depth (shadows.raster = compute) against the hardware rasterizer: the
// shadow term of every light of every canonical scene, and the atlases themselves, must agree.
#include <cmath>

#include <array>

#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"
#include "shadows/shadow_planner.h"

namespace penumbra::test {
namespace {

class ComputeRasterTest : public RenderTest {
protected:
    RenderResult render(Renderer& renderer, ShadowRaster raster, uint32_t light, Settings settings, bool atlas = false) {
        settings.shadows.raster = raster;
        RenderRequest request;
        request.width = 160;
        request.height = 90;
        request.output = OutputMode::ShadowAov;
        request.aovLight = light;
        request.captureAtlas = atlas;
        return renderer.render(request, settings);
    }
    // Pixels whose lit / shadowed class (at 0.5) differs.
    static double classDifference(const Image& a, const Image& b) {
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += (a.pixels[i] >= 128) != (b.pixels[i] >= 128);
        return double(differ) / double(a.pixels.size());
    }
};

TEST_F(ComputeRasterTest, ShadowTermOfEveryCanonicalSceneMatchesTheHardwarePath) {
    double worst = 0.0;
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        Renderer renderer(device(), scene);
        Settings settings;
        settings.shadows.maxDistance = 150.0f;
        settings.shadows.directional.atlasSize = 512;  // lavapipe runs compute shaders on the CPU: keep it small
        settings.shadows.spot.atlasSize = 512;
        for (uint32_t light = 0; light < scene.lights.size(); ++light) {
            if (scene.lights[light].shadows == LightShadows::None) continue;
            const RenderResult hw = render(renderer, ShadowRaster::Hw, light, settings);
            const RenderResult compute = render(renderer, ShadowRaster::Compute, light, settings);
            EXPECT_EQ(hw.stats.shadowRaster, "hw");
            EXPECT_EQ(compute.stats.shadowRaster, "compute");
            const double difference = classDifference(hw.image, compute.image);
            worst = std::max(worst, difference);
            EXPECT_LT(difference, 0.0005) << info.name << " light " << light;
        }
    }
    std::printf("worst class difference hw vs compute: %.4f %%\n", 100.0 * worst);
}

TEST_F(ComputeRasterTest, AtlasDepthMatchesTheHardwarePathTexelForTexel) {
    // The demo: a ground larger than every tile (large, clipped triangles), boxes, spheres, an
    // alpha-clipped quad, a dithered sphere, two spots.
    Renderer renderer(device(), makeDemoScene());
    Settings settings;
    settings.shadows.directional.atlasSize = 512;
    settings.shadows.spot.atlasSize = 512;
    const Image hw = render(renderer, ShadowRaster::Hw, 0, settings, true).atlas;
    const RenderResult computed = render(renderer, ShadowRaster::Compute, 0, settings, true);
    const Image& compute = computed.atlas;
    // Every level of the compute rasterizer drew some of it: its threads, its workgroups, the chunk passes.
    EXPECT_GT(computed.stats.rasterMediumTriangles, 0u) << "pieces rasterized by their workgroup in blocks";
    EXPECT_GT(computed.stats.rasterLargeTriangles, 0u) << "pieces rasterized in chunks";
    ASSERT_EQ(hw.pixels.size(), compute.pixels.size());
    size_t differ = 0, written = 0;
    for (size_t i = 0; i < hw.pixels.size(); ++i) {
        differ += std::abs(int(hw.pixels[i]) - int(compute.pixels[i])) > 1;
        written += hw.pixels[i] < 255;
    }
    EXPECT_GT(written, hw.pixels.size() / 10) << "the atlases hold casters";
    EXPECT_LT(double(differ) / double(hw.pixels.size()), 0.0005) << differ << " texels differ";
}

TEST_F(ComputeRasterTest, BuiltInFieldMatchesTheHardwarePath) {
    Renderer renderer(device(), loadScene("gen:field:4:4"));
    Settings settings;
    settings.shadows.directional.atlasSize = 512;
    settings.shadows.spot.atlasSize = 512;
    for (uint32_t light : {0u, 1u, 3u}) {
        const double difference = classDifference(render(renderer, ShadowRaster::Hw, light, settings).image,
                                                  render(renderer, ShadowRaster::Compute, light, settings).image);
        EXPECT_LT(difference, 0.0005) << "light " << light;
    }
}

// Boxes (one meshlet of 12 triangles each) share work items: a million small objects must not cost a
// million workgroups of 12 busy threads. The packed items draw what the hardware draws.
TEST_F(ComputeRasterTest, SmallObjectsShareWorkItemsAndMatchTheHardwarePath) {
    Renderer renderer(device(), loadScene("gen:boxes:3000"));
    Settings settings;
    settings.shadows.directional.atlasSize = 512;
    const RenderResult compute = render(renderer, ShadowRaster::Compute, 0, settings);
    const RenderResult hw = render(renderer, ShadowRaster::Hw, 0, settings);
    uint64_t boxesInTiles = 0;
    for (const AtlasDrawStats& atlas : compute.stats.atlases) boxesInTiles += atlas.triangles / 12;
    ASSERT_GT(boxesInTiles, 2000u);
    std::printf("%llu boxes in tiles, %llu work items\n", (unsigned long long)boxesInTiles,
                (unsigned long long)compute.stats.rasterWorkItems);
    EXPECT_LT(compute.stats.rasterWorkItems * 10, boxesInTiles) << "21 boxes to an item, but for each tile's last";
    EXPECT_LT(classDifference(hw.image, compute.image), 0.0005);
}

// Frames of the demo scene with shadows.raster = auto, the camera moved by `step` metres per frame.
std::vector<FrameStats> autoRasterFrames(Device& device, float step, int count) {
    Renderer renderer(device, makeDemoScene());
    const CameraView still = resolveCameraView(renderer.scene(), 64, 36);
    RenderRequest request;
    request.width = 64;
    request.height = 36;
    Settings settings;  // shadows.raster = auto by default
    settings.shadows.directional.atlasSize = 256;
    settings.shadows.spot.atlasSize = 256;
    std::vector<FrameStats> frames;
    for (int i = 0; i < count; ++i) {
        renderer.submitFrame(request, settings, translatedCameraView(still, float(i) * step * wsCameraRight(still)));
        renderer.waitIdle();
        for (FrameStats& f : renderer.takeCompletedFrames()) frames.push_back(std::move(f));
    }
    return frames;
}

TEST_F(ComputeRasterTest, AutoMeasuresBothPathsThenKeepsTheFaster) {
    const std::vector<FrameStats> frames = autoRasterFrames(device(), 0.05f, 16);  // a moving camera: tiles drawn
    ASSERT_EQ(frames.size(), 16u);
    EXPECT_EQ(frames[0].shadowRaster, "hw");
    bool sawCompute = false;
    for (const FrameStats& f : frames) sawCompute |= f.shadowRaster == "compute";
    EXPECT_TRUE(sawCompute) << "auto measures the compute path too";
    const std::string choice = frames.back().shadowRasterChoice;
    EXPECT_NE(choice.find("measured"), std::string::npos) << choice;
    EXPECT_EQ(choice.rfind("auto: " + frames.back().shadowRaster, 0), 0u) << "the last frame uses the choice: " << choice;
}

TEST_F(ComputeRasterTest, AutoDoesNotMeasureFramesWhoseTilesWereCached) {
    const std::vector<FrameStats> frames = autoRasterFrames(device(), 0.0f, 16);  // a still camera
    ASSERT_EQ(frames.size(), 16u);
    EXPECT_GT(frames.back().tilesReused, 0u);
    EXPECT_EQ(frames.back().tilesRendered, 0u);
    EXPECT_EQ(frames.back().shadowRasterChoice, "auto: measuring") << "only the first frame drew tiles";
}

// A horizontal quad whose corners land exactly on texel centres of cascade 0: both rasterizers must
// cover exactly the texels of Vulkan's top-left rule, columns i0 <= i < i1 and rows j0 <= j < j1.
Scene quadOnTexelCentres(const std::array<int, 4>& window, const CameraView& view, const Settings& settings) {
    auto build = [&](const std::array<glm::vec3, 4>& corners) {
        SceneBuilder builder;
        Material matte;
        const uint32_t material = builder.addMaterial(matte);
        Mesh quad;
        for (const glm::vec3& corner : corners) quad.vertices.push_back({corner, glm::vec3(0, 1, 0), glm::vec2(0.0f)});
        quad.indices = {0, 1, 2, 0, 2, 3};
        quad.materialIndex = material;
        builder.addInstance(builder.addMesh(quad), glm::mat4(1.0f));
        builder.addLight(makeDirectionalLight(glm::vec3(0.3f, -1.0f, 0.2f), 3.0f));
        return builder.build();
    };
    constexpr float kHeight = 1.0f;
    const Scene probe = build({glm::vec3(-1, kHeight, -1), glm::vec3(1, kHeight, -1), glm::vec3(1, kHeight, 1),
                               glm::vec3(-1, kHeight, 1)});
    // Tile 0's projection does not depend on the casters: invert its affine map of the plane y = kHeight.
    const ShadowTile tile = ShadowPlanner::plan(probe, view, settings.shadows).directional.tiles.at(0);
    auto windowOf = [&](glm::vec3 ws) {
        const glm::vec4 clip = tile.clipFromWorld * glm::vec4(ws, 1.0f);
        return glm::dvec2(tile.rect.offset) + (glm::dvec2(clip) / double(clip.w) * 0.5 + 0.5) * double(tile.rect.size);
    };
    const glm::dvec2 origin = windowOf({0, kHeight, 0});
    const glm::dmat2 map(windowOf({1, kHeight, 0}) - origin, windowOf({0, kHeight, 1}) - origin);
    const glm::dmat2 inverse = glm::inverse(map);
    auto worldAt = [&](double x, double y) {
        const glm::dvec2 xz = inverse * (glm::dvec2(x + 0.5, y + 0.5) - origin);
        return glm::vec3(float(xz.x), kHeight, float(xz.y));
    };
    return build({worldAt(window[0], window[1]), worldAt(window[2], window[1]), worldAt(window[2], window[3]),
                  worldAt(window[0], window[3])});
}

// Quads of three sizes reach the compute rasterizer's three levels: triangles walked by their thread
// (bounds of at most 32 texels), by their workgroup in blocks (up to 2048) and in chunks.
TEST_F(ComputeRasterTest, BothRasterizersFollowTheTopLeftRuleOnTexelCentres) {
    Settings settings;
    settings.shadows.directional.atlasSize = 256;
    settings.shadows.directional.cascadeCount = 1;
    // The quads lie where the camera may not see them, over nothing: receiver culling would leave them out.
    settings.shadows.directional.receiverCulling = false;
    Camera camera = makeLookAtCamera(glm::vec3(0, 6, 6), glm::vec3(0), 0.9f);
    const CameraView view = makeCameraView(camera, 64, 64);
    struct Case {
        const char* level;
        std::array<int, 4> window;  // texel centres (i0, j0) .. (i1, j1)
    };
    for (const Case& c : {Case{"thread", {101, 91, 103, 94}}, Case{"workgroup", {100, 90, 125, 121}},
                          Case{"chunks", {100, 90, 140, 150}}}) {
        Scene scene = quadOnTexelCentres(c.window, view, settings);
        scene.camera = camera;
        for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
            // A renderer each: a second frame's tight fit would follow the first frame's depth (read back
            // when it is ready), moving the cascade off the texel grid the quad was placed on.
            Renderer renderer(device(), scene);
            settings.shadows.raster = raster;
            RenderRequest request;
            request.width = request.height = 64;
            request.captureAtlas = true;
            const RenderResult result = renderer.render(request, settings);
            size_t covered = 0, outside = 0;
            for (uint32_t y = 0; y < 256; ++y)
                for (uint32_t x = 0; x < 256; ++x) {
                    if (result.atlas.at(x, y) == 255) continue;
                    const bool inside = int(x) >= c.window[0] && int(x) < c.window[2] && int(y) >= c.window[1] &&
                                        int(y) < c.window[3];
                    (inside ? covered : outside)++;
                }
            const std::string name = std::string(shadowRasterName(raster)) + ", " + c.level;
            EXPECT_EQ(covered, size_t(c.window[2] - c.window[0]) * size_t(c.window[3] - c.window[1])) << name;
            EXPECT_EQ(outside, 0u) << name;
            if (raster != ShadowRaster::Compute) continue;
            const std::string level = c.level;
            EXPECT_EQ(result.stats.rasterMediumTriangles > 0, level == "workgroup") << name;
            EXPECT_EQ(result.stats.rasterLargeTriangles > 0, level == "chunks") << name;
        }
    }
}

}  // namespace
}  // namespace penumbra::test


namespace penumbra::test {
namespace {

TEST_F(ComputeRasterTest, OverflowingQueuesGrowAndTheFrameIsDrawnAgain) {
    RendererOptions tiny;
    tiny.rasterLargeQueue = 4;  // the demo's ground alone needs more
    tiny.rasterChunkQueue = 8;
    Renderer small(device(), makeDemoScene(), tiny), normal(device(), makeDemoScene());
    Settings settings;
    const RenderResult grown = render(small, ShadowRaster::Compute, 0, settings);
    EXPECT_EQ(grown.stats.rasterDropped, 0u) << "render() drew the frame again with larger queues";
    EXPECT_GT(grown.stats.rasterLargeTriangles, 4u);
    EXPECT_TRUE(grown.image.pixels == render(normal, ShadowRaster::Compute, 0, settings).image.pixels);
}

TEST_F(ComputeRasterTest, AnOverflowingWorkQueueGrowsAndTheFrameIsDrawnAgain) {
    RendererOptions tiny;
    tiny.rasterWorkQueue = 2;  // the demo's casters in four cascades need more
    Renderer small(device(), makeDemoScene(), tiny), normal(device(), makeDemoScene());
    Settings settings;
    const RenderResult grown = render(small, ShadowRaster::Compute, 0, settings);
    EXPECT_EQ(grown.stats.rasterDropped, 0u) << "render() drew the frame again with a larger queue";
    EXPECT_TRUE(grown.image.pixels == render(normal, ShadowRaster::Compute, 0, settings).image.pixels);
}

TEST_F(ComputeRasterTest, VirtualPagesDrawnWithAnOverflowingWorkQueueAreDrawnAgain) {
    // The pages of a frame that dropped work items hold holes: the renderer redraws every page.
    RendererOptions tiny;
    tiny.rasterWorkQueue = 2;
    Renderer small(device(), makeDemoScene(), tiny), normal(device(), makeDemoScene());
    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.virtualMaps.poolPages = 256;
    settings.shadows.virtualMaps.resolution = 4096;
    const RenderResult grown = render(small, ShadowRaster::Compute, 0, settings);
    EXPECT_EQ(grown.stats.rasterDropped, 0u);
    EXPECT_GT(grown.stats.virtualPages.drawn, 0u);
    EXPECT_TRUE(grown.image.pixels == render(normal, ShadowRaster::Compute, 0, settings).image.pixels);
}

}  // namespace
}  // namespace penumbra::test
