// Virtual shadow map page marking on the GPU (render/virtual_page_mark_pass.h) against its CPU
// reference (shadows/virtual_page_marking.h), on lavapipe with validation: the same depth gives the
// same requested pages, for a synthetic depth image and for the main view's depth of real scenes.
//
// Tolerance: the GPU and C++ round the reconstruction (matrix products, divisions) differently in the
// last bits, so a receiver within a rounding error of a page (or level) boundary can request the
// page next to the CPU's. Allowed: at most 0.5% of the CPU's requested pages (and at most 2 on a
// sparse set) differ, and every page requested by one side only has a page the other side requested
// next to it: in the same level within one page (8-neighbourhood), or in the level above or below
// over the same ground.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_loading.h"
#include "render/frame_data.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "render/screen_space_shadow_pass.h"
#include "render/virtual_page_mark_pass.h"
#include "render_test_support.h"
#include "virtual_shadow_test_support.h"
#include "scene/canonical_scenes.h"
#include "shadows/cascades.h"

namespace penumbra::test {
namespace {

// Global page coordinates of a requested slot of a level placed around lsCamera.
glm::ivec2 globalPage(const ClipmapLevel& level, const glm::uvec2& slot) {
    const glm::uvec2 first = pageTableSlot(level, level.window.min);
    const int32_t n = int32_t(level.pagesPerSide);
    return level.window.min + (glm::ivec2(slot) - glm::ivec2(first) + n) % n;
}

bool requestedAt(const VirtualPageRequests& requests, const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                 uint32_t level, const glm::ivec2& page) {
    if (level >= requests.levelCount) return false;
    const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
    if (!placed.window.contains({page, page})) return false;
    return requests.requested(level, pageTableSlot(placed, page));
}

// A page of `other` next to (level, page): same level within one page, or the level above or below
// over the same ground.
bool hasNeighbour(const VirtualPageRequests& other, const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                  uint32_t level, const glm::ivec2& page) {
    for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx)
            if (requestedAt(other, config, lsCamera, level, page + glm::ivec2(dx, dy))) return true;
    const glm::ivec2 coarser(page.x >> 1, page.y >> 1);  // floor division: the pages halve per level
    if (requestedAt(other, config, lsCamera, level + 1, coarser)) return true;
    for (int32_t dy = 0; dy <= 1 && level > 0; ++dy)
        for (int32_t dx = 0; dx <= 1; ++dx)
            if (requestedAt(other, config, lsCamera, level - 1, page * 2 + glm::ivec2(dx, dy))) return true;
    return false;
}

struct Disagreement {
    uint32_t differing = 0;    // pages one side requests and the other does not
    uint32_t unexplained = 0;  // of those, the ones with no neighbour on the other side
};

Disagreement compareRequests(const VirtualPageRequests& gpu, const VirtualPageRequests& cpu,
                             const VirtualClipmapConfig& config, const glm::vec2& lsCamera) {
    Disagreement result;
    for (uint32_t level = 0; level < config.levelCount; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        for (uint32_t y = 0; y < placed.pagesPerSide; ++y)
            for (uint32_t x = 0; x < placed.pagesPerSide; ++x) {
                const bool onGpu = gpu.requested(level, {x, y}), onCpu = cpu.requested(level, {x, y});
                if (onGpu == onCpu) continue;
                ++result.differing;
                const VirtualPageRequests& other = onGpu ? cpu : gpu;
                if (!hasNeighbour(other, config, lsCamera, level, globalPage(placed, {x, y}))) ++result.unexplained;
            }
    }
    return result;
}

class VirtualPageMarkTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }

    SceneDepth renderDepth(const Scene& scene, const CameraView& view) { return renderSceneDepth(gpu(), scene, view); }

    // The GPU's requests equal the CPU's within the tolerance above; returns the CPU's.
    VirtualPageRequests expectAgreement(const VirtualPageRequests& onGpu, const VirtualPageRequests& onCpu,
                                        const VirtualClipmapConfig& config, const glm::vec2& lsCamera,
                                        const std::string& what) {
        const Disagreement d = compareRequests(onGpu, onCpu, config, lsCamera);
        const uint32_t allowed = std::max(2u, onCpu.pageCount() / 200);
        EXPECT_LE(d.differing, allowed) << what << ": " << d.differing << " of " << onCpu.pageCount() << " pages differ";
        EXPECT_EQ(d.unexplained, 0u) << what << ": pages with no neighbour requested by the other side";
        EXPECT_GT(onCpu.pageCount(), 0u) << what;
        return onCpu;
    }

    // Marks the scene's view from its rendered depth on both sides, with each config; returns the
    // CPU's requests of the last.
    VirtualPageRequests expectSceneAgreement(const Scene& scene, const std::string& what,
                                             std::initializer_list<VirtualClipmapConfig> configs) {
        const CameraView view = sceneView(scene);
        const glm::mat4 lightRotation = sceneLightRotation(scene);
        const SceneDepth depth = renderDepth(scene, view);
        VirtualPageMarkPass pass(gpu());
        std::optional<VirtualPageRequests> onCpu;
        for (const VirtualClipmapConfig& config : configs) {
            const VirtualPageRequests onGpu = pass.markNow(depth.texture, view, lightRotation, config, kMarginTexels);
            onCpu = markVirtualPages(config, lightRotation, view, depth.image, kMarginTexels);
            expectAgreement(onGpu, *onCpu, config, lsClipmapCentre(lightRotation, view),
                            what + ", " + std::to_string(pagesPerSide(config)) + " pages a side");
        }
        gpu().destroy(depth.texture);
        return *onCpu;
    }

    static constexpr float kMarginTexels = 2.0f;
    static CameraView sceneView(const Scene& scene) { return resolveCameraView(scene, 640, 360); }
    static glm::mat4 sceneLightRotation(const Scene& scene) {
        for (const Light& light : scene.lights)
            if (light.type == LightType::Directional) return lightRotationFromWorld(light.wsDirection);
        throw std::runtime_error("the scene has no directional light");
    }
};

// Pages of 32 texels, level 0 64 m wide (1.6 cm texels): at 640x360 the demo's closest surfaces
// (7.6 m away, 2.2 cm pixels) sample level 0, and a scene requests hundreds of pages.
VirtualClipmapConfig sceneScaleConfig() {
    return {.resolution = 4096, .pageSize = 32, .levelCount = 10, .firstLevelSize = 64.0f};
}

// Depth that reaches most levels, seen by a camera far from the light-space origin (windows away from
// page 0, so slots wrap): pseudo-random depths from the near plane to thousands of metres, and empty
// pixels.
Image scatteredDepth(const CameraView& view) {
    Image depth(view.width, view.height, 4);
    uint32_t state = 12345u;
    for (size_t pixel = 0; pixel < size_t(view.width) * view.height; ++pixel) {
        state = state * 1664525u + 1013904223u;  // a linear congruential generator: the same image every run
        const float unit = float(state >> 8) / float(1u << 24);
        const float d = unit < 0.1f ? 0.0f : view.zNear / (view.zNear + std::exp2(unit * 14.0f) - 1.0f);
        std::memcpy(&depth.pixels[pixel * 4], &d, sizeof(float));
    }
    return depth;
}

CameraView offsetCamera(uint32_t width, uint32_t height) {
    Camera camera;
    const glm::vec3 eye(-37.3f, 4.2f, 211.9f);
    camera.worldFromView = glm::inverse(glm::lookAt(eye, eye + glm::vec3(0.4f, -0.3f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.yfov = glm::radians(50.0f);
    camera.zNear = 0.1f;
    return makeCameraView(camera, width, height);
}

TEST_F(VirtualPageMarkTest, GpuMarksEqualTheCpuReferenceOnASyntheticDepthImage) {
    const CameraView view = offsetCamera(200, 150);
    const Image depth = scatteredDepth(view);
    const glm::mat4 lightRotation = lightRotationFromWorld(glm::normalize(glm::vec3(0.3f, -1.0f, 0.45f)));
    VirtualPageMarkPass pass(gpu());
    const VirtualClipmapConfig small{.resolution = 2048, .levelCount = 12, .firstLevelSize = 1.0f};  // 16 pages a side
    for (const VirtualClipmapConfig& config : {VirtualClipmapConfig{}, small}) {
        for (float marginTexels : {0.0f, 3.5f, 40.0f}) {
            const std::string what = std::to_string(pagesPerSide(config)) + " pages a side, margin " + std::to_string(marginTexels);
            const VirtualPageRequests onGpu = pass.markNow(depth, view, lightRotation, config, marginTexels);
            const VirtualPageRequests onCpu = markVirtualPages(config, lightRotation, view, depth, marginTexels);
            expectAgreement(onGpu, onCpu, config, lsClipmapCentre(lightRotation, view), what);
        }
    }
}

TEST_F(VirtualPageMarkTest, GpuMarksEqualTheCpuReferenceOnTheDemoScene) {
    expectSceneAgreement(makeDemoScene(), "demo", {VirtualClipmapConfig{}, sceneScaleConfig()});
}

TEST_F(VirtualPageMarkTest, GpuMarksEqualTheCpuReferenceOnCanonicalScenes) {
    for (const char* name : {"field_of_objects", "far_field", "low_sun"})
        expectSceneAgreement(makeCanonicalScene(name), name, {VirtualClipmapConfig{}, sceneScaleConfig()});
}

TEST_F(VirtualPageMarkTest, TheDemoSceneMarksFewPagesAndLevelZeroOnlyNearTheCamera) {
    const VirtualClipmapConfig config = sceneScaleConfig();
    const Scene scene = makeDemoScene();
    const VirtualPageRequests requests = expectSceneAgreement(scene, "demo", {config});
    const uint32_t side = pagesPerSide(config);
    EXPECT_LT(requests.pageCount(), config.levelCount * side * side / 20) << "more than 5% of the clipmap's pages";
    ASSERT_GT(requests.levelPageCounts[0], 0u) << "the closest surfaces sample level 0";
    // Level 0 serves footprints below level 1's texel, so receivers closer than vsLevel0 in view
    // depth, and thus within vsLevel0 / cos(the corner ray's angle) of the camera; a page's centre lies
    // within half its diagonal and the margin of such a receiver.
    const CameraView view = sceneView(scene);
    const glm::vec2 lsCamera = lsClipmapCentre(sceneLightRotation(scene), view);
    const ClipmapLevel level0 = placeClipmapLevel(config, 0, lsCamera);
    const float tanHalf = std::tan(0.5f * view.yfov);
    const float cornerSecant = std::sqrt(1.0f + tanHalf * tanHalf * (1.0f + view.aspect * view.aspect));
    const float vsLevel0 = 2.0f * level0.lsTexelSize / wsFootprintPerDepth(view);
    const float lsReach = vsLevel0 * cornerSecant + level0.lsPageSize * std::sqrt(0.5f) + kMarginTexels * level0.lsTexelSize;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) {
            if (!requests.requested(0, {x, y})) continue;
            const glm::vec2 lsPageCentre = (glm::vec2(globalPage(level0, {x, y})) + 0.5f) * level0.lsPageSize;
            EXPECT_LE(glm::distance(lsPageCentre, lsCamera), lsReach) << "slot " << x << ", " << y;
        }
}

// The pass's frame-graph declarations leave no hazard: marking twice from the main pass's depth
// target (clear after the last readback, mark after the depth writes, readback after the marks) on a
// device with synchronization validation.
TEST_F(VirtualPageMarkTest, MarkingTwiceFromADepthTargetPassesSynchronizationValidation) {
    DeviceOptions options = testDeviceOptions();
    options.synchronizationValidation = true;
    Device syncDevice(options);
    gpu::Device& gpu = gpu::backend(syncDevice);
    const Scene scene = makeDemoScene();
    const CameraView view = resolveCameraView(scene, 160, 90);
    const SceneDepth depth = renderSceneDepth(gpu, scene, view);
    {
        VirtualPageMarkPass pass(gpu);
        const glm::mat4 lightRotation = sceneLightRotation(scene);
        const VirtualPageRequests first = pass.markNow(depth.texture, view, lightRotation, sceneScaleConfig(), kMarginTexels);
        const VirtualPageRequests second = pass.markNow(depth.texture, view, lightRotation, sceneScaleConfig(), kMarginTexels);
        EXPECT_GT(first.pageCount(), 0u);
        EXPECT_EQ(second.words, first.words);
    }
    gpu.destroy(depth.texture);
    gpu.waitIdle();
    EXPECT_EQ(syncDevice.validationMessageCount(), 0u) << (syncDevice.validationMessageCount() ? syncDevice.validationMessages()[0] : "");
}

// The tolerance is no blanket: a page next to the other side's passes, a page far from all of them does not.
TEST_F(VirtualPageMarkTest, TheComparisonToleratesOnlyPagesNextToTheOtherSides) {
    const VirtualClipmapConfig config = sceneScaleConfig();
    const Scene scene = makeDemoScene();
    const CameraView view = sceneView(scene);
    const glm::mat4 lightRotation = sceneLightRotation(scene);
    const glm::vec2 lsCamera = lsClipmapCentre(lightRotation, view);
    const SceneDepth depth = renderDepth(scene, view);
    gpu().destroy(depth.texture);
    const VirtualPageRequests cpu = markVirtualPages(config, lightRotation, view, depth.image, kMarginTexels);
    ASSERT_EQ(compareRequests(cpu, cpu, config, lsCamera).differing, 0u);
    // The first unrequested level-0 page beside a requested one, and a page of the coarsest level far
    // from any request (its window's corner).
    const ClipmapLevel level0 = placeClipmapLevel(config, 0, lsCamera);
    std::optional<glm::ivec2> beside;
    for (int32_t y = level0.window.min.y + 1; y < level0.window.max.y && !beside; ++y)
        for (int32_t x = level0.window.min.x + 1; x < level0.window.max.x && !beside; ++x)
            if (requestedAt(cpu, config, lsCamera, 0, {x, y}) && !requestedAt(cpu, config, lsCamera, 0, {x + 1, y}))
                beside = glm::ivec2(x + 1, y);
    ASSERT_TRUE(beside);
    VirtualPageRequests withNeighbour = cpu;
    withNeighbour.request(0, pageTableSlot(level0, *beside));
    const Disagreement neighbour = compareRequests(withNeighbour, cpu, config, lsCamera);
    EXPECT_EQ(neighbour.differing, 1u);
    EXPECT_EQ(neighbour.unexplained, 0u);
    const ClipmapLevel last = placeClipmapLevel(config, config.levelCount - 1, lsCamera);
    ASSERT_EQ(cpu.levelPageCounts[last.level] + cpu.levelPageCounts[last.level - 1], 0u) << "the demo needs no 16 km pages";
    VirtualPageRequests withStray = cpu;
    withStray.request(config.levelCount - 1, pageTableSlot(last, last.window.min));
    const Disagreement stray = compareRequests(cpu, withStray, config, lsCamera);
    EXPECT_EQ(stray.differing, 1u);
    EXPECT_EQ(stray.unexplained, 1u);
}

}  // namespace
}  // namespace penumbra::test
