// Drawing the virtual shadow map's dirty pages (render/virtual_page_draw_pass.h) with the shared compute
// rasterizer, from a draw list the test writes (as the page table pass would on the GPU), against two
// references: the hardware rasterizer (the shadow caster pass, depth clamp, LessOrEqual) drawing each page
// as one tile of an atlas laid out like the pool with the CPU's projection of the page, and, for a ground
// plane, its light-space depth computed on the CPU at every texel centre.
//
// Tolerances: against the hardware, a texel agrees when both are far or their depths differ by at most
// 1e-5 of the depth range plus the pool's quantization step (the page's own depth range / 65534:
// virtual_page_structs.h, "The pool's texels"); at most 0.1 % of a page's texels may disagree (coverage
// of edges exactly on a texel centre, rounded differently). Against the plane: 2e-5 of the depth range
// plus the step, everywhere.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "cull_structs.h"
#include "pass_bindings.h"
#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/shadow_caster_pass.h"
#include "render/shadow_culling_pass.h"
#include "render/virtual_page_draw_pass.h"
#include "render/virtual_page_storage.h"
#include "render_test_support.h"
#include "shadows/cull_packing.h"
#include "shadows/spot_projection.h"
#include "shadows/virtual_faces.h"
#include "shadows/virtual_page_depth.h"
#include "virtual_face_structs.h"

namespace penumbra::test {
namespace {

constexpr uint32_t kPoolPagesPerSide = 4;  // 16 physical pages, 512 x 512 texels
constexpr float kFar = 1.0f;
using gpu_data::kVirtualPageNone;
using gpu_data::VirtualPageEntry;
constexpr uint32_t kMaxLevels = 64;  // levels (faces' mip * faceCount + face) the rig's entries hold, of 16^2 pages

VirtualClipmapConfig testClipmap() {
    VirtualClipmapConfig config;
    config.resolution = 128 * 16;  // 16 pages a level's side
    config.pageSize = 128;
    config.levelCount = 4;
    config.firstLevelSize = 8.0f;  // pages of 0.5, 1, 2 and 4 m
    return config;
}

// A page to draw: global page `page` of `level` into physical page `physical`.
struct PageDraw {
    uint32_t level = 0;
    glm::ivec2 page{0};
    uint32_t physical = 0;
};

glm::vec3 firstDirectionalLight(const Scene& scene) {
    for (const Light& light : scene.lights)
        if (light.type == LightType::Directional) return light.wsDirection;
    return glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
}

// Faces' pages (a table of fixed windows: level = mip * faceCount + face) of 16 pages a side, 5 mips.
constexpr VirtualFaceConfig kFaceConfig{.resolution = 128 * 16, .pageSize = 128};

// One pass and its pool, on a scene; draws pages and reads the pool back. With faces, the pages are
// theirs (spot and point light faces) instead of the clipmap's.
class PageRig {
public:
    PageRig(gpu::Device& gpu, Scene scene, std::vector<VirtualFace> faces = {}, uint32_t poolPagesPerSide = kPoolPagesPerSide)
        : gpu_(gpu), scene_(std::move(scene)), gpuScene_(gpu, scene_), raster_(gpu, gpuScene_),
          pages_(faces.empty() ? VirtualPageDrawPass(gpu, gpuScene_, raster_, testClipmap(), poolPagesPerSide)
                               : VirtualPageDrawPass(gpu, gpuScene_, raster_, kFaceConfig, poolPagesPerSide)),
          faces_(std::move(faces)) {
        space_ = makeVirtualPageDrawSpace(testClipmap(), firstDirectionalLight(scene_), scene_.wsBounds);
        using namespace gpu_data;
        writes_ = {{kSceneBindingVertices, gpuScene_.vertexBuffer(), {}, {}},
                   {kSceneBindingInstances, gpuScene_.instanceBuffer(), {}, {}},
                   {kSceneBindingMaterials, gpuScene_.materialBuffer(), {}, {}}};
        drawList_ = gpu.createBuffer(sizeof(VirtualPageDrawHeader) + pages_.capacity() * sizeof(VirtualPageDraw),
                                     gpu::kBufferStorage | gpu::kBufferIndirect, gpu::MemoryKind::HostVisible, nullptr,
                                     "test page draw list");
        // Entries for every level the tests draw (the copy step writes a drawn page's depth range there).
        const std::vector<VirtualPageEntry> entries(size_t(kMaxLevels) * 16 * 16, VirtualPageEntry{kVirtualPageNone, 0, 0, 0, 0, 0.0f, 0.0f, 0});
        entries_ = gpu.createBuffer(entries.size() * sizeof(VirtualPageEntry), gpu::kBufferStorage, gpu::MemoryKind::HostVisible,
                                    entries.data(), "test page entries");
        physicalEntry_.assign(pages_.capacity(), kVirtualPageNone);
        std::vector<VirtualFaceData> faceData;
        for (const VirtualFace& face : faces_) faceData.push_back({face.clipFromWorld, face.wsPosition, face.tanHalfFov});
        if (!faceData.empty())
            faceBuffer_ = gpu.createBuffer(faceData.size() * sizeof(VirtualFaceData), gpu::kBufferStorage,
                                           gpu::MemoryKind::HostVisible, faceData.data(), "test faces");
    }
    ~PageRig() {
        gpu_.destroy(drawList_);
        gpu_.destroy(entries_);
        gpu_.destroy(faceBuffer_);
    }

    const Scene& scene() const { return scene_; }
    const VirtualPageDrawSpace& space() const { return space_; }
    VirtualPageDrawSpace& space() { return space_; }
    VirtualPageDrawPass& pass() { return pages_; }
    uint32_t side() const { return pages_.poolSide(); }
    uint32_t poolPagesPerSide() const { return pages_.poolSide() / 128; }

    // Writes the list as the page table pass would (header with its dispatch sizes, then the draws) and draws it.
    void draw(const std::vector<PageDraw>& draws) {
        const uint32_t perSide = faces_.empty() ? pagesPerSide(testClipmap()) : virtualFacePagesPerSide(kFaceConfig);
        const uint32_t count = uint32_t(draws.size());
        gpu_data::VirtualPageDrawHeader header{};
        header.pageDispatch = glm::uvec4(count, 1, 1, 0);
        header.listDispatch = glm::uvec4((count + gpu_data::kVirtualPageGroupSize - 1) / gpu_data::kVirtualPageGroupSize, 1, 1, 0);
        header.count = count;
        std::vector<gpu_data::VirtualPageDraw> list;
        for (const PageDraw& d : draws) {
            const auto wrap = [&](int v) { return uint32_t(((v % int(perSide)) + int(perSide)) % int(perSide)); };
            const uint32_t entry = (d.level * perSide + wrap(d.page.y)) * perSide + wrap(d.page.x);
            list.push_back({entry, d.physical, d.page.x, d.page.y});
            physicalEntry_.at(d.physical) = entry;
        }
        gpu_.writeBuffer(drawList_, &header, sizeof(header));
        if (!list.empty()) gpu_.writeBuffer(drawList_, list.data(), list.size() * sizeof(list[0]), sizeof(header));
        gpu::CommandList commands = gpu_.beginCommands();
        VirtualPageDrawInputs inputs{drawList_, {entries_, 0, gpu_.bufferSize(entries_)}, faces_.empty() ? &space_ : nullptr, true, {}, 0};
        if (!faces_.empty()) {
            inputs.faces = {faceBuffer_, 0, faces_.size() * sizeof(gpu_data::VirtualFaceData)};
            inputs.faceCount = uint32_t(faces_.size());
        }
        pages_.record(commands, inputs);
        gpu_.submitAndWait(commands);
    }

    // The pool's depths, row by row: its codes decoded with the ranges the copy step wrote into the entries of
    // the pages drawn last into each physical page (a page never drawn holds far codes, which decode to far).
    std::vector<float> readPool() {
        const std::vector<uint16_t> codes = readCodes(pages_.poolTexture());
        std::vector<VirtualPageEntry> entries(gpu_.bufferSize(entries_) / sizeof(VirtualPageEntry));
        std::memcpy(entries.data(), gpu_.mappedPointer(entries_), entries.size() * sizeof(VirtualPageEntry));
        std::vector<float> texels(size_t(side()) * side());
        for (uint32_t y = 0; y < side(); ++y)
            for (uint32_t x = 0; x < side(); ++x) {
                const uint32_t physical = y / 128 * poolPagesPerSide() + x / 128, entry = physicalEntry_[physical];
                const VirtualPageDepthRange range =
                    entry == kVirtualPageNone ? VirtualPageDepthRange{} : VirtualPageDepthRange{entries[entry].depthMin, entries[entry].depthStep};
                texels[size_t(y) * side() + x] = virtualPoolDepth(codes, side(), x, y, range);
            }
        return texels;
    }
    // The quantization step of the page last drawn into `physical` (what a tolerance must add).
    float depthStep(uint32_t physical) {
        const uint32_t entry = physicalEntry_.at(physical);
        if (entry == kVirtualPageNone) return 0.0f;
        VirtualPageEntry e;
        std::memcpy(&e, static_cast<const uint8_t*>(gpu_.mappedPointer(entries_)) + entry * sizeof(e), sizeof(e));
        return e.depthStep;
    }

    // The hardware rasterizer's depth of the same pages, drawn where the compute rasterizer draws them and laid out as the pool: every caster
    // drawn (a culling tile that keeps everything), projected by the CPU's virtualPageClipFromWorld.
    std::vector<float> hardwareReference(const std::vector<PageDraw>& draws) {
        ShadowCullingPass culling(gpu_, gpuScene_);
        ShadowCasterPass casters(gpu_, gpuScene_);
        CullTileUpload tiles;
        std::vector<ShadowTile> shadowTiles;
        std::vector<uint32_t> drawn;
        for (const PageDraw& d : draws) {
            gpu_data::CullTile& keepAll = tiles.tiles[shadowTiles.size()];
            keepAll = {};
            keepAll.lightFromWorld = space_.lightRotationFromWorld;
            keepAll.kind = gpu_data::kCullTileDirectional;
            keepAll.halfExtent = keepAll.farDistance = 1e30f;
            ShadowTile tile;
            // Where the compute rasterizer draws it: the record's depth target's slot (laid out as the
            // pool below).
            const gpu::Rect rect = virtualPageRect(uint32_t(shadowTiles.size()), pages_.targetPagesPerSide(), 128);
            tile.rect.offset = glm::uvec2(rect.x, rect.y);
            tile.rect.size = 128;
            const uint32_t faceCount = uint32_t(faces_.size());
            tile.clipFromWorld = faces_.empty() ? virtualPageClipFromWorld(space_, d.level, d.page)
                                                : virtualFacePageClipFromWorld(faces_[d.level % faceCount],
                                                                               virtualFacePagesPerSide(kFaceConfig),
                                                                               d.level / faceCount, d.page);
            drawn.push_back(uint32_t(shadowTiles.size()));
            shadowTiles.push_back(tile);
        }
        const uint32_t count = uint32_t(draws.size()), groups = gpu_data::kCullWorkgroupSize;
        tiles.header.count = count;
        tiles.header.cullDispatch = glm::uvec4((gpuScene_.instanceCount() + groups - 1) / groups, count, 1, 0);
        tiles.header.drawsDispatch = glm::uvec4((gpuScene_.meshSlotCount() + groups - 1) / groups, count, 1, 0);
        gpu_data::CullFrame frame{};
        frame.instanceCount = gpuScene_.instanceCount();
        frame.meshCount = gpuScene_.meshSlotCount();
        const gpu::BufferHandle frameBuffer = gpu_.createBuffer(sizeof(frame), gpu::kBufferUniform, gpu::MemoryKind::HostVisible,
                                                                &frame, "test cull frame");
        const gpu::BufferHandle tileBuffer = gpu_.createBuffer(tiles.bytes(), gpu::kBufferStorage | gpu::kBufferIndirect,
                                                               gpu::MemoryKind::HostVisible, &tiles, "test cull tiles");
        const gpu::TextureHandle atlas = gpu_.createTexture(
            {side(), side(), gpu::Format::D32Float, gpu::kTextureDepthTarget | gpu::kTextureTransferSrc, 1, "test hw pages"});
        gpu::CommandList commands = gpu_.beginCommands();
        culling.record(commands, {frameBuffer, 0, sizeof(frame)}, {tileBuffer, 0, tiles.bytes()}, "test.culling");
        casters.record(commands, shadowTiles, drawn, true, 0, atlas, side(), writes_, culling, "test.hw");
        gpu_.submitAndWait(commands);
        const std::vector<float> depth = readTexture(atlas, "hw");
        gpu_.destroy(atlas);
        gpu_.destroy(frameBuffer);
        gpu_.destroy(tileBuffer);
        std::vector<float> pool(depth.size(), kFar);  // each slot at its physical page, as the copy step does
        for (size_t i = 0; i < draws.size(); ++i) {
            const gpu::Rect from = virtualPageRect(uint32_t(i), pages_.targetPagesPerSide(), 128);
            const gpu::Rect to = virtualPageRect(draws[i].physical, poolPagesPerSide(), 128);
            for (int32_t y = 0; y < 128; ++y)
                for (int32_t x = 0; x < 128; ++x)
                    pool[size_t(to.y + y) * side() + to.x + x] = depth[size_t(from.y + y) * side() + from.x + x];
        }
        return pool;
    }

    // The GPU-written culling tile list of the last draw.
    std::vector<gpu_data::CullTile> tileRecords(gpu_data::CullTileListHeader& header) {
        const std::vector<uint8_t> bytes = gpu_.readBuffer(pages_.tileList());
        std::memcpy(&header, bytes.data(), sizeof(header));
        std::vector<gpu_data::CullTile> records(header.count);
        std::memcpy(records.data(), bytes.data() + sizeof(header), records.size() * sizeof(gpu_data::CullTile));
        return records;
    }

private:
    // A texture of side() rows of `width` Texels (a pool's bytes, `width` its row's bytes; a depth image's
    // floats), row by row.
    template <typename Texel>
    std::vector<Texel> readTexels(gpu::TextureHandle texture, uint32_t width, const char* what) {
        std::vector<Texel> texels(size_t(width) * side());
        const gpu::BufferHandle readback = gpu_.createBuffer(texels.size() * sizeof(Texel), gpu::kBufferTransferDst,
                                                             gpu::MemoryKind::HostVisible, nullptr, what);
        gpu::CommandList commands = gpu_.beginCommands();
        commands.pass("test/read", {gpu::use(texture, gpu::Usage::TransferRead), gpu::use(readback, gpu::Usage::TransferWrite)});
        commands.copyTextureToBuffer(texture, readback);
        commands.pass("test/host", {gpu::use(readback, gpu::Usage::HostRead)});
        gpu_.submitAndWait(commands);
        std::memcpy(texels.data(), gpu_.mappedPointer(readback), texels.size() * sizeof(Texel));
        gpu_.destroy(readback);
        return texels;
    }
    // The pool's depth codes, row by row, from either pool format (virtual_page_structs.h, "The pool's texels").
    std::vector<uint16_t> readCodes(gpu::TextureHandle texture) {
        const uint32_t texelBytes = virtualPoolBytesPerTexel(gpu_.textureDesc(texture).format);
        return virtualPoolCodesOfBytes(readTexels<uint8_t>(texture, side() * texelBytes, "pool"), texelBytes);
    }
    std::vector<float> readTexture(gpu::TextureHandle texture, const char* what) { return readTexels<float>(texture, side(), what); }

    gpu::Device& gpu_;
    Scene scene_;
    GpuScene gpuScene_;
    ComputeRasterPass raster_;
    VirtualPageDrawPass pages_;
    std::vector<VirtualFace> faces_;
    gpu::BufferHandle faceBuffer_;
    VirtualPageDrawSpace space_;
    std::vector<gpu::DescriptorWrite> writes_;
    gpu::BufferHandle drawList_, entries_;
    std::vector<uint32_t> physicalEntry_;  // by physical page: the entry of the page last drawn there
};

// What one page of the pool holds compared with a reference.
struct PageComparison {
    size_t differ = 0;   // texels beyond the tolerance
    size_t written = 0;  // reference texels nearer than far
    size_t texels = 0;
    float worst = 0.0f;  // the largest difference where both are written
};

PageComparison comparePage(const std::vector<float>& pool, const std::vector<float>& reference, uint32_t side,
                           uint32_t physical, float tolerance) {
    const gpu::Rect rect = virtualPageRect(physical, side / 128, 128);
    PageComparison c;
    for (int32_t y = rect.y; y < rect.y + int32_t(rect.height); ++y)
        for (int32_t x = rect.x; x < rect.x + int32_t(rect.width); ++x) {
            const float a = pool[size_t(y) * side + x], b = reference[size_t(y) * side + x];
            ++c.texels;
            c.written += b < kFar;
            if (a < kFar && b < kFar) c.worst = std::max(c.worst, std::abs(a - b));
            c.differ += std::abs(a - b) > tolerance;
        }
    return c;
}

// Level `level`'s page holding light-space point lsPoint.
glm::ivec2 pageAt(const glm::vec2& lsPoint, uint32_t level) {
    const VirtualClipmapConfig config = testClipmap();
    const float lsPage = config.firstLevelSize * std::exp2(float(level)) / float(pagesPerSide(config));
    return glm::ivec2(glm::floor(lsPoint / lsPage));
}

Aabb lightSpaceBounds(const PageRig& rig) { return rig.scene().wsBounds.transformed(rig.space().lightRotationFromWorld); }

class VirtualPageDrawTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }
};

// The demo's casters (boxes, spheres, an alpha-clipped quad, a dithered sphere on a large ground) in pages
// of every level: levels 0 and 1 at the centres of its four smallest casters (so each of those pages holds
// one), levels 2 and 3 at the scene's centre, and level 0 at two casters' edges.
std::vector<PageDraw> demoPages(const PageRig& rig) {
    const Scene& scene = rig.scene();
    std::vector<const Instance*> casters;
    for (const Instance& instance : scene.instances)
        if (instance.castShadows && instance.wsBounds.valid()) casters.push_back(&instance);
    std::sort(casters.begin(), casters.end(), [](const Instance* a, const Instance* b) {
        return glm::length(a->wsBounds.max - a->wsBounds.min) < glm::length(b->wsBounds.max - b->wsBounds.min);
    });
    const glm::mat4& rotation = rig.space().lightRotationFromWorld;
    const glm::vec2 centre = glm::vec2(lightSpaceBounds(rig).center());
    std::vector<PageDraw> draws = {{3, pageAt(centre, 3), 5}, {2, pageAt(centre, 2), 0}};
    const uint32_t physical[4] = {10, 3, 15, 6};
    for (size_t i = 0; i < casters.size() && i < 4; ++i) {
        const glm::vec2 lsCaster(rotation * glm::vec4(casters[i]->wsBounds.center(), 1.0f));
        draws.push_back({uint32_t(i % 2), pageAt(lsCaster, uint32_t(i % 2)), physical[i]});
    }
    // The level-0 pages holding the two smallest casters' light-space +x edge: only part of each caster's
    // bounds lies in the page (a page's culling must keep a caster that overlaps its border).
    const uint32_t edgePhysical[2] = {8, 12};
    for (size_t i = 0; i < casters.size() && i < 2; ++i) {
        const Aabb ls = casters[i]->wsBounds.transformed(rotation);
        draws.push_back({0, pageAt(glm::vec2(ls.max.x - 0.01f, ls.center().y), 0), edgePhysical[i]});
    }
    return draws;
}

// A record draws every page of the pool up to its depth target's 484 slots, unless the culling's lists
// (room for every instance in each, two more than the pages) would take more than the budget; never
// fewer than 32 pages (or the pool).
TEST(VirtualPagesPerRecord, FollowTheCullingListsBudgetUpToTheDepthTargetsSlots) {
    constexpr uint64_t kBudget = kVirtualPageListBytes;
    EXPECT_EQ(virtualPagesPerRecord(400, 1000, kBudget), 400u);
    EXPECT_EQ(virtualPagesPerRecord(3600, 1000, kBudget), kMaxVirtualPagesPerRecord);
    EXPECT_EQ(virtualPagesPerRecord(3600, 100000, kBudget), kMaxVirtualPagesPerRecord);  // lists for 1342
    EXPECT_EQ(virtualPagesPerRecord(3600, 1000000, kBudget), 134u - 2u);  // 4 MB a list
    EXPECT_EQ(virtualPagesPerRecord(3600, 10000000, kBudget), 32u);       // the least
    EXPECT_EQ(virtualPagesPerRecord(16, 10000000, kBudget), 16u);         // a pool smaller than that
    EXPECT_EQ(virtualPagesPerRecord(3600, 0, kBudget), kMaxVirtualPagesPerRecord);
    EXPECT_EQ(virtualDrawBudget(0, 65), 65u);
    EXPECT_EQ(virtualDrawBudget(8, 65), 8u);
    EXPECT_EQ(virtualDrawBudget(100, 65), 65u);
}

TEST(VirtualPagesPerRecord, TheDepthTargetIsTheSmallestSquareOfSlotsThatHoldsThem) {
    EXPECT_EQ(virtualDrawTargetPagesPerSide(1), 1u);
    EXPECT_EQ(virtualDrawTargetPagesPerSide(16), 4u);
    EXPECT_EQ(virtualDrawTargetPagesPerSide(17), 5u);
    EXPECT_EQ(virtualDrawTargetPagesPerSide(kMaxVirtualPagesPerRecord), 22u);
}

TEST_F(VirtualPageDrawTest, PagesMatchTheHardwareRasterizerTexelForTexel) {
    PageRig rig(gpu(), makeDemoScene());
    const std::vector<PageDraw> draws = demoPages(rig);
    rig.draw(draws);
    const std::vector<float> pool = rig.readPool(), reference = rig.hardwareReference(draws);
    for (const PageDraw& d : draws) {
        const PageComparison c = comparePage(pool, reference, rig.side(), d.physical, 1e-5f + rig.depthStep(d.physical));
        const std::string what = "level " + std::to_string(d.level) + " page (" + std::to_string(d.page.x) + ", " +
                                 std::to_string(d.page.y) + ")";
        EXPECT_GT(c.written, c.texels / 4) << what << ": the page holds casters";
        EXPECT_LE(c.differ, c.texels / 1000) << what << ": " << c.differ << " texels differ, worst depth difference " << c.worst;
        std::printf("%s: %zu of %zu texels written, %zu differ, worst %.2e\n", what.c_str(), c.written, c.texels, c.differ,
                    double(c.worst));
        ASSERT_GE(draws.size(), 8u) << "the demo has at least four casters besides its ground";
    }
}

// The pool holds each drawn texel as a 16-bit code of its page's own depth range (virtual_page_copy.comp):
// decoded, never nearer the light than the rasterizer drew it (quantization lights, never shadows) and
// at most one step (the page's range / 65534) farther; far texels decode to exactly far.
TEST_F(VirtualPageDrawTest, PoolCodesDecodeNoNearerThanDrawnAndWithinOneStepOfIt) {
    PageRig rig(gpu(), makeDemoScene());
    const std::vector<PageDraw> draws = demoPages(rig);
    rig.draw(draws);
    const std::vector<float> pool = rig.readPool();
    const std::vector<uint8_t> bytes = gpu().readBuffer(rig.pass().targetDepth());
    const uint32_t targetSide = rig.pass().targetPagesPerSide() * 128;
    for (size_t i = 0; i < draws.size(); ++i) {
        const gpu::Rect slot = virtualPageRect(uint32_t(i), rig.pass().targetPagesPerSide(), 128);
        const gpu::Rect page = virtualPageRect(draws[i].physical, rig.poolPagesPerSide(), 128);
        const float step = rig.depthStep(draws[i].physical);
        size_t drawn = 0, nearer = 0, beyondStep = 0, farWrong = 0;
        for (int32_t y = 0; y < 128; ++y)
            for (int32_t x = 0; x < 128; ++x) {
                float raw;
                std::memcpy(&raw, bytes.data() + (size_t(slot.y + y) * targetSide + slot.x + x) * 4, 4);
                raw = std::max(raw, 0.0f);
                const float decoded = pool[size_t(page.y + y) * rig.side() + page.x + x];
                if (raw >= kFar) {
                    farWrong += decoded != kFar;
                    continue;
                }
                ++drawn;
                nearer += decoded < raw;
                beyondStep += decoded - raw > step * 1.001f + 1e-7f;
            }
        EXPECT_GT(drawn, 1000u) << "page " << i << " holds casters";
        EXPECT_GT(step, 0.0f) << "page " << i << " spans depths";
        EXPECT_EQ(nearer, 0u) << "page " << i;
        EXPECT_EQ(beyondStep, 0u) << "page " << i;
        EXPECT_EQ(farWrong, 0u) << "page " << i;
    }
}

// A pool of 24^2 pages is larger than a record's depth target (22^2 slots): the pages are drawn in the
// target's first slots and still land at their physical pages, here all beyond the target's 484.
TEST_F(VirtualPageDrawTest, APoolLargerThanTheDepthTargetGetsEveryPageAtItsPhysicalPlace) {
    PageRig rig(gpu(), makeDemoScene(), {}, 24);
    ASSERT_EQ(rig.pass().pagesPerRecord(), kMaxVirtualPagesPerRecord);
    ASSERT_EQ(rig.pass().targetPagesPerSide(), 22u);
    EXPECT_EQ(gpu().bufferSize(rig.pass().targetDepth()), 22ull * 22 * 128 * 128 * 4) << "the target holds a record, not the pool";
    std::vector<PageDraw> draws = demoPages(rig);
    for (PageDraw& d : draws) d.physical = 560 + d.physical;  // of 576
    rig.draw(draws);
    const std::vector<float> pool = rig.readPool(), reference = rig.hardwareReference(draws);
    for (const PageDraw& d : draws) {
        const PageComparison c = comparePage(pool, reference, rig.side(), d.physical, 1e-5f + rig.depthStep(d.physical));
        EXPECT_GT(c.written, c.texels / 4) << "physical page " << d.physical << " holds casters";
        EXPECT_LE(c.differ, c.texels / 1000) << "physical page " << d.physical << ": " << c.differ << " texels differ";
    }
}

TEST_F(VirtualPageDrawTest, TheGpuWritesOneTilePerPageWithTheCpuProjection) {
    PageRig rig(gpu(), makeDemoScene());
    const std::vector<PageDraw> draws = demoPages(rig);
    rig.draw(draws);
    gpu_data::CullTileListHeader header{};
    const std::vector<gpu_data::CullTile> tiles = rig.tileRecords(header);
    ASSERT_EQ(header.count, draws.size());
    EXPECT_EQ(header.cullDispatch.y, draws.size());
    EXPECT_EQ(header.drawsDispatch.y, draws.size());
    for (size_t i = 0; i < draws.size(); ++i) {
        const glm::mat4 cpu = virtualPageClipFromWorld(rig.space(), draws[i].level, draws[i].page);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(tiles[i].clipFromWorld[c][r], cpu[c][r], 1e-4f * std::max(1.0f, std::abs(cpu[c][r]))) << "tile " << i;
        // Page i is drawn into slot i of the record's depth target (then copied to its physical page).
        const gpu::Rect rect = virtualPageRect(uint32_t(i), rig.pass().targetPagesPerSide(), 128);
        EXPECT_EQ(tiles[i].viewport, glm::vec4(rect.x, rect.y, 128, 128)) << "tile " << i;
        EXPECT_EQ(tiles[i].scissor, glm::uvec4(rect.x, rect.y, rect.x + 128, rect.y + 128)) << "tile " << i;
    }
}

TEST_F(VirtualPageDrawTest, PagesNotInTheListKeepTheirContentsAndAnEmptyPageReadsFar) {
    PageRig rig(gpu(), makeDemoScene());
    const std::vector<PageDraw> first = demoPages(rig);
    rig.draw(first);
    const std::vector<float> before = rig.readPool();
    // Physical page 0 now gets a page of level 0 beyond the scene's bounds (no caster), page 1 a drawn one.
    const Aabb ls = lightSpaceBounds(rig);
    const PageDraw empty{0, pageAt(glm::vec2(ls.max) + glm::vec2(10.0f), 0), 0};
    const PageDraw again{2, pageAt(glm::vec2(ls.center()), 2), 1};
    rig.draw({empty, again});
    const std::vector<float> after = rig.readPool();
    const PageComparison emptyPage = comparePage(after, std::vector<float>(after.size(), kFar), rig.side(), 0, 0.0f);
    EXPECT_EQ(emptyPage.differ, 0u) << "a page with no caster reads far (its earlier contents cleared)";
    // Physical page 1 (never drawn before) now holds what physical page 0 held (the same global page).
    for (uint32_t y = 0; y < 128; ++y)
        for (uint32_t x = 0; x < 128; ++x)
            ASSERT_EQ(after[size_t(y) * rig.side() + 128 + x], before[size_t(y) * rig.side() + x]) << x << ", " << y;
    for (const PageDraw& d : first) {
        if (d.physical <= 1) continue;
        EXPECT_EQ(comparePage(after, before, rig.side(), d.physical, 0.0f).differ, 0u) << "physical page " << d.physical << " kept";
    }
}

// A ground of two triangles, 400 m wide, tilted (normal kGroundNormal) so that its light-space depth
// changes along both page axes, under a slanted light: each triangle covers thousands of pages; every
// texel of every page drawn must hold the plane's light-space depth at its centre.
const glm::vec3 kGroundNormal = glm::normalize(glm::vec3(0.15f, 1.0f, -0.1f));

Scene groundScene() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    Mesh ground;
    constexpr float h = 200.0f;
    const glm::vec3 n = kGroundNormal;
    for (glm::vec2 xz : {glm::vec2(-h, -h), glm::vec2(h, -h), glm::vec2(h, h), glm::vec2(-h, h)})  // n . p = 0
        ground.vertices.push_back({glm::vec3(xz.x, -(n.x * xz.x + n.z * xz.y) / n.y, xz.y), n, glm::vec2(0.0f)});
    ground.indices = {0, 1, 2, 0, 2, 3};
    ground.materialIndex = material;
    builder.addInstance(builder.addMesh(ground), glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight(glm::normalize(glm::vec3(0.4f, -1.0f, 0.25f)), 3.0f));
    return builder.build();
}

TEST_F(VirtualPageDrawTest, AGroundTriangleSpanningManyPagesIsDrawnRightInEach) {
    PageRig rig(gpu(), groundScene());
    const VirtualPageDrawSpace& space = rig.space();
    std::vector<PageDraw> draws;
    uint32_t physical = 0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) draws.push_back({0, glm::ivec2(x, y), physical++});  // around the origin
    draws.push_back({3, glm::ivec2(5, -7), physical++});  // finer and coarser, away from the origin
    draws.push_back({2, glm::ivec2(-20, 13), physical++});
    draws.push_back({1, glm::ivec2(40, 3), physical++});
    rig.draw(draws);
    const std::vector<float> pool = rig.readPool();
    // The plane n . world = 0 at light-space (x, y): world = transpose(rotation) * ls, so z solves
    // (rotation * n) . ls = 0.
    const glm::dvec3 k = glm::dmat3(glm::mat3(space.lightRotationFromWorld)) * glm::dvec3(kGroundNormal);
    const VirtualClipmapConfig config = testClipmap();
    for (const PageDraw& d : draws) {
        const double lsPage = config.firstLevelSize * std::exp2(double(d.level)) / pagesPerSide(config);
        const gpu::Rect rect = virtualPageRect(d.physical, rig.poolPagesPerSide(), 128);
        size_t differ = 0;
        double worst = 0.0;
        const double tolerance = 2e-5 + rig.depthStep(d.physical);  // plus the pool's quantization step
        for (uint32_t ty = 0; ty < 128; ++ty)
            for (uint32_t tx = 0; tx < 128; ++tx) {
                const double x = (d.page.x + (tx + 0.5) / 128.0) * lsPage, y = (d.page.y + (ty + 0.5) / 128.0) * lsPage;
                const double z = -(k.x * x + k.y * y) / k.z;
                const double expected = (space.lsDepthNear - z) / (space.lsDepthNear - space.lsDepthFar);
                const float got = pool[size_t(rect.y + ty) * rig.side() + rect.x + tx];
                worst = std::max(worst, std::abs(got - expected));
                differ += std::abs(got - expected) > tolerance;
            }
        EXPECT_EQ(differ, 0u) << "level " << d.level << " page (" << d.page.x << ", " << d.page.y << "): worst " << worst;
    }
}

// A point light 3 m above a scene's centre (faces 0-5) and a spot beside it looking down (face 6): the
// pages of spot and point light faces are the faces' perspective projections cropped to each page
// (virtual_face_tiles.comp), drawn by the compute rasterizer as the hardware draws them. The demo's
// casters, and the tilted ground, whose depth changes across every page (a level ground seen straight
// from above has one depth everywhere, which would hide a page drawn at the wrong place).
void expectFacePagesMatchTheHardware(gpu::Device& gpu, const Scene& scene) {
    const glm::vec3 wsLight = scene.wsBounds.center() + glm::vec3(0.0f, 3.0f, 0.0f);
    std::vector<VirtualFace> faces;
    for (const glm::vec3& direction : pointLightFaceDirections())
        faces.push_back(makeVirtualFace(kFaceConfig, wsLight, direction, 1.0f, 0.1f, 30.0f, 2.0f));
    faces.push_back(makeVirtualFace(kFaceConfig, wsLight + glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 0.6f,
                                    0.1f, 30.0f, 2.0f));
    constexpr uint32_t kFaces = 7, kDown = 3, kSpot = 6;
    PageRig rig(gpu, scene, faces);
    // Mip 0 pages at the centre of the light's downward face and of the spot, every mip of the downward
    // face, and a page of each side face near its bottom edge (where the ground is).
    std::vector<PageDraw> draws = {{kDown, {8, 8}, 0},  {kDown, {7, 8}, 1},  {kSpot, {8, 7}, 2},
                                   {kFaces + kDown, {4, 3}, 3}, {2 * kFaces + kDown, {2, 2}, 4},
                                   {3 * kFaces + kDown, {1, 0}, 5}, {4 * kFaces + kDown, {0, 0}, 6},
                                   {4 * kFaces + kSpot, {0, 0}, 7}};
    for (uint32_t face : {0u, 1u, 4u, 5u}) draws.push_back({kFaces + face, {4, 7}, 8 + face});
    rig.draw(draws);
    const std::vector<float> pool = rig.readPool(), reference = rig.hardwareReference(draws);
    uint32_t pagesWithCasters = 0;
    for (const PageDraw& d : draws) {
        const PageComparison c = comparePage(pool, reference, rig.side(), d.physical, 1e-5f + rig.depthStep(d.physical));
        const std::string what = "face " + std::to_string(d.level % kFaces) + " mip " + std::to_string(d.level / kFaces) +
                                 " page (" + std::to_string(d.page.x) + ", " + std::to_string(d.page.y) + ")";
        EXPECT_LE(c.differ, c.texels / 1000) << what << ": " << c.differ << " texels differ, worst depth difference " << c.worst;
        pagesWithCasters += c.written > c.texels / 4;
    }
    EXPECT_GE(pagesWithCasters, 8u) << "most pages see the ground or a caster";
}

TEST_F(VirtualPageDrawTest, FacePagesMatchTheHardwareRasterizerTexelForTexel) {
    {
        SCOPED_TRACE("demo");
        expectFacePagesMatchTheHardware(gpu(), makeDemoScene());
    }
    SCOPED_TRACE("tilted ground");
    expectFacePagesMatchTheHardware(gpu(), groundScene());
}

}  // namespace
}  // namespace penumbra::test
