// The renderer as a real-time engine: frames through the persistent path equal one-shot
// renders, steady-state frames allocate nothing and submit once, a renderer gives back everything it
// made, and scene changes between frames show up in the next frame.
#include <filesystem>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/error.h"

#include "penumbra/scene_loading.h"
#include "render/raster_choice.h"
#include "render_test_support.h"
#include "spot_render_scenes.h"

namespace penumbra::test {
namespace {

RenderRequest request(OutputMode output, uint32_t width = 96, uint32_t height = 54) {
    RenderRequest r;
    r.width = width;
    r.height = height;
    r.output = output;
    return r;
}

// The settings of frame `i` of a run that changes atlas sizes, cascade count, filters, blends, the
// spot atlas and the screen-space resolve every frame.
Settings varyingSettings(uint32_t i) {
    Settings settings;
    const uint32_t sizes[] = {256, 512, 1024};
    settings.shadows.directional.atlasSize = sizes[i % 3];
    settings.shadows.spot.atlasSize = sizes[(i / 3) % 3];
    settings.shadows.directional.cascadeCount = 1 + i % 4;
    settings.shadows.directional.filter = ShadowFilter(i % 4);
    settings.shadows.spot.filter = ShadowFilter((i / 2) % 4);
    settings.shadows.directional.cascadeBlend = CascadeBlend((i / 5) % 3);
    settings.shadows.screenSpace = i % 7 == 3;
    return settings;
}

class PersistentFrameTest : public RenderTest {};

TEST_F(PersistentFrameTest, FrameAfterManyOthersEqualsAOneShotRender) {
    const Scene scene = makeDemoScene();
    Settings final;
    final.shadows.directional.filter = ShadowFilter::PCF5x5;
    final.shadows.directional.cascadeBlend = CascadeBlend::Soft;
    // render.mainView = auto may have chosen the visibility buffer after its first frames (an image
    // within 2 levels of the forward one, tested in visibility_view_test.cpp); this test is exact.
    final.render.mainView = MainView::Forward;
    for (OutputMode output : {OutputMode::Color, OutputMode::ShadowAov, OutputMode::CascadesAov}) {
        Renderer oneShot(device(), scene);
        const Image expected = oneShot.render(request(output), final).image;
        Renderer persistent(device(), scene);
        const CameraView view = resolveCameraView(scene, 96, 54);
        for (uint32_t i = 0; i < 12; ++i) persistent.submitFrame(request(OutputMode(i % 3)), varyingSettings(i), view);
        const Image actual = persistent.render(request(output), final).image;
        ASSERT_EQ(actual.pixels.size(), expected.pixels.size());
        EXPECT_TRUE(actual.pixels == expected.pixels) << "output " << int(output);
    }
}

TEST_F(PersistentFrameTest, SubmittedFramesReportTheirStatsOnceFinished) {
    Renderer renderer(device(), makeDemoScene());
    const CameraView view = resolveCameraView(renderer.scene(), 96, 54);
    std::vector<uint64_t> submitted;
    for (int i = 0; i < 5; ++i) submitted.push_back(renderer.submitFrame(request(OutputMode::Color), {}, view));
    renderer.waitIdle();
    const std::vector<FrameStats> finished = renderer.takeCompletedFrames();
    ASSERT_EQ(finished.size(), submitted.size());
    for (size_t i = 0; i < finished.size(); ++i) {
        EXPECT_EQ(finished[i].frameIndex, submitted[i]);
        EXPECT_GT(finished[i].submitToFenceMilliseconds, 0.0);
        ASSERT_EQ(finished[i].atlases.size(), 2u);
        EXPECT_GT(finished[i].atlases[0].draws, 0u);
    }
    EXPECT_TRUE(renderer.takeCompletedFrames().empty());
}

TEST_F(PersistentFrameTest, SteadyStateFramesMakeNothingWaitForNothingAndSubmitOnce) {
    Renderer renderer(device(), makeDemoScene());
    const CameraView view = resolveCameraView(renderer.scene(), 96, 54);
    Settings settings;
    settings.shadows.screenSpace = true;
    for (int i = 0; i < 3; ++i) renderer.submitFrame(request(OutputMode::Color), settings, view);
    const DeviceObjectCounts before = device().liveObjects();
    for (int i = 0; i < 8; ++i) renderer.submitFrame(request(OutputMode::Color), settings, view);
    const DeviceObjectCounts after = device().liveObjects();
    EXPECT_EQ(after.objectsCreated, before.objectsCreated);
    EXPECT_EQ(after.memoryAllocations, before.memoryAllocations);
    EXPECT_EQ(after.submits, before.submits + 8);
    EXPECT_EQ(after.deviceWaits, before.deviceWaits);
    EXPECT_EQ(after.total(), before.total());
}

TEST_F(PersistentFrameTest, TargetsAreRemadeOnlyWhenTheirSizeChanges) {
    Renderer renderer(device(), makeDemoScene());
    Settings settings;
    renderer.render(request(OutputMode::Color), settings);
    const uint64_t made = device().liveObjects().objectsCreated;
    renderer.render(request(OutputMode::Color), settings);
    EXPECT_EQ(device().liveObjects().objectsCreated, made);
    settings.shadows.directional.atlasSize = 2048;
    renderer.render(request(OutputMode::Color), settings);
    // The directional atlas and both rasterizers' depth, sized by the larger atlas (shadows.raster auto,
    // still measuring: the compute one's buffer and the hardware one's D32 target).
    const DeviceObjectCounts counts = device().liveObjects();
    EXPECT_EQ(counts.objectsCreated, made + 3);
    // The counts name the last one made (what `penumbra bench` prints when a steady state makes any).
    const std::string last(counts.lastObjectName.data());
    EXPECT_TRUE(last.find("atlas") != std::string::npos || last.find("depth") != std::string::npos) << last;
}

// shadows.raster = auto measures both rasterizers, each with its own tile depth (a 4096² atlas's is 64 MiB),
// then keeps only the chosen one's: the live buffers and textures are those of that rasterizer set outright.
TEST_F(PersistentFrameTest, AutoRasterKeepsOnlyTheChosenRasterizersDepthOnceDecided) {
    struct Live {
        uint32_t buffers, textures;
        std::string raster;
    };
    auto liveAfterAMovingRun = [&](ShadowRaster raster) {
        Renderer renderer(device(), makeDemoScene());
        Settings settings;
        settings.shadows.raster = raster;
        const CameraView still = resolveCameraView(renderer.scene(), 48, 27);
        std::vector<FrameStats> finished;
        std::string lastRaster;
        for (int i = 0; i < 2 * (RasterChoice::kWarmup + RasterChoice::kSamples) + 6; ++i) {  // every frame draws
            renderer.submitFrame(request(OutputMode::Color, 48, 27), settings,
                                 translatedCameraView(still, 0.05f * float(i) * wsCameraRight(still)));
            renderer.takeCompletedFrames(finished);
        }
        renderer.waitIdle();
        renderer.takeCompletedFrames(finished);
        if (!finished.empty()) lastRaster = finished.back().shadowRaster;
        const DeviceObjectCounts counts = device().liveObjects();
        return Live{counts.buffers, counts.textures, lastRaster};
    };
    const Live automatic = liveAfterAMovingRun(ShadowRaster::Auto);
    ASSERT_TRUE(automatic.raster == "hw" || automatic.raster == "compute") << automatic.raster;
    const Live chosen = liveAfterAMovingRun(automatic.raster == "hw" ? ShadowRaster::Hw : ShadowRaster::Compute);
    EXPECT_EQ(automatic.buffers, chosen.buffers);
    EXPECT_EQ(automatic.textures, chosen.textures);
}

// Every frame changes the settings (atlas sizes, cascades, filters, blend, screen-space shadows) and
// the shadowed lights; each setting comes back several times in 60 frames (every lit-pass variant they
// reach is a compile of seconds on lavapipe, so more frames would test the same objects at length).
TEST_F(PersistentFrameTest, SixtyChangingFramesLeaveNoDeviceObjectOnceTheRendererIsGone) {
    const DeviceObjectCounts before = device().liveObjects();
    {
        Renderer renderer(device(), makeDemoScene());
        const CameraView view = resolveCameraView(renderer.scene(), 48, 27);
        const std::vector<Light> lights = renderer.scene().lights;
        for (uint32_t i = 0; i < 60; ++i) {
            // The number of shadowed lights changes too: lights drop in and out of the shadow budget.
            for (uint32_t l = 0; l < lights.size(); ++l) {
                Light light = lights[l];
                if ((i / 5 + l) % 3 == 0) light.shadows = LightShadows::None;
                if ((i / 10 + l) % 4 == 1) light.shadows = LightShadows::Hard;
                renderer.setLight(l, light);
            }
            if (i % 20 == 19) renderer.render(request(OutputMode::ShadowAov, 48, 27), varyingSettings(i));
            else renderer.submitFrame(request(OutputMode(i % 3), 48, 27), varyingSettings(i), view);
        }
    }
    const DeviceObjectCounts after = device().liveObjects();
    EXPECT_EQ(after.buffers, before.buffers);
    EXPECT_EQ(after.textures, before.textures);
    EXPECT_EQ(after.samplers, before.samplers);
    EXPECT_EQ(after.pipelines, before.pipelines);
    EXPECT_EQ(after.textureTables, before.textureTables);
    EXPECT_EQ(after.memoryBlocks, before.memoryBlocks);
    EXPECT_EQ(after.pendingDestroys, 0u);
}

TEST_F(PersistentFrameTest, GpuObjectsCarryDebugNames) {
    const uint64_t before = device().liveObjects().debugNamesSet;
    Renderer renderer(device(), makeDemoScene());
    renderer.render(request(OutputMode::Color), {});
    // The validation layer brings VK_EXT_debug_utils: every buffer, image, view and pipeline is named.
    EXPECT_GT(device().liveObjects().debugNamesSet, before + 20);
}

// ---- scene changes between frames

class SceneUpdateTest : public RenderTest {
protected:
    Image shadowOf(Renderer& renderer, uint32_t light = 0) {
        return renderer.render(shadowAov(light, 96), smallSpotAtlas()).image;
    }
};

TEST_F(SceneUpdateTest, MovedCasterRendersAsAFreshSceneWithItMoved) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    Renderer renderer(device(), scene);
    const Image before = shadowOf(renderer);
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.5f, 0.4f));
    renderer.setInstanceTransform(1, moved);
    const Image after = shadowOf(renderer);
    scene.instances[1].worldFromObject = moved;
    scene.instances[1].wsBounds = scene.meshes[scene.instances[1].meshIndex].osBounds.transformed(moved);
    Renderer fresh(device(), scene);
    EXPECT_TRUE(after.pixels == shadowOf(fresh).pixels);
    EXPECT_FALSE(after.pixels == before.pixels);
}

// Ten thousand scattered moves in one frame (scene_scatter.comp writes them to their places): their
// staging (1.2 MB) outgrows the frame's first upload ring (1 MiB), which grows while the frame records.
TEST_F(SceneUpdateTest, TenThousandScatteredMovesInOneFrameRenderAsAFreshSceneWithThemMoved) {
    Scene scene = makeBoxesScene(20000);
    Settings settings;
    settings.shadows.maxDistance = 500.0f;  // the camera sees the field from 180 to 383 m
    Renderer renderer(device(), scene);
    const Image before = renderer.render(shadowAov(0, 96), settings).image;
    for (uint32_t instance = 1; instance < scene.instances.size(); instance += 2) {  // every other box: 10k runs
        // 30 m up: its shadow lands tens of metres away.
        const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 30.0f, 0.0f)) * scene.instances[instance].worldFromObject;
        renderer.setInstanceTransform(instance, moved);
        scene.instances[instance].worldFromObject = moved;
        scene.instances[instance].wsBounds = scene.meshes[scene.instances[instance].meshIndex].osBounds.transformed(moved);
    }
    const RenderResult after = renderer.render(shadowAov(0, 96), settings);
    EXPECT_GT(after.stats.sceneBytesUploaded, 1ull << 20);
    Renderer fresh(device(), scene);
    EXPECT_TRUE(after.image.pixels == fresh.render(shadowAov(0, 96), settings).image.pixels);
    EXPECT_GT(shareOfPixelsOver(after.image, before, 64), 0.005) << "the boxes' shadows must have moved";
}

// The tight cascade fit of a one-shot render reads the view's depth before the frame: drawn from the
// instances as they are after the edit, not as the GPU held them before it.
TEST_F(SceneUpdateTest, AOneShotRenderAfterAnEditFitsTheCascadesToTheEditedScene) {
    Light sun = makeDirectionalLight(glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f)), 3.0f);
    Scene scene = boxUnderLight(sun);
    Settings settings;
    settings.shadows.directional.fit = CascadeFit::Tight;
    Renderer renderer(device(), scene);
    const Image before = renderer.render(shadowAov(0, 96), settings).image;
    // The wall moves far off: the visible depth range changes, and with it the tight fit's cascades.
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(-4.5f, 0.75f, -4.0f));
    renderer.setInstanceTransform(2, moved);
    const Image after = renderer.render(shadowAov(0, 96), settings).image;
    scene.instances[2].worldFromObject = moved;
    scene.instances[2].wsBounds = scene.meshes[scene.instances[2].meshIndex].osBounds.transformed(moved);
    Renderer fresh(device(), scene);
    EXPECT_TRUE(after.pixels == fresh.render(shadowAov(0, 96), settings).image.pixels);
    EXPECT_FALSE(after.pixels == before.pixels);
}

TEST_F(SceneUpdateTest, OnlyTheChangedInstanceIsUploaded) {
    Renderer renderer(device(), boxUnderLight(testSpot(LightShadows::Soft)));
    const RenderResult first = renderer.render(shadowAov(0, 32), {});
    EXPECT_EQ(first.stats.sceneBytesUploaded, 0u);
    renderer.setInstanceTransform(2, glm::translate(glm::mat4(1.0f), glm::vec3(1, 0.75f, 1)));
    // One InstanceData, its CullInstance and its index (where scene_scatter.comp writes them).
    EXPECT_EQ(renderer.render(shadowAov(0, 32), {}).stats.sceneBytesUploaded, 64u + 48u + 4u);
    EXPECT_EQ(renderer.render(shadowAov(0, 32), {}).stats.sceneBytesUploaded, 0u);
}

TEST_F(SceneUpdateTest, TurnedLightRendersAsAFreshSceneWithItTurned) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Hard));
    Renderer renderer(device(), scene);
    shadowOf(renderer);
    Light turned = scene.lights[0];
    turned.wsDirection = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    turned.wsPosition = glm::vec3(-1.0f, 4.5f, -0.5f);
    renderer.setLight(0, turned);
    scene.lights[0] = turned;
    Renderer fresh(device(), scene);
    EXPECT_TRUE(shadowOf(renderer).pixels == shadowOf(fresh).pixels);
}

TEST_F(SceneUpdateTest, MaterialShadowModeOffRemovesTheShadowOnTheNextFrame) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    Renderer renderer(device(), scene);
    const Image shadowed = shadowOf(renderer);
    Material off = scene.materials[0];
    off.shadows = MaterialShadowMode::Off;
    renderer.setMaterial(0, off);
    const Image unshadowed = shadowOf(renderer);
    EXPECT_FALSE(shadowed.pixels == unshadowed.pixels);
    EXPECT_EQ(*std::min_element(unshadowed.pixels.begin(), unshadowed.pixels.end()), 255);
}

TEST_F(SceneUpdateTest, InstanceThatStopsCastingLeavesNoShadow) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    Renderer renderer(device(), scene);
    shadowOf(renderer);
    for (uint32_t i = 0; i < scene.instances.size(); ++i) renderer.setInstanceCastShadows(i, false);
    const Image image = shadowOf(renderer);
    EXPECT_EQ(*std::min_element(image.pixels.begin(), image.pixels.end()), 255);
}

TEST_F(SceneUpdateTest, BadChangesAreRefusedWithAnError) {
    Renderer renderer(device(), boxUnderLight(testSpot(LightShadows::Soft)));
    EXPECT_THROW(renderer.setInstanceTransform(99, glm::mat4(1.0f)), Error);
    Light bad = renderer.scene().lights[0];
    bad.wsDirection = glm::vec3(0.0f);
    EXPECT_THROW(renderer.setLight(0, bad), Error);
    EXPECT_THROW(renderer.setInstanceCastShadows(99, false), Error);
}

// ---- pipeline variants

class PipelineVariantTest : public RenderTest {};

TEST_F(PipelineVariantTest, GenericVariantGivesTheSpecializedImage) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    scene.lights.push_back(testPoint(LightShadows::Hard));
    RendererOptions generic;
    generic.forceGenericVariants = true;
    Renderer specialized(device(), scene), fallback(device(), scene, generic);
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF7x7}) {
        Settings settings = smallSpotAtlas();
        settings.shadows.spot.filter = filter;
        for (uint32_t light : {0u, 1u})
            EXPECT_TRUE(specialized.render(shadowAov(light, 96), settings).image.pixels ==
                        fallback.render(shadowAov(light, 96), settings).image.pixels)
                << "filter " << int(filter) << " light " << light;
        RenderRequest colour = shadowAov(0, 96);
        colour.output = OutputMode::Color;
        const Image a = specialized.render(colour, settings).image, b = fallback.render(colour, settings).image;
        std::printf("filter %d: %.5f %% over 0, %.5f %% over 1\n", int(filter), 100.0 * shareOfPixelsOver(a, b, 0),
                    100.0 * shareOfPixelsOver(a, b, 1));
        // The shadow terms above are equal bit for bit; the colour may round one level apart: lavapipe
        // compiles the two variants' lighting (constant vs runtime loop bounds) to differently ordered
        // float arithmetic, and one pixel in ~10 000 came out one level off in some runs (CI and here,
        // 2026-12-02, the same binary passing and failing). More than one level is a real difference.
        EXPECT_EQ(shareOfPixelsOver(a, b, 1), 0.0) << "filter " << int(filter);
    }
}

// shadows.spot.mode = virtual frames draw with the one variant that compiles only the faces' sampling;
// the generic variant (every mode bit) gives the same shadow terms.
TEST_F(PipelineVariantTest, GenericVariantGivesTheVirtualFaceVariantsImage) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    scene.lights.push_back(testPoint(LightShadows::Hard));
    RendererOptions generic;
    generic.forceGenericVariants = true;
    Renderer specialized(device(), scene), fallback(device(), scene, generic);
    Settings settings = smallSpotAtlas();
    settings.shadows.spot.mode = SpotShadowMode::Virtual;
    settings.shadows.virtualMaps.faceResolution = 2048;
    const auto darkShare = [](const Image& image) {
        size_t dark = 0;
        for (uint8_t value : image.pixels) dark += value < 128;
        return double(dark) / double(image.pixels.size());
    };
    for (uint32_t light : {0u, 1u}) {
        const RenderResult a = specialized.render(shadowAov(light, 96), settings);
        EXPECT_GT(a.stats.virtualFacePages.requested, 0u);
        EXPECT_LT(darkShare(a.image), 0.99) << "light " << light;
        EXPECT_GT(darkShare(a.image), 0.01) << "light " << light << ": some shadow";
        EXPECT_TRUE(a.image.pixels == fallback.render(shadowAov(light, 96), settings).image.pixels) << "light " << light;
    }
}

TEST_F(PipelineVariantTest, AfterBackgroundWarmupNoSettingChangeBuildsAPipeline) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    scene.lights.push_back(testPoint(LightShadows::Hard));
    RendererOptions options;
    options.warmup = PipelineWarmup::Background;
    Renderer renderer(device(), scene, options);
    renderer.buildAllPipelines();
    EXPECT_EQ(renderer.pipelineBuildsPending(), 0u);
    const CameraView view = resolveCameraView(renderer.scene(), 32, 32);
    uint64_t made = 0;
    for (uint32_t i = 0; i < 48; ++i) {
        if (i == 24) made = device().liveObjects().objectsCreated;  // the first round made the targets
        Settings settings = varyingSettings(i);
        settings.shadows.spot.atlasSize = 1024;
        settings.shadows.directional.atlasSize = 1024;
        Light spot = renderer.scene().lights[0];
        spot.shadows = LightShadows(i % 3);  // none, hard, soft: every spot/point specialization
        renderer.setLight(0, spot);
        renderer.submitFrame(request(OutputMode(i % 3), 32, 32), settings, view);
    }
    renderer.waitIdle();
    EXPECT_EQ(device().liveObjects().objectsCreated, made);
}

// penumbra-viewer reloads a scene by making its renderer again, maybe while variants still build on the
// worker thread: the pipeline layouts those builds use must outlive them (lavapipe crashed otherwise).
TEST_F(PipelineVariantTest, RendererDestroyedWhileItsVariantsBuildLeavesNoValidationMessage) {
    Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    RendererOptions options;
    options.warmup = PipelineWarmup::Background;
    for (int round = 0; round < 6; ++round) {
        Renderer renderer(device(), scene, options);
        renderer.submitFrame(request(OutputMode::Color, 16, 16), {}, resolveCameraView(renderer.scene(), 16, 16));
    }
}

TEST_F(PipelineVariantTest, PipelineCacheIsWrittenToTheCacheFolder) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("penumbra_cache_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(folder);
    {
        DeviceOptions options = testDeviceOptions();
        options.pipelineCache = folder.string();
        Device own(options);
        Renderer renderer(own, makeDemoScene());
        renderer.render(request(OutputMode::Color, 16, 16), {});
    }
    ASSERT_TRUE(std::filesystem::is_directory(folder));
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        EXPECT_EQ(entry.path().extension(), ".bin");
        EXPECT_GE(entry.file_size(), 16u);  // at least the header the driver checks on load
        ++files;
    }
    EXPECT_EQ(files, 1u);
    {
        DeviceOptions options = testDeviceOptions();
        options.pipelineCache = folder.string();
        Device again(options);  // reads it back
        EXPECT_EQ(again.validationMessageCount(), 0u);
    }
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace penumbra::test
