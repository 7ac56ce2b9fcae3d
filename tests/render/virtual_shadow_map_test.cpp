// One directional light's virtual shadow map over several frames (render/virtual_shadow_map.h: mark ->
// table update -> draw -> mark drawn in one frame, stats through Device::readBackAtFrameEnd), on the demo
// scene at 320 x 180 with pages of 32 texels (level 0's pages 0.5 m, its texels 1.6 cm), lavapipe with
// validation. The lookups are probed (virtual_shadow_probe.comp) from the map's own GPU page table and pool
// at the ground the view sees, against the ray tracer (reference/embree_scene.h) where its answer is clear.
//
// Tolerances: at most 1 % of the ground points disagree with the ray tracer (pixels at silhouettes, where
// the rasterized depth that marks the pages and the traced ray see different surfaces, and acne or edges
// the rays and the pages cut differently), and at most 0.5 % are served by no level. Page counts against
// the CPU's marking (shadows/virtual_page_marking.h) differ by the marking's own tolerance (0.5 % of the
// requested pages per marking, at least 2).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_loading.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/virtual_shadow_map.h"
#include "render_test_support.h"
#include "shadows/cascades.h"
#include "shadows/virtual_clipmap.h"
#include "virtual_shadow_test_support.h"

namespace penumbra::test {
namespace {

using gpu_data::VirtualPageStats;
using gpu_data::VirtualShadowProbePoint;
using gpu_data::VirtualShadowProbeResult;

constexpr float kMarginTexels = 2.0f;

// A view of the scene, its depth, and the ground points it sees with the ray tracer's answer for a light.
struct ViewCase {
    CameraView view;
    SceneDepth depth;
    std::vector<VirtualShadowProbePoint> points;
    std::vector<bool> shadowed;
};

// How the lookups at a view's ground points compare with the ray tracer.
struct Verdict {
    size_t points = 0, shadowed = 0, wrongShadowed = 0, wrongLit = 0, unserved = 0;
};

// The map of one light over the demo scene, recorded in frames on `gpu`.
class MapRig {
public:
    explicit MapRig(gpu::Device& gpu, VirtualShadowMapConfig config = mapConfig())
        : gpu_(gpu), scene_(makeDemoScene()), gpuScene_(gpu, scene_), raster_(gpu, gpuScene_),
          map_(gpu, gpuScene_, raster_, config), probe_(gpu) {}

    const Scene& scene() const { return scene_; }
    VirtualShadowMap& map() { return map_; }

    ViewCase viewCase(const CameraView& view, const glm::vec3& wsLight) {
        ViewCase c{view, renderSceneDepth(gpu_, scene_, view), {}, {}};
        clearViewGroundPoints(scene_, view, lightRotationFromWorld(wsLight), wsLight, 1, c.points, c.shadowed);
        return c;
    }
    void release(ViewCase& c) { gpu_.destroy(c.depth.texture); }

    // One frame: the chain for the view and light, its stats read back at the frame's end.
    VirtualPageStats frame(const ViewCase& c, const glm::vec3& wsLight, const Aabb& wsBounds,
                           std::span<const gpu_data::VirtualPageInvalidation> invalidations = {}) {
        gpu::CommandList commands = gpu_.beginFrame();
        map_.record(commands, VirtualPageDepthSource::texture(c.depth.texture), c.view, wsLight, wsBounds, kMarginTexels, invalidations);
        const uint64_t at = gpu_.readBackAtFrameEnd(commands, map_.stats());
        const uint64_t index = gpu_.submitFrame(commands);
        gpu_.waitFrame(index);
        VirtualPageStats stats{};
        bool found = false;
        for (const gpu::CompletedFrame& done : gpu_.completedFrames())
            if (done.frameIndex == index) {
                stats = VirtualShadowMap::statsFromReadback(done.readback.data() + at);
                found = true;
            }
        gpu_.releaseCompletedFrames();
        EXPECT_TRUE(found) << "frame " << index << " read back";
        return stats;
    }
    VirtualPageStats frame(const ViewCase& c, const glm::vec3& wsLight) { return frame(c, wsLight, scene_.wsBounds); }

    // The lookups at the view's ground points from the map's GPU page table and pool, as a lit pass reads them.
    std::vector<VirtualShadowProbeResult> lookups(const ViewCase& c) {
        return probe_.run(map_.lookupData(), map_.pageEntries(), map_.pageEntryCount(), map_.poolTexture(), c.points);
    }

    Verdict judge(const ViewCase& c, const char* what) {
        const std::vector<VirtualShadowProbeResult> results = lookups(c);
        Verdict v;
        v.points = c.points.size();
        for (size_t i = 0; i < results.size(); ++i) {
            v.shadowed += c.shadowed[i];
            v.unserved += results[i].level < 0;
            v.wrongShadowed += c.shadowed[i] && results[i].lit > 0.5f;
            v.wrongLit += !c.shadowed[i] && results[i].lit < 0.5f;
        }
        std::printf("%s: %zu ground points (%zu shadowed); lit where shadowed %zu, shadowed where lit %zu; %zu unserved\n", what,
                    v.points, v.shadowed, v.wrongShadowed, v.wrongLit, v.unserved);
        EXPECT_GT(v.shadowed, 500u) << what;
        EXPECT_GT(v.points - v.shadowed, 10000u) << what;
        EXPECT_LE(v.wrongShadowed, v.shadowed / 100) << what << ": at most 1 % of the shadowed points lit";
        EXPECT_LE(v.wrongLit, (v.points - v.shadowed) / 100) << what << ": at most 1 % of the lit points shadowed";
        EXPECT_LE(v.unserved, v.points / 200) << what << ": ground the view sees has its pages";
        return v;
    }

private:
    gpu::Device& gpu_;
    Scene scene_;
    GpuScene gpuScene_;
    ComputeRasterPass raster_;
    VirtualShadowMap map_;
    ShadowProbe probe_;
};

// The pages `now` requests that `before` did not (by slot: both views' windows hold the same pages near
// the camera).
uint32_t newPages(const VirtualPageRequests& now, const VirtualPageRequests& before) {
    uint32_t count = 0;
    for (uint32_t level = 0; level < now.levelCount; ++level)
        for (uint32_t y = 0; y < now.pagesPerSide; ++y)
            for (uint32_t x = 0; x < now.pagesPerSide; ++x)
                count += now.requested(level, {x, y}) && !before.requested(level, {x, y});
    return count;
}

uint32_t markingTolerance(uint32_t requested) { return std::max(2u, requested / 200); }

class VirtualShadowMapTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }
};

TEST_F(VirtualShadowMapTest, TheFirstFrameDrawsEveryRequestedPageAndTheLookupsAgreeWithTheRayTracer) {
    MapRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    ViewCase c = rig.viewCase(demoView(), light);
    const VirtualPageStats stats = rig.frame(c, light);
    const uint32_t onCpu =
        markVirtualPages(mapConfig().clipmap, clipmapRotationFromWorld(light), c.view, c.depth.image, kMarginTexels).pageCount();
    std::printf("first frame: %u pages requested (CPU marking %u), %u drawn\n", stats.requested, onCpu, stats.toDraw);
    EXPECT_NEAR(double(stats.requested), double(onCpu), double(markingTolerance(onCpu)));
    EXPECT_GT(stats.requested, 50u);
    EXPECT_EQ(stats.allocated, stats.requested);
    EXPECT_EQ(stats.toDraw, stats.requested);
    EXPECT_EQ(stats.overflowed, 0u);
    EXPECT_TRUE(rig.map().lastRecordInvalidatedAll());
    rig.judge(c, "first frame");
    rig.release(c);
}

TEST_F(VirtualShadowMapTest, ASecondFrameWithTheSameCameraDrawsNoPageAndLooksUpTheSame) {
    MapRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    ViewCase c = rig.viewCase(demoView(), light);
    const VirtualPageStats first = rig.frame(c, light);
    const std::vector<VirtualShadowProbeResult> before = rig.lookups(c);
    const VirtualPageStats second = rig.frame(c, light);
    EXPECT_EQ(second.requested, first.requested);
    EXPECT_EQ(second.toDraw, 0u);
    EXPECT_EQ(second.cached, second.requested);
    EXPECT_EQ(second.allocated, 0u);
    EXPECT_FALSE(rig.map().lastRecordInvalidatedAll());
    const std::vector<VirtualShadowProbeResult> after = rig.lookups(c);
    ASSERT_EQ(after.size(), before.size());
    size_t differ = 0;
    for (size_t i = 0; i < after.size(); ++i) differ += after[i].lit != before[i].lit || after[i].level != before[i].level;
    EXPECT_EQ(differ, 0u) << "the same pages serve the same lookups";
    rig.judge(c, "second frame");
    rig.release(c);
}

TEST_F(VirtualShadowMapTest, ACameraMovedByAFractionOfAPageDrawsOnlyTheNewlyRequestedPages) {
    MapRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    const glm::mat4 rotation = clipmapRotationFromWorld(light);
    const CameraView first = demoView();
    // 0.3 of a level-0 page (0.5 m) to the camera's right, level with the ground.
    const glm::vec3 right = glm::normalize(glm::vec3(first.worldFromView[0].x, 0.0f, first.worldFromView[0].z));
    ViewCase a = rig.viewCase(first, light);
    ViewCase b = rig.viewCase(translatedCameraView(first, 0.15f * right), light);
    rig.frame(a, light);
    const VirtualPageStats moved = rig.frame(b, light);
    const VirtualPageRequests before = markVirtualPages(mapConfig().clipmap, rotation, a.view, a.depth.image, kMarginTexels);
    const VirtualPageRequests now = markVirtualPages(mapConfig().clipmap, rotation, b.view, b.depth.image, kMarginTexels);
    const uint32_t expected = newPages(now, before);
    std::printf("moved camera: %u pages requested, %u drawn (CPU marking: %u new)\n", moved.requested, moved.toDraw, expected);
    ASSERT_GT(expected, 0u) << "the move brings new pages into view";
    EXPECT_EQ(moved.toDraw, moved.allocated) << "only pages new to the table are drawn";
    const uint32_t tolerance = markingTolerance(before.pageCount()) + markingTolerance(now.pageCount());
    EXPECT_NEAR(double(moved.toDraw), double(expected), double(tolerance));
    EXPECT_LT(moved.toDraw, moved.requested / 4);
    EXPECT_EQ(moved.cached + moved.allocated + moved.overflowed, moved.requested);
    rig.judge(b, "moved camera");
    rig.release(a);
    rig.release(b);
}

TEST_F(VirtualShadowMapTest, AChangedLightOrSceneBoundsRedrawEveryRequestedPageAndTheLookupsFollowTheLight) {
    MapRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    // The light turned 25 degrees about the vertical: the shadows swing over the ground.
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(25.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 turned = glm::vec3(turn * glm::vec4(light, 0.0f));
    const CameraView view = demoView();
    ViewCase old = rig.viewCase(view, light);  // the first frame's depth (the same view)
    ViewCase next = rig.viewCase(view, turned);
    rig.frame(old, light);
    const std::vector<VirtualShadowProbeResult> before = rig.lookups(next);  // the same ground under the old light
    const VirtualPageStats stats = rig.frame(next, turned);
    std::printf("turned light: %u pages requested, %u drawn\n", stats.requested, stats.toDraw);
    EXPECT_TRUE(rig.map().lastRecordInvalidatedAll());
    EXPECT_EQ(stats.overflowed, 0u);
    EXPECT_EQ(stats.toDraw, stats.requested) << "every requested page is drawn again";
    EXPECT_GT(stats.cached, 0u) << "the pages stayed resident (dirty), not freed";
    rig.judge(next, "turned light");
    const std::vector<VirtualShadowProbeResult> after = rig.lookups(next);
    size_t changed = 0;  // ground points whose answer the turn changed
    for (size_t i = 0; i < after.size(); ++i) changed += (before[i].lit < 0.5f) != (after[i].lit < 0.5f);
    std::printf("turned light: %zu of the ground points changed between lit and shadowed\n", changed);
    EXPECT_GT(changed, 250u) << "the turn moves shadows over the ground the view sees";
    // Bounds that change (a caster added far away, say) invalidate everything too; the same bounds again do not.
    Aabb wider = rig.scene().wsBounds;
    wider.extend(wider.max + glm::vec3(0.0f, 5.0f, 0.0f));
    EXPECT_EQ(rig.frame(next, turned, wider).toDraw, stats.requested);
    EXPECT_TRUE(rig.map().lastRecordInvalidatedAll());
    EXPECT_EQ(rig.frame(next, turned, wider).toDraw, 0u);
    rig.judge(next, "wider bounds");
    rig.release(old);
    rig.release(next);
}

// Casters that moved redraw the requested pages of the rectangles they pass, and only those; more
// rectangles than the map takes in one record redraw every requested page.
TEST_F(VirtualShadowMapTest, MovedCastersRedrawOnlyTheRequestedPagesOfTheirRectangles) {
    MapRig rig(gpu());
    const glm::vec3 light = sceneLight(rig.scene());
    ViewCase c = rig.viewCase(demoView(), light);
    const VirtualPageStats first = rig.frame(c, light);
    // The pages of levels 0 to 3 within 2 m of the light-space origin (the demo's casters stand there).
    const VirtualClipmapConfig config = mapConfig().clipmap;
    const glm::mat4 rotation = clipmapRotationFromWorld(light);
    const VirtualPageRequests requests = markVirtualPages(config, rotation, c.view, c.depth.image, kMarginTexels);
    const glm::vec2 lsCamera = lsClipmapCentre(rotation, c.view);
    std::vector<gpu_data::VirtualPageInvalidation> moved;
    uint32_t expected = 0;
    for (uint32_t level = 0; level < 4; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        const PageRect pages{pageOf(placed, glm::vec2(-2.0f)), pageOf(placed, glm::vec2(2.0f))};
        moved.push_back(virtualPageInvalidation(level, pages));
        for (int32_t y = pages.min.y; y <= pages.max.y; ++y)
            for (int32_t x = pages.min.x; x <= pages.max.x; ++x)
                expected += placed.window.contains({{x, y}, {x, y}}) && requests.requested(level, pageTableSlot(placed, {x, y}));
    }
    const VirtualPageStats stats = rig.frame(c, light, rig.scene().wsBounds, moved);
    std::printf("moved casters: %u pages requested, %u drawn (CPU marking: %u in the rectangles)\n", stats.requested,
                stats.toDraw, expected);
    ASSERT_GT(expected, 0u);
    EXPECT_FALSE(rig.map().lastRecordInvalidatedAll());
    EXPECT_NEAR(double(stats.toDraw), double(expected), double(markingTolerance(requests.pageCount())));
    EXPECT_LT(stats.toDraw, first.requested);
    EXPECT_EQ(stats.allocated, 0u);
    rig.judge(c, "moved casters");
    const std::vector<gpu_data::VirtualPageInvalidation> many(VirtualShadowMap::kMaxInvalidations + 1, moved[0]);
    EXPECT_EQ(rig.frame(c, light, rig.scene().wsBounds, many).toDraw, first.requested);
    EXPECT_TRUE(rig.map().lastRecordInvalidatedAll());
    rig.release(c);
}

// The chain's frame-graph declarations leave no hazard: on a device with synchronization validation, frames
// that draw every page, none, the pages of moved casters, of a moved camera and every page of a turned
// light, each followed by the lookups that read the table and the pool.
TEST_F(VirtualShadowMapTest, FramesPassSynchronizationValidation) {
    DeviceOptions options = testDeviceOptions();
    options.synchronizationValidation = true;
    Device syncDevice(options);
    gpu::Device& gpu = gpu::backend(syncDevice);
    {
        MapRig rig(gpu);
        const glm::vec3 light = sceneLight(rig.scene());
        const glm::vec3 turned = glm::normalize(light + glm::vec3(0.2f, 0.0f, -0.1f));
        const CameraView view = demoView(160, 90);
        ViewCase a = rig.viewCase(view, light);
        ViewCase b = rig.viewCase(translatedCameraView(view, glm::vec3(0.2f, 0.0f, 0.1f)), light);
        const gpu_data::VirtualPageInvalidation moved = virtualPageInvalidation(1, {{-3, -3}, {3, 3}});
        int frame = 0;
        for (const auto& [c, l] : {std::pair{&a, light}, std::pair{&a, light}, std::pair{&a, light}, std::pair{&b, light},
                                   std::pair{&b, turned}}) {
            const size_t rectangles = frame++ == 2 ? 1 : 0;  // the third frame: casters moved
            rig.frame(*c, l, rig.scene().wsBounds, std::span(&moved, rectangles));
            EXPECT_EQ(rig.lookups(*c).size(), c->points.size());
        }
        rig.release(a);
        rig.release(b);
    }
    gpu.waitIdle();
    const uint32_t messages = syncDevice.validationMessageCount();
    EXPECT_EQ(messages, 0u) << (messages ? syncDevice.validationMessages()[0] : "");
}

}  // namespace
}  // namespace penumbra::test
