// The renderer at the limits: textures and atlases over the device's image size
// (a device limit made small with gpu::DeviceFaultInjection::maxImageSize), culling lists split over
// storage buffers (maxStorageBufferRange made small), more lights than the shader
// arrays hold, degenerate triangles and singular transforms, scenes 10^6 m across, bad camera views,
// a damaged pipeline cache file.
// Each is a warning with a fallback or a one-line Error, with no validation message and no NaN.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/error.h"
#include "penumbra/scene_builder.h"
#include "render_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A box on a ground under a sun, sized `scale` (1 = a 1 m box on a 20 m ground), seen from above.
Scene boxOnGround(float scale = 1.0f) {
    SceneBuilder builder;
    Material matte;
    matte.metallic = 0.0f;
    const uint32_t material = builder.addMaterial(matte);
    builder.addInstance(builder.addMesh(makePlaneMesh(glm::vec2(20.0f * scale), material)), glm::mat4(1.0f));
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f * scale), material)),
                        glm::translate(glm::mat4(1.0f), {0.0f, 0.5f * scale, 0.0f}));
    builder.addLight(makeDirectionalLight({0.3f, -1.0f, -0.2f}, 3.0f));
    builder.setCamera(makeLookAtCamera(glm::vec3(0.0f, 4.0f, 6.0f) * scale, glm::vec3(0.0f), 0.9f, 0.1f * scale));
    return builder.build();
}

RenderRequest request(OutputMode output = OutputMode::Color, uint32_t width = 96, uint32_t height = 64) {
    RenderRequest r;
    r.width = width;
    r.height = height;
    r.output = output;
    return r;
}

Device smallDevice(uint32_t maxImageSize) {
    gpu::DeviceFaultInjection faults;
    faults.maxImageSize = maxImageSize;
    return DeviceAccess::makeDevice({testDeviceOptions(), faults});
}

constexpr uint32_t kSmallAtlas = 256;

Device smallStorageRangeDevice(uint64_t maxStorageBufferRange) {
    gpu::DeviceFaultInjection faults;
    faults.maxStorageBufferRange = maxStorageBufferRange;
    return DeviceAccess::makeDevice({testDeviceOptions(), faults});
}

uint32_t darkPixels(const Image& aov) {
    uint32_t count = 0;
    for (uint8_t value : aov.pixels) count += value < 128;
    return count;
}

}  // namespace

TEST_F(RenderTest, TextureOverTheDeviceLimitIsDownscaledWithAWarning) {
    Device small(smallDevice(256));
    Scene scene = boxOnGround();
    Texture texture;
    texture.name = "big";
    texture.rgba = Image(1024, 512, 4, 200);
    scene.textures.push_back(texture);
    scene.materials[0].baseColorTexture = 0;
    Renderer renderer(small, scene);
    const RenderResult result = renderer.render(request(), {});
    EXPECT_TRUE(hasWarning(result.stats, "texture 0 'big' is 1024x512, larger than the device's 256 texel limit: "
                                         "downscaled to 256x128"));
    EXPECT_EQ(small.validationMessageCount(), 0u);
}

TEST_F(RenderTest, AtlasOverTheDeviceLimitIsMadeAsLargeAsItAllowsWithAWarning) {
    Device small(smallDevice(512));
    Renderer renderer(small, boxOnGround());
    Settings settings;
    settings.shadows.directional.atlasSize = 2048;
    const RenderResult result = renderer.render(request(OutputMode::ShadowAov), settings);
    EXPECT_TRUE(hasWarning(result.stats, "shadows.directional.atlasSize = 2048 is larger than the device's largest "
                                         "image (512): using 512"));
    EXPECT_GT(darkPixels(result.image), 0u);  // still a shadow, from the smaller atlas
    EXPECT_EQ(small.validationMessageCount(), 0u);
}

TEST_F(RenderTest, OutputLargerThanTheDeviceLimitIsAnError) {
    Device small(smallDevice(256));
    Renderer renderer(small, boxOnGround());
    try {
        renderer.render(request(OutputMode::Color, 300, 100), {});
        FAIL() << "rendered past the device's image size";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the output size 300x100 is out of range (allowed 1..256 per side"),
                  std::string::npos)
            << e.what();
    }
}

// The culling pass's 34 lists (32 tiles, the main view's 2) of one entry per instance, on a device whose
// storage buffers seem to hold 16 of them: split over three buffers (tiles 0-15, tiles 16-31, the main
// view's lists), each read by its tiles' draws, the compute rasterizers and the visibility buffer. The
// scene has 18 tiles, so both tile buffers are drawn from. Every pixel is the one a single buffer gives.
// (Small atlases: the compute rasterizer's queues fit that small range too, and hold what they draw.)
TEST_F(RenderTest, CullingListsSplitOverStorageBuffersDrawTheSameImage) {
    const Scene scene = boxesWithEighteenShadowTiles(kSplitListBoxes);
    Device split(smallStorageRangeDevice(kSplitListsPerBuffer * sizeof(uint32_t) * scene.instances.size()));
    for (MainView mainView : {MainView::Forward, MainView::Visibility})
        for (ShadowRaster raster : {ShadowRaster::Hw, ShadowRaster::Compute}) {
            Settings settings;
            settings.render.mainView = mainView;
            settings.shadows.raster = raster;
            settings.shadows.directional.atlasSize = settings.shadows.spot.atlasSize = kSmallAtlas;
            Renderer renderer(split, scene);
            const RenderResult splitFrame = renderer.render(request(), settings);
            EXPECT_TRUE(splitFrame.stats.warnings.empty()) << splitFrame.stats.warnings.front();  // nothing left out
            EXPECT_EQ(splitFrame.image.pixels, renderScene(scene, request(), settings).image.pixels)
                << mainViewName(mainView) << ", raster " << int(raster);
        }
    EXPECT_EQ(split.validationMessageCount(), 0u);
}

TEST_F(RenderTest, LightsBeyondTheShaderArraysAreLeftOutByNameWithAWarning) {
    Scene scene = boxOnGround();
    for (int i = 0; i < 1030; ++i) {
        Light point = makePointLight({0.2f * float(i % 40) - 4.0f, 2.0f, 0.2f * float(i / 40) - 3.0f}, 0.01f, 1.0f);
        point.name = "p" + std::to_string(i);
        point.shadows = LightShadows::None;
        scene.lights.push_back(point);
    }
    for (int i = 0; i < 5; ++i) scene.lights.push_back(makeDirectionalLight({0.1f * float(i), -1.0f, 0.0f}, 0.1f));
    const RenderResult result = renderScene(scene, request());
    EXPECT_FALSE(hasWarning(result.stats, "light 1024 'p1023' not drawn"));
    EXPECT_TRUE(hasWarning(result.stats, "light 1025 'p1024' not drawn: more than 1024 spot/point lights"));
    EXPECT_TRUE(hasWarning(result.stats, "light 1035 '' not drawn: more than 4 directional lights"));
}

TEST_F(RenderTest, DegenerateTrianglesChangeNoPixel) {
    const Scene clean = boxOnGround();
    Scene degenerate = clean;
    Mesh& box = degenerate.meshes[1];
    const uint32_t first = uint32_t(box.vertices.size());
    box.vertices.push_back(box.vertices[0]);
    box.vertices.push_back(box.vertices[0]);
    box.indices.insert(box.indices.end(), {first, first, first + 1, 0, 1, 1});  // zero-area triangles
    for (OutputMode output : {OutputMode::Color, OutputMode::ShadowAov})
        EXPECT_EQ(renderScene(degenerate, request(output)).image.pixels, renderScene(clean, request(output)).image.pixels);
}

TEST_F(RenderTest, ZeroScaleInstanceDisappearsWithoutNaN) {
    Renderer renderer(device(), boxOnGround());
    const Image before = renderer.render(request(), {}).image;
    renderer.setInstanceTransform(1, glm::scale(glm::mat4(1.0f), glm::vec3(0.0f)));
    const Image hidden = renderer.render(request(), {}).image;
    renderer.setInstanceTransform(1, glm::scale(glm::translate(glm::mat4(1.0f), {0, 0.5f, 0}), glm::vec3(1, 1, 0)));
    const Image flattened = renderer.render(request(), {}).image;  // a singular transform with area
    EXPECT_NE(hidden.pixels, before.pixels);
    EXPECT_EQ(flattened.pixels.size(), before.pixels.size());
}

TEST_F(RenderTest, SceneAMillionMetresAcrossCastsTheShadowOfTheSameSceneInMetres) {
    const auto shadowPixels = [&](float scale) {
        const Scene scene = boxOnGround(scale);  // at 1e5: a 100 km box on a 2000 km ground
        Settings settings;
        const CameraView view = resolveCameraView(scene, 192, 128);
        applySceneDefaults(settings, scene, view);  // at 1e5: maxDistance from the bounds, not 100
        Renderer renderer(device(), scene);
        return darkPixels(renderer.render(request(OutputMode::ShadowAov, 192, 128), settings, view).image);
    };
    const uint32_t metres = shadowPixels(1.0f);
    ASSERT_GT(metres, 20u);
    EXPECT_GE(shadowPixels(1e5f), metres / 2);
}

TEST_F(RenderTest, CameraViewWithNearBeyondFarIsAnError) {
    Renderer renderer(device(), boxOnGround());
    CameraView view = resolveCameraView(renderer.scene(), 96, 64);
    view.zNear = 5.0f;
    view.zFar = 1.0f;
    EXPECT_THROW(renderer.render(request(), {}, view), Error);
    view = resolveCameraView(renderer.scene(), 96, 64);
    view.clipFromWorld[0][0] = NAN;
    EXPECT_THROW(renderer.render(request(), {}, view), Error);
}

TEST_F(RenderTest, SceneWithAnIndexOutOfRangeIsRefusedBeforeTheGpuSeesIt) {
    Scene scene = boxOnGround();
    scene.meshes[1].indices[0] = 100000;
    try {
        Renderer renderer(device(), scene);
        FAIL() << "the renderer took the scene";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("scene: mesh 1 'box': index 0 is 100000"), std::string::npos) << e.what();
    }
}

TEST_F(RenderTest, DamagedPipelineCacheFileIsIgnoredAndWrittenAgain) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("penumbra_cache_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(folder);
    DeviceOptions options = testDeviceOptions();
    options.pipelineCache = folder.string();
    const auto renderOnce = [&] {
        Device cached(options);
        Renderer renderer(cached, boxOnGround());
        const Image image = renderer.render(request(), {}).image;
        EXPECT_EQ(cached.validationMessageCount(), 0u);
        return image;
    };
    const Image first = renderOnce();
    ASSERT_EQ(std::distance(std::filesystem::directory_iterator(folder), {}), 1);
    const std::filesystem::path file = std::filesystem::directory_iterator(folder)->path();
    std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(4096, '\x5a');  // garbage
    EXPECT_EQ(renderOnce().pixels, first.pixels);
    std::ifstream written(file, std::ios::binary);
    EXPECT_EQ(written.get(), 'P');  // Penumbra's header again, not the garbage
    std::filesystem::remove_all(folder);
}
