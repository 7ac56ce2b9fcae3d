// The virtual shadow map lookup on the GPU (penumbra/shadows/virtual_shadow_lookup.glsl, through the tests' probe
// virtual_shadow_probe.comp) against its CPU reference (src/shadows/virtual_shadow_lookup.h) on the same
// page table and pool, and, on the demo scene drawn into pages by the page drawing pass, against the
// ray-traced reference (reference/embree_scene.h) at ground points that are clearly lit or clearly shadowed.
//
// Tolerance against the CPU: the shadow term within 1e-4 and the same serving level, except at points
// whose virtual texel coordinate (at any level from the footprint's to the one that served) lies within
// 1e-3 texel of a texel edge, or whose footprint lies within 1e-5 (relative) of a level boundary: there
// the float rounding of the light-space transform or of log2 may pick the neighbouring texel or level.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

#include "pass_bindings.h"
#include "penumbra/scene_loading.h"
#include "reference/embree_scene.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/pass_layouts.h"
#include "render/virtual_page_draw_pass.h"
#include "render_test_support.h"
#include "virtual_shadow_test_support.h"
#include "shadows/cascades.h"
#include "shadows/virtual_page_depth.h"
#include "shadows/virtual_shadow_lookup.h"

namespace penumbra::test {
namespace {

using gpu_data::VirtualPageEntry;
using gpu_data::VirtualShadowLookupData;
using gpu_data::VirtualShadowProbePoint;
using gpu_data::VirtualShadowProbeResult;

const VirtualPageEntry kNoPage{gpu_data::kVirtualPageNone, 0, 0, 0, 0, 0, 0, 0};

class VirtualShadowLookupTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }
};

// Integer hash (a fixed mix of multiplications and shifts) for the table's made-up states.
uint32_t mixBits(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}

// A table of every state: per window page of every level, ready (60 %), dirty, missing or stale (the slot
// holds another page), ready pages spread over 16 physical pages of random depths in [0.3, 0.7].
TEST_F(VirtualShadowLookupTest, TheGpuLookupMatchesTheCpuReferenceOnTheSameTable) {
    // 16 pages of 16 texels a side; levels of 16, 32, 64 and 128 m: texels of 1/16 to 1/2 m.
    const VirtualClipmapConfig config{.resolution = 16 * 16, .pageSize = 16, .levelCount = 4, .firstLevelSize = 16.0f};
    constexpr uint32_t kPool = 4, kSide = kPool * 16;
    const glm::vec2 lsCamera(-3.3f, 2.7f);
    const glm::mat4 rotation = lightRotationFromWorld(glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)));
    const VirtualShadowLookupData data = packVirtualShadowLookup(config, rotation, 30.0f, -30.0f, lsCamera, kPool);
    std::vector<VirtualPageEntry> entries(size_t(config.levelCount) * 256, kNoPage);
    for (uint32_t level = 0; level < config.levelCount; ++level) {
        const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
        for (int y = placed.window.min.y; y <= placed.window.max.y; ++y)
            for (int x = placed.window.min.x; x <= placed.window.max.x; ++x) {
                const uint32_t h = mixBits(uint32_t(x * 73856093) ^ uint32_t(y * 19349663) ^ (level * 83492791u));
                const uint32_t state = h % 10, flags = state == 6 ? 3u : state == 7 ? 0u : 1u;  // 3: resident | dirty
                VirtualPageEntry& e = entries[size_t(virtualShadowEntryIndex(data, level, {x, y}))];
                e = {flags ? (h >> 8) % (kPool * kPool) : gpu_data::kVirtualPageNone, flags, x + (state == 8 ? 16 : 0), y, 0, 0.0f, 0.0f, 0};
            }
    }
    std::vector<float> depths(size_t(kSide) * kSide);
    for (size_t i = 0; i < depths.size(); ++i) depths[i] = 0.3f + 0.4f * float(mixBits(uint32_t(i) + 12345u) % 4096u) / 4096.0f;
    // As the copy pass stores drawn pages: each page's codes of its own range, the range in its entries.
    const VirtualPoolCodes codes = encodeVirtualPool(depths, kSide, config.pageSize);
    setVirtualPageRanges(entries, codes, kPool, 0);
    const std::vector<uint16_t>& pool = codes.codes;

    std::mt19937 random(20261205u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<VirtualShadowProbePoint> points;
    const glm::mat4 worldFromLight = glm::inverse(rotation);
    for (int i = 0; i < 6000; ++i) {
        const float reach = i % 4 == 0 ? 80.0f : i % 4 == 1 ? 30.0f : 7.0f;  // beyond every window, level 1's, level 0's
        const glm::vec3 ls(lsCamera.x + reach * (2.0f * unit(random) - 1.0f), lsCamera.y + reach * (2.0f * unit(random) - 1.0f),
                           30.0f - 60.0f * unit(random));
        const float footprint = 0.01f * std::exp2(7.0f * unit(random));  // 1 cm to 1.3 m: every level
        points.push_back({glm::vec3(worldFromLight * glm::vec4(ls, 1.0f)), footprint});
    }
    ShadowProbe probe(gpu());
    const gpu::TextureHandle texture = probe.uploadPool(pool, kSide);
    const std::vector<VirtualShadowProbeResult> results = probe.run(data, entries, texture, points);
    gpu().destroy(texture);
    const Agreement a = compareWithCpu(data, {entries, pool}, points, results);
    EXPECT_EQ(a.differ, 0u);
    EXPECT_LT(a.nearEdges, points.size() / 50) << "few points are excused";
    for (uint32_t level = 0; level < config.levelCount; ++level) EXPECT_GT(a.perLevel[level], 100u) << "level " << level << " served";
    EXPECT_GT(a.fellBack, 200u) << "lookups served by a coarser level than the footprint's";
    EXPECT_GT(a.fractional, 500u) << "2 x 2 compares that blend lit and shadowed texels";
    EXPECT_GT(a.unserved, 200u) << "receivers outside every window";
    std::printf("%zu points: %zu near an edge, %zu fractional, %zu fell back, %zu outside; per level %zu %zu %zu %zu\n",
                points.size(), a.nearEdges, a.fractional, a.fellBack, a.unserved, a.perLevel[0], a.perLevel[1], a.perLevel[2],
                a.perLevel[3]);
}

// ---- The demo scene drawn into pages around the world's origin (its near casters stand within 6 m of it):
// level 3 (4 m pages) 4 x 4 pages, level 2 (2 m) 3 x 3.
constexpr uint32_t kScenePool = 5;  // 25 physical pages of 128 texels

// Pages of 0.5, 1, 2 and 4 m; level 2's texels are 1.6 cm, level 3's 3.1 cm.
VirtualClipmapConfig sceneClipmap() { return {.resolution = 128 * 16, .pageSize = 128, .levelCount = 4, .firstLevelSize = 8.0f}; }

// A page to draw: global page `page` of `level` into physical page `physical`.
struct ScenePage {
    uint32_t level = 0;
    glm::ivec2 page{0};
    uint32_t physical = 0;
};

// The draw list (VirtualPageDrawHeader + VirtualPageDraw[]) of the pages, as the page table would write it.
std::vector<uint8_t> drawListBytes(const VirtualShadowLookupData& data, const std::vector<ScenePage>& pages) {
    gpu_data::VirtualPageDrawHeader header{};
    const uint32_t count = uint32_t(pages.size());
    header.pageDispatch = glm::uvec4(count, 1, 1, 0);
    header.listDispatch = glm::uvec4((count + gpu_data::kVirtualPageGroupSize - 1) / gpu_data::kVirtualPageGroupSize, 1, 1, 0);
    header.count = count;
    std::vector<uint8_t> bytes(sizeof(header) + pages.size() * sizeof(gpu_data::VirtualPageDraw));
    std::memcpy(bytes.data(), &header, sizeof(header));
    for (size_t i = 0; i < pages.size(); ++i) {
        const gpu_data::VirtualPageDraw draw{uint32_t(virtualShadowEntryIndex(data, pages[i].level, pages[i].page)),
                                             pages[i].physical, pages[i].page.x, pages[i].page.y};
        std::memcpy(bytes.data() + sizeof(header) + i * sizeof(draw), &draw, sizeof(draw));
    }
    return bytes;
}

// Draws the pages of a draw list with the page drawing pass; `entries` gets the drawn pages' depth ranges.
void drawPages(gpu::Device& gpu, VirtualPageDrawPass& drawPass, const VirtualPageDrawSpace& space,
               const std::vector<uint8_t>& list, std::vector<VirtualPageEntry>& entries) {
    const gpu::BufferHandle drawList = gpu.createBuffer(list.size(), gpu::kBufferStorage | gpu::kBufferIndirect,
                                                        gpu::MemoryKind::HostVisible, list.data(), "test page draw list");
    const uint64_t entryBytes = entries.size() * sizeof(VirtualPageEntry);
    const gpu::BufferHandle entryBuffer = gpu.createBuffer(entryBytes, gpu::kBufferStorage, gpu::MemoryKind::HostVisible,
                                                           entries.data(), "test page entries");
    gpu::CommandList commands = gpu.beginCommands();
    drawPass.record(commands, {drawList, {entryBuffer, 0, entryBytes}, &space, true, {}, 0});
    commands.pass("test/host", {gpu::use(entryBuffer, gpu::Usage::HostRead)});
    gpu.submitAndWait(commands);
    std::memcpy(entries.data(), gpu.mappedPointer(entryBuffer), entryBytes);
    gpu.destroy(drawList);
    gpu.destroy(entryBuffer);
}

TEST_F(VirtualShadowLookupTest, DemoGroundPointsAreShadowedWhereTheRayTracerSaysSo) {
    const Scene scene = makeDemoScene();
    glm::vec3 wsLight = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    for (const Light& light : scene.lights)
        if (light.type == LightType::Directional) {
            wsLight = light.wsDirection;
            break;
        }
    const VirtualClipmapConfig config = sceneClipmap();
    const VirtualPageDrawSpace space = makeVirtualPageDrawSpace(config, wsLight, scene.wsBounds);
    const glm::vec2 lsCentre(space.lightRotationFromWorld * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // the near casters' middle
    const VirtualShadowLookupData data = packVirtualShadowLookup(config, space.lightRotationFromWorld, space.lsDepthNear,
                                                                 space.lsDepthFar, lsCentre, kScenePool);
    std::vector<ScenePage> pages;
    for (const auto& [level, from, to] : {std::tuple{3u, -2, 1}, std::tuple{2u, -1, 1}}) {
        const glm::ivec2 centre = glm::ivec2(glm::floor(lsCentre / (config.firstLevelSize * std::exp2(float(level)) / 16.0f)));
        for (int y = from; y <= to; ++y)
            for (int x = from; x <= to; ++x) pages.push_back({level, centre + glm::ivec2(x, y), uint32_t(pages.size())});
    }
    std::vector<VirtualPageEntry> entries(size_t(config.levelCount) * 256, kNoPage);
    for (const ScenePage& p : pages)
        entries[size_t(virtualShadowEntryIndex(data, p.level, p.page))] = {p.physical, gpu_data::kVirtualPageResident, p.page.x,
                                                                            p.page.y, 0, 0.0f, 0.0f, 0};
    GpuScene gpuScene(gpu(), scene);
    ComputeRasterPass raster(gpu(), gpuScene);
    VirtualPageDrawPass drawPass(gpu(), gpuScene, raster, config, kScenePool);
    drawPages(gpu(), drawPass, space, drawListBytes(data, pages), entries);
    const glm::vec2 drawnMin = glm::vec2(pages.front().page) * 4.0f;  // level 3's 4 x 4 pages, 4 m each
    const Aabb drawn{glm::vec3(drawnMin, 0.0f), glm::vec3(drawnMin + 16.0f, 0.0f)};
    std::vector<VirtualShadowProbePoint> points;
    std::vector<bool> shadowed;
    // Their footprint, 2 cm, is level 2's: level 3 serves beyond level 2's 3 x 3 pages.
    clearGroundPoints(scene, space.lightRotationFromWorld, wsLight, drawn, points, shadowed);
    ShadowProbe probe(gpu());
    const std::vector<VirtualShadowProbeResult> results = probe.run(data, entries, drawPass.poolTexture(), points);
    const std::vector<uint16_t> pool = probe.readPool(drawPass.poolTexture());
    size_t wrong = 0, inShadow = 0, served[2] = {0, 0};
    for (size_t i = 0; i < points.size(); ++i) {
        ASSERT_GE(results[i].level, 2) << "every ground point lies in a drawn page";
        ++served[results[i].level - 2];
        inShadow += shadowed[i];
        wrong += shadowed[i] ? results[i].lit > 0.5f : results[i].lit < 0.5f;
    }
    std::printf("%zu ground points (%zu shadowed), %zu disagree with the ray tracer; served by level 2: %zu, level 3: %zu\n",
                points.size(), inShadow, wrong, served[0], served[1]);
    EXPECT_GT(inShadow, 100u);
    EXPECT_GT(points.size() - inShadow, 1000u);
    EXPECT_GT(served[0], 300u);
    EXPECT_GT(served[1], 500u);
    EXPECT_LE(wrong, points.size() / 200) << "at most 0.5 % disagree (acne, or edges the rays and the pages cut differently)";
    const Agreement a = compareWithCpu(data, {entries, pool}, points, results);
    EXPECT_EQ(a.differ, 0u) << "the GPU lookup equals the CPU reference on the drawn pool";
}

}  // namespace
}  // namespace penumbra::test
