// Heap allocations of the renderer's per-frame work, counted: the parts of a steady-state frame that
// are made allocation-free (the shadow plan's stats, the tile cache's decision) allocate nothing once
// their storage has been used by a first frame.
//
// What is counted: every global operator new (all its forms) on the calling thread, between the
// start and the end of the counted work. This binary replaces the global operator new/delete to
// count; nothing else changes. Not counted: malloc and other threads. The Vulkan driver (lavapipe:
// C code, malloc through its allocation callbacks, and its own queue thread) is outside our code, so
// leaving malloc and other threads out counts our code and nothing of the driver's. That is also why
// the whole-frame tests make their own Device without the validation layers: the layers are C++ and
// allocate with operator new on the calling thread for every command recorded.
//
// A whole steady-state frame allocates nothing: the renderer plans into the pending frame's recycled
// ShadowFrame, keeps every per-record list as a member, recycles finished frames' stats through
// Renderer::takeCompletedFrames(std::vector<FrameStats>&), and the GPU layer keeps its scratch. When a
// test below fails, PENUMBRA_ALLOCATION_TRACE=1 prints the call stack of every counted allocation
// (symbolize the offsets with addr2line -f -C -i -e tests/penumbra_render_tests).
#include <execinfo.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <new>

#include "gpu/device.h"
#include "gpu/device_access.h"
#include "penumbra/scene_loading.h"
#include "render/raster_choice.h"
#include "render/shadow_stats_json.h"
#include "render/tile_cache.h"
#include "render/virtual_page_storage.h"
#include "render/virtual_shadow_map.h"
#include "render_test_support.h"
#include "shadows/shadow_planner.h"
#include "virtual_shadow_test_support.h"

namespace {

thread_local bool tCounting = false;
thread_local uint64_t tAllocations = 0;
bool gTrace = false;

void noteAllocation() {
    if (!tCounting) return;
    ++tAllocations;
    if (gTrace) {
        tCounting = false;  // backtrace_symbols_fd writes without allocating; stay out of our own count anyway
        void* frames[32];
        const int depth = backtrace(frames, 32);
        const char header[] = "---- operator new during a counted frame:\n";
        (void)!write(2, header, sizeof(header) - 1);
        backtrace_symbols_fd(frames, depth, 2);
        tCounting = true;
    }
}

void* allocate(std::size_t size, std::size_t alignment = 0) {
    noteAllocation();
    if (size == 0) size = 1;
    void* p = alignment > alignof(std::max_align_t) ? std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment)
                                                    : std::malloc(size);
    if (!p) throw std::bad_alloc();
    return p;
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, std::align_val_t a) { return allocate(size, std::size_t(a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocate(size, std::size_t(a)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try { return allocate(size); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    try { return allocate(size); } catch (...) { return nullptr; }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace penumbra::test {
namespace {

// Heap allocations `frame` makes on this thread.
template <typename Frame>
uint64_t allocationsOf(Frame&& frame) {
    tAllocations = 0;
    tCounting = true;
    frame();
    tCounting = false;
    return tAllocations;
}

Device& deviceWithoutValidation() {
    static std::unique_ptr<Device> device = [] {
        DeviceOptions options = testDeviceOptions();
        options.validation = false;
        return std::make_unique<Device>(options);
    }();
    return *device;
}

class FrameAllocationTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        gTrace = std::getenv("PENUMBRA_ALLOCATION_TRACE") != nullptr;
        void* warm[1];
        backtrace(warm, 1);  // its first call loads libgcc: not during a counted frame
    }

    RenderRequest request() const {
        RenderRequest r;
        r.width = 96;
        r.height = 54;
        return r;
    }

    // A view of the scene's camera, moved along x by `step` (0: the still camera).
    CameraView view(const Scene& scene, float step) const {
        const CameraView still = resolveCameraView(scene, 96, 54);
        return translatedCameraView(still, step * wsCameraRight(still));
    }

    // Heap allocations of frame `warmup + 1` (a frame submitted and the finished frames' stats taken).
    // Steady state: after the auto choices (shadows.raster, render.mainView) have measured both of their
    // paths (RasterChoice: kWarmup + kSamples frames each) and every frame slot has been used.
    uint64_t steadyFrameAllocations(const Settings& settings, bool movingCamera) {
        Renderer renderer(deviceWithoutValidation(), makeDemoScene());
        std::vector<FrameStats> finished;
        finished.reserve(8);
        const int warmup = 2 * (RasterChoice::kWarmup + RasterChoice::kSamples) + 8;
        for (int i = 0; i < warmup; ++i) {
            renderer.submitFrame(request(), settings, view(renderer.scene(), movingCamera ? 0.05f * float(i) : 0.0f));
            renderer.takeCompletedFrames(finished);
        }
        const CameraView next = view(renderer.scene(), movingCamera ? 0.05f * float(warmup) : 0.0f);
        return allocationsOf([&] {
            renderer.submitFrame(request(), settings, next);
            renderer.takeCompletedFrames(finished);
        });
    }
};

Settings forwardSettings() {
    Settings settings;
    settings.render.mainView = MainView::Forward;
    return settings;
}

Settings hardwareRasterSettings() {
    Settings settings = forwardSettings();
    settings.shadows.raster = ShadowRaster::Hw;
    return settings;
}

Settings visibilitySettings() {
    Settings settings;
    settings.render.mainView = MainView::Visibility;
    return settings;
}

TEST_F(FrameAllocationTest, CountsAnAllocationMadeDuringTheFrame) {
    EXPECT_EQ(allocationsOf([] { delete new int(1); }), 1u);
}

// The plan of a frame of the demo scene from its camera moved by `step` metres to the right.
ShadowFrame demoPlan(const Scene& scene, float step) {
    const CameraView still = resolveCameraView(scene, 96, 54);
    return ShadowPlanner::plan(scene, translatedCameraView(still, step * wsCameraRight(still)), ShadowSettings{});
}

TEST_F(FrameAllocationTest, ShadowStatsOfAFrameAllocateNothing) {
    const Scene scene = makeDemoScene();
    const ShadowFrame first = demoPlan(scene, 0.0f), next = demoPlan(scene, 0.5f);
    ASSERT_FALSE(next.directional.tiles.empty());
    FrameStats stats;
    fillShadowPlanStats(first, stats.shadows);
    std::array<CullTileCount, 32> gpuCounts{};
    gpuCounts.fill({3, 1000});
    EXPECT_EQ(allocationsOf([&] {
                  fillShadowPlanStats(next, stats.shadows);
                  setGpuTileCounts(stats.shadows, gpuCounts);
                  FrameStats copy = stats;  // FrameStats moves into the completed list the same way
                  (void)copy;
              }),
              0u);
    EXPECT_EQ(stats.shadows.directional.tileStats.size(), next.directional.tiles.size());
}

TEST_F(FrameAllocationTest, TileCacheDecisionOfASteadyFrameAllocatesNothing) {
    const Scene scene = makeDemoScene();
    const ShadowFrame first = demoPlan(scene, 0.0f), next = demoPlan(scene, 0.5f);
    TileCache cache;
    std::vector<TileSignature> signatures;
    std::vector<uint32_t> draw;
    const auto decide = [&](const ShadowFrame& plan) {
        signatures.clear();
        for (const ShadowTile& tile : plan.directional.tiles)
            signatures.push_back(directionalTileSignature(tile, plan.directional));
        cache.tilesToDraw(signatures, 0, false, 0, true, draw);
    };
    decide(first);
    decide(first);
    EXPECT_EQ(allocationsOf([&] { decide(next); }), 0u);
    EXPECT_EQ(draw.size(), next.directional.tiles.size()) << "the camera moved: every cascade is drawn again";
}

TEST_F(FrameAllocationTest, SteadyForwardFrameWithAStillCameraAllocatesNothing) {
    EXPECT_EQ(steadyFrameAllocations(forwardSettings(), false), 0u);
}

TEST_F(FrameAllocationTest, SteadyForwardFrameWithAMovingCameraAllocatesNothing) {
    EXPECT_EQ(steadyFrameAllocations(forwardSettings(), true), 0u);
}

TEST_F(FrameAllocationTest, SteadyFrameOfTheHardwareShadowRasterizerAllocatesNothing) {
    EXPECT_EQ(steadyFrameAllocations(hardwareRasterSettings(), true), 0u);
}

TEST_F(FrameAllocationTest, SteadyVisibilityBufferFrameAllocatesNothing) {
    if (!gpu::backend(deviceWithoutValidation()).hasBufferInt64Atomics()) GTEST_SKIP() << "no 64-bit buffer atomics";
    EXPECT_EQ(steadyFrameAllocations(visibilitySettings(), true), 0u);
}

Settings virtualSettings(MainView mainView) {
    Settings settings;
    settings.render.mainView = mainView;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.virtualMaps.poolPages = 256;
    return settings;
}

// The renderer's frames with shadows.directional.mode = virtual: the depth prepass (forward) or the
// visibility buffer's geometry, the maps' chains, their stats read back.
TEST_F(FrameAllocationTest, SteadyForwardFrameWithVirtualShadowMapsAllocatesNothing) {
    EXPECT_EQ(steadyFrameAllocations(virtualSettings(MainView::Forward), true), 0u);
}

TEST_F(FrameAllocationTest, SteadyVisibilityBufferFrameWithVirtualShadowMapsAllocatesNothing) {
    if (!gpu::backend(deviceWithoutValidation()).hasBufferInt64Atomics()) GTEST_SKIP() << "no 64-bit buffer atomics";
    EXPECT_EQ(steadyFrameAllocations(virtualSettings(MainView::Visibility), true), 0u);
}

// A frame of a directional light's virtual shadow map (render/virtual_shadow_map.h): the whole chain with
// moved casters' rectangles (so pages are drawn every frame), its stats read back, the frame submitted
// and its readback taken, after frames that used every upload slot.
TEST_F(FrameAllocationTest, SteadyVirtualShadowMapFrameAllocatesNothing) {
    gpu::Device& gpu = gpu::backend(deviceWithoutValidation());
    const Scene scene = makeDemoScene();
    const CameraView view = resolveCameraView(scene, 96, 54);
    SceneDepth depth = renderSceneDepth(gpu, scene, view);
    GpuScene gpuScene(gpu, scene);
    ComputeRasterPass raster(gpu, gpuScene);
    VirtualShadowMapConfig config;
    config.clipmap = {.resolution = 4096, .pageSize = 32, .levelCount = 10, .firstLevelSize = 64.0f};
    VirtualShadowMap map(gpu, gpuScene, raster, config);
    glm::vec3 light(0.0f, -1.0f, 0.0f);
    for (const Light& l : scene.lights)
        if (l.type == LightType::Directional) light = l.wsDirection;
    std::array<gpu_data::VirtualPageInvalidation, 4> moved{};  // the pages around the origin, levels 0 to 3
    for (uint32_t level = 0; level < moved.size(); ++level) moved[level] = virtualPageInvalidation(level, {{-4, -4}, {4, 4}});
    uint32_t drawn = 0;
    const auto frame = [&] {
        gpu::CommandList commands = gpu.beginFrame();
        map.record(commands, VirtualPageDepthSource::texture(depth.texture), view, light, scene.wsBounds, 2.0f, moved);
        const uint64_t at = gpu.readBackAtFrameEnd(commands, map.stats());
        gpu.waitFrame(gpu.submitFrame(commands));
        for (const gpu::CompletedFrame& done : gpu.completedFrames())
            drawn = VirtualShadowMap::statsFromReadback(done.readback.data() + at).toDraw;
        gpu.releaseCompletedFrames();
    };
    for (uint32_t i = 0; i < 2 * gpu.framesInFlight() + 4; ++i) frame();
    EXPECT_EQ(allocationsOf(frame), 0u);
    EXPECT_GT(drawn, 0u) << "the invalidated pages are drawn again every frame";
    gpu.destroy(depth.texture);
}

// Two maps sharing one pool texture and entry buffer (render/virtual_page_storage.h), recorded in one
// frame for two lights: their records allocate nothing either.
TEST_F(FrameAllocationTest, SteadyFrameOfTwoVirtualShadowMapsSharingStorageAllocatesNothing) {
    gpu::Device& gpu = gpu::backend(deviceWithoutValidation());
    const Scene scene = makeDemoScene();
    const CameraView view = resolveCameraView(scene, 96, 54);
    SceneDepth depth = renderSceneDepth(gpu, scene, view);
    GpuScene gpuScene(gpu, scene);
    ComputeRasterPass raster(gpu, gpuScene);
    VirtualShadowMapConfig config;
    config.clipmap = {.resolution = 4096, .pageSize = 32, .levelCount = 10, .firstLevelSize = 64.0f};
    VirtualPageStorageSet storage(gpu, config.clipmap, config.poolPagesPerSide, 2);
    const VirtualPageStorage places[2] = {storage.storageFor(0), storage.storageFor(1)};
    VirtualShadowMap first(gpu, gpuScene, raster, config, &places[0]), second(gpu, gpuScene, raster, config, &places[1]);
    const glm::vec3 lights[2] = {glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f)), glm::normalize(glm::vec3(-0.5f, -1.0f, 0.1f))};
    const gpu_data::VirtualPageInvalidation moved = virtualPageInvalidation(0, {{-4, -4}, {4, 4}});
    const auto frame = [&] {
        gpu::CommandList commands = gpu.beginFrame();
        first.record(commands, VirtualPageDepthSource::texture(depth.texture), view, lights[0], scene.wsBounds, 2.0f,
                     std::span(&moved, 1));
        second.record(commands, VirtualPageDepthSource::texture(depth.texture), view, lights[1], scene.wsBounds, 2.0f,
                      std::span(&moved, 1));
        gpu.waitFrame(gpu.submitFrame(commands));
        gpu.releaseCompletedFrames();
    };
    for (uint32_t i = 0; i < 2 * gpu.framesInFlight() + 4; ++i) frame();
    EXPECT_EQ(allocationsOf(frame), 0u);
    gpu.destroy(depth.texture);
}

}  // namespace
}  // namespace penumbra::test
