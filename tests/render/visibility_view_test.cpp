// The visibility-buffer main view (render.mainView = visibility): the compute rasterizer + resolve gives the
// forward pass's image on every canonical scene (colour within 2 levels in 99.5 % of pixels, the
// shadow AOV's lit / shadowed class in all but 0.05 %), with clustered and unculled lights alike,
// blended materials drawn forward on top, and says which path drew each frame.
#include <algorithm>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "render/gpu_scene.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"

namespace penumbra::test {
namespace {

class VisibilityViewTest : public RenderTest {
protected:
    static Settings settingsFor(MainView mainView, LightCulling culling = LightCulling::Clustered) {
        Settings settings;
        settings.render.mainView = mainView;
        settings.render.lightCulling = culling;
        settings.shadows.directional.atlasSize = 512;  // lavapipe: keep the shadow passes small
        settings.shadows.spot.atlasSize = 512;
        settings.render.background = Background::Black;  // the resolve's own clear colour shows where nothing is
        return settings;
    }
    // Colour at 320 x 180: nearest-filtered alpha masks (fence) flip texels where the two paths' uv
    // round apart, along every texel edge, a share that falls with the resolution (0.57 % at 192 x 108).
    static RenderResult renderWith(Renderer& renderer, const Settings& settings, OutputMode output, uint32_t light = 0) {
        const bool colour = output == OutputMode::Color;
        RenderRequest request;
        request.width = colour ? 320 : 192;
        request.height = colour ? 180 : 108;
        request.output = output;
        request.aovLight = light;
        return renderer.render(request, settings);
    }
    // The share of pixels whose lit / shadowed class (at 0.5) differs, first channel.
    static double classDifference(const Image& a, const Image& b) {
        size_t differ = 0, pixels = a.pixels.size() / a.channels;
        for (size_t p = 0; p < pixels; ++p)
            differ += (a.pixels[p * a.channels] >= 128) != (b.pixels[p * b.channels] >= 128);
        return double(differ) / double(pixels);
    }
    // Forward and visibility colour of `scene`; returns the share of pixels over 2 levels.
    double colourDifference(const Scene& scene, const std::string& what, LightCulling culling = LightCulling::Clustered) {
        Renderer renderer(device(), scene);
        const RenderResult forward = renderWith(renderer, settingsFor(MainView::Forward, culling), OutputMode::Color);
        const RenderResult visibility = renderWith(renderer, settingsFor(MainView::Visibility, culling), OutputMode::Color);
        EXPECT_EQ(forward.stats.mainView, "forward") << what;
        EXPECT_EQ(visibility.stats.mainView, "visibility") << what;
        const double over = shareOfPixelsOver(forward.image, visibility.image, 2);
        EXPECT_LE(over, 0.005) << what << ": " << 100.0 * over << " % of pixels differ by more than 2 levels";
        return over;
    }
};

TEST_F(VisibilityViewTest, LavapipeHasWhatTheVisibilityBufferNeeds) {
    // Without it every test below would silently compare forward with forward.
    EXPECT_TRUE(gpu::backend(device()).hasBufferInt64Atomics());
}

TEST_F(VisibilityViewTest, ColourEqualsTheForwardPassOnEveryCanonicalScene) {
    double worst = 0.0;
    for (const CanonicalSceneInfo& info : canonicalScenes())
        worst = std::max(worst, colourDifference(makeCanonicalScene(info.name), info.name));
    std::printf("canonical scenes: at most %.4f %% of pixels differ by more than 2 levels (forward vs visibility)\n",
                100.0 * worst);
}

TEST_F(VisibilityViewTest, BlendedMaterialsAreDrawnForwardOnTheVisibilityBuffer) {
    // The demo scene has an alpha-blended material over opaque ones.
    const double over = colourDifference(makeDemoScene(), "demo");
    std::printf("demo (blended materials): %.4f %% of pixels differ by more than 2 levels\n", 100.0 * over);
}

// A half-transparent blue quad half hidden by an opaque green one in front, over a red backdrop: drawn
// without the opaque surfaces' depth, the blue would cover the green too.
Scene glassBehindAnOpaqueQuad() {
    SceneBuilder builder;
    Material red, green, blue;
    red.baseColorFactor = {1, 0, 0, 1};
    green.baseColorFactor = {0, 1, 0, 1};
    blue.alphaMode = AlphaMode::Blend;
    blue.baseColorFactor = {0, 0, 1, 0.5f};
    const uint32_t r = builder.addMaterial(red), g = builder.addMaterial(green), b = builder.addMaterial(blue);
    builder.addInstance(builder.addMesh(makeQuadMesh({10, 10}, r)), glm::translate(glm::mat4(1), {0, 0, -1}));
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, g)), glm::translate(glm::mat4(1), {1, 0, 0.5f}));
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, b)), glm::mat4(1));
    builder.addLight(makeDirectionalLight({0.3f, -0.4f, -1.0f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0, 0, 3}, {0, 0, 0}, 0.9f));
    return builder.build();
}

// GPUs resolve in compute and copy the colour into the target, the view's depth only for a later pass
// that reads it (blended materials); the gradient background is the resolve's too. On lavapipe, made to
// take that path: the forward pass's image with the gradient, with and without blended materials.
TEST_F(VisibilityViewTest, TheComputeResolveDrawsTheBackgroundAndKeepsDepthForBlendedMaterials) {
    gpu::DeviceFaultInjection faults;
    faults.computeResolve = true;
    Device gpuLike = DeviceAccess::makeDevice({testDeviceOptions(), faults});
    for (const char* name : {"glass", "low_sun"}) {  // a blended material behind an opaque one; low_sun's sky
        const Scene scene = std::string(name) == "glass" ? glassBehindAnOpaqueQuad() : makeCanonicalScene(name);
        Renderer forwardRenderer(device(), scene), computeRenderer(gpuLike, scene);
        Settings forward = settingsFor(MainView::Forward), visibility = settingsFor(MainView::Visibility);
        forward.render.background = visibility.render.background = Background::Gradient;
        const RenderResult expected = renderWith(forwardRenderer, forward, OutputMode::Color);
        const RenderResult resolved = renderWith(computeRenderer, visibility, OutputMode::Color);
        EXPECT_EQ(resolved.stats.mainView, "visibility") << name;
        const double over = shareOfPixelsOver(expected.image, resolved.image, 2);
        EXPECT_LE(over, 0.005) << name << ": " << 100.0 * over << " % of pixels differ by more than 2 levels";
        EXPECT_EQ(gpuLike.validationMessageCount(), 0u) << name;
    }
}

TEST_F(VisibilityViewTest, ColourEqualsTheForwardPassWith400PointLightsClusteredOrNot) {
    const Scene scene = loadScene("gen:boxes:100:400");
    const double clustered = colourDifference(scene, "400 points, clustered");
    const double unculled = colourDifference(scene, "400 points, unculled", LightCulling::None);
    std::printf("400 point lights: %.4f %% (clustered), %.4f %% (unculled) over 2 levels\n", 100.0 * clustered,
                100.0 * unculled);
}

TEST_F(VisibilityViewTest, ShadowAovClassEqualsTheForwardPassOnEveryCanonicalScene) {
    double worst = 0.0;
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        Renderer renderer(device(), scene);
        for (uint32_t light = 0; light < scene.lights.size(); ++light) {
            if (scene.lights[light].shadows == LightShadows::None) continue;
            const Image forward = renderWith(renderer, settingsFor(MainView::Forward), OutputMode::ShadowAov, light).image;
            const Image visibility =
                renderWith(renderer, settingsFor(MainView::Visibility), OutputMode::ShadowAov, light).image;
            const double differ = classDifference(forward, visibility);
            EXPECT_LT(differ, 0.0005) << info.name << " light " << light;
            worst = std::max(worst, differ);
        }
    }
    std::printf("canonical scenes: shadow class differs in at most %.4f %% of pixels (forward vs visibility)\n",
                100.0 * worst);
}

TEST_F(VisibilityViewTest, CascadeColoursEqualTheForwardPass) {
    const Scene scene = makeCanonicalScene(canonicalScenes().front().name);
    Renderer renderer(device(), scene);
    const Image forward = renderWith(renderer, settingsFor(MainView::Forward), OutputMode::CascadesAov).image;
    const Image visibility = renderWith(renderer, settingsFor(MainView::Visibility), OutputMode::CascadesAov).image;
    EXPECT_LE(shareOfPixelsOver(forward, visibility, 0), 0.005);
}

TEST_F(VisibilityViewTest, AutoKeepsTheForwardPassOnACpuDevice) {
    Renderer renderer(device(), makeCanonicalScene(canonicalScenes().front().name));
    for (int i = 0; i < 10; ++i) {  // past the measuring frames a GPU would take
        const RenderResult frame = renderWith(renderer, settingsFor(MainView::Auto), OutputMode::Color);
        EXPECT_EQ(frame.stats.mainView, "forward");
    }
}

TEST_F(VisibilityViewTest, StatsSayWhetherTheSettingOrAutoChoseTheMainView) {
    Renderer renderer(device(), makeCanonicalScene(canonicalScenes().front().name));
    const RenderResult forward = renderWith(renderer, settingsFor(MainView::Forward), OutputMode::Color);
    EXPECT_EQ(forward.stats.mainViewChoice, "render.mainView = forward");
    const RenderResult visibility = renderWith(renderer, settingsFor(MainView::Visibility), OutputMode::Color);
    EXPECT_EQ(visibility.stats.mainViewChoice, "render.mainView = visibility") << "not auto's \"measuring\"";
    const RenderResult automatic = renderWith(renderer, settingsFor(MainView::Auto), OutputMode::Color);
    EXPECT_EQ(automatic.stats.mainViewChoice, "forward (a CPU device: auto keeps the forward pass)");
}

TEST_F(VisibilityViewTest, BackFacesShowOnlyForDoubleSidedMaterials) {
    // Two unlit quads seen from behind: the left single-sided (culled: the background shows), the
    // right double-sided (green). The visibility buffer culls as the forward pass does.
    SceneBuilder builder;
    Material single, both;
    single.unlit = both.unlit = true;
    single.baseColorFactor = glm::vec4(1, 0, 0, 1);
    both.baseColorFactor = glm::vec4(0, 1, 0, 1);
    both.doubleSided = true;
    const glm::mat4 facingAway = glm::rotate(glm::mat4(1), glm::radians(180.0f), glm::vec3(0, 1, 0));
    builder.addInstance(builder.addMesh(makeQuadMesh({1.8f, 1.8f}, builder.addMaterial(single))),
                        glm::translate(glm::mat4(1), {-1, 0, 0}) * facingAway);
    builder.addInstance(builder.addMesh(makeQuadMesh({1.8f, 1.8f}, builder.addMaterial(both))),
                        glm::translate(glm::mat4(1), {1, 0, 0}) * facingAway);
    builder.setCamera(makeLookAtCamera({0, 0, 3}, {0, 0, 0}, glm::radians(60.0f)));
    Renderer renderer(device(), builder.build());
    Settings settings = settingsFor(MainView::Visibility);
    const Image image = renderWith(renderer, settings, OutputMode::Color).image;
    auto at = [&](uint32_t x, uint32_t y) { return &image.pixels[(size_t(y) * image.width + x) * image.channels]; };
    const uint8_t* left = at(image.width / 4, image.height / 2);
    const uint8_t* right = at(3 * image.width / 4, image.height / 2);
    EXPECT_LT(left[0], 64) << "a single-sided back face was drawn";
    EXPECT_GT(right[1], 200) << "a double-sided back face was culled";
    EXPECT_LE(shareOfPixelsOver(renderWith(renderer, settingsFor(MainView::Forward), OutputMode::Color).image, image, 2), 0.005);
}

// Boxes (one meshlet of 12 triangles each) are rasterized 21 to a workgroup, not one workgroup each:
// the same image as the forward pass.
TEST_F(VisibilityViewTest, SmallObjectsPackedIntoWorkItemsEqualTheForwardPass) {
    const Scene scene = loadScene("gen:boxes:3000");
    GpuScene gpuScene(gpu::backend(device()), scene);
    EXPECT_LT(gpuScene.rasterWorkItems() * 10, uint32_t(scene.instances.size())) << "packed work items";
    const double over = colourDifference(scene, "boxes");
    std::printf("3000 boxes: %.4f %% of pixels differ by more than 2 levels\n", 100.0 * over);
}

TEST_F(VisibilityViewTest, InstanceAndTriangleIdsOfTheCanonicalScenesFit32Bits) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        GpuScene gpuScene(gpu::backend(device()), scene);
        EXPECT_TRUE(gpuScene.visibilityIdsFit()) << info.name;
        uint32_t mostTriangles = 0;
        for (const Mesh& mesh : scene.meshes) mostTriangles = std::max(mostTriangles, uint32_t(mesh.indices.size() / 3));
        EXPECT_GE(uint64_t(1) << gpuScene.triangleIdBits(), mostTriangles) << info.name;
        EXPECT_LT(uint64_t(1) << gpuScene.triangleIdBits(), 2ull * std::max(mostTriangles, 1u)) << info.name;
    }
}

}  // namespace
}  // namespace penumbra::test
