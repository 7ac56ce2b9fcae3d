// The CPU reference of virtual shadow map page marking (src/shadows/virtual_page_marking.h): which
// clipmap pages the main view's depth requests, checked against the clipmap rules on synthetic depth
// images (a ground plane under an overhead sun, single pixels at known places).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "shadows/cascades.h"
#include "shadows/virtual_page_marking.h"
#include "shadows/visible_surfaces.h"
#include "virtual_page_structs.h"

namespace penumbra {
namespace {

// 16 pages a side, 8 m level 0 of 1024 texels (7.8 mm texels), 8 levels: the ground camera below
// sees its closest ground (about 1.4 m away, 8.6 mm pixels at 256x192) in level 0.
VirtualClipmapConfig testConfig() {
    return {.resolution = 1024, .pageSize = 64, .levelCount = 8, .firstLevelSize = 8.0f};
}

// A sun straight overhead: light space x = -world x, y = world z.
glm::mat4 overheadSun() { return lightRotationFromWorld(glm::vec3(0.0f, -1.0f, 0.0f)); }

// 1.5 m above the ground at wsEye.xz, looking 35 degrees down along -z.
CameraView groundCamera(const glm::vec2& wsEyeXz = glm::vec2(0.0f), uint32_t width = 256, uint32_t height = 192) {
    Camera camera;
    const glm::vec3 eye(wsEyeXz.x, 1.5f, wsEyeXz.y);
    const glm::vec3 target = eye + glm::vec3(0.0f, -std::sin(glm::radians(35.0f)), -std::cos(glm::radians(35.0f)));
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.yfov = glm::radians(60.0f);
    camera.zNear = 0.05f;
    return makeCameraView(camera, width, height);
}

void setDepth(Image& depth, uint32_t x, uint32_t y, float d) {
    std::memcpy(&depth.pixels[(size_t(y) * depth.width + x) * 4], &d, sizeof(float));
}

// The reversed-Z depth of a world point seen by the view.
float depthOf(const CameraView& view, const glm::vec3& wsPoint) {
    const glm::vec4 clip = view.clipFromWorld * glm::vec4(wsPoint, 1.0f);
    return clip.z / clip.w;
}

// The world point of pixel (x, y) on the ground plane y = 0, if its ray reaches it.
std::optional<glm::vec3> groundPoint(const CameraView& view, uint32_t x, uint32_t y) {
    const glm::vec3 wsDirection = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
    if (wsDirection.y > -1e-3f) return std::nullopt;
    return view.wsPosition + wsDirection * (-view.wsPosition.y / wsDirection.y);
}

// The view's depth of the ground plane y = 0 in rows [firstRow, lastRow) (0 elsewhere and above the horizon).
Image groundDepth(const CameraView& view, uint32_t firstRow = 0, uint32_t lastRow = ~0u) {
    Image depth(view.width, view.height, 4);
    for (uint32_t y = firstRow; y < std::min(lastRow, view.height); ++y)
        for (uint32_t x = 0; x < view.width; ++x)
            if (const std::optional<glm::vec3> wsPoint = groundPoint(view, x, y)) setDepth(depth, x, y, depthOf(view, *wsPoint));
    return depth;
}

// The requested pages of one level as global page coordinates of its window.
std::vector<glm::ivec2> requestedPages(const VirtualPageRequests& requests, const ClipmapLevel& level) {
    std::vector<glm::ivec2> pages;
    for (int32_t y = level.window.min.y; y <= level.window.max.y; ++y)
        for (int32_t x = level.window.min.x; x <= level.window.max.x; ++x)
            if (requests.requested(level.level, pageTableSlot(level, {x, y}))) pages.push_back({x, y});
    return pages;
}

std::vector<uint32_t> requestedLevels(const VirtualPageRequests& requests) {
    std::vector<uint32_t> levels;
    for (uint32_t level = 0; level < requests.levelCount; ++level)
        if (requests.levelPageCounts[level] > 0) levels.push_back(level);
    return levels;
}

TEST(VirtualPageMarking, APixelsFootprintIsItsSideAtThatViewDepth) {
    const CameraView view = groundCamera();
    const float vsDepth = 7.0f;
    // Two horizontally adjacent pixel centres on the plane vsDepth in front of the camera.
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld);
    const float d = depthOf(view, view.wsPosition + view.wsForward * vsDepth);
    const glm::vec3 a = wsPositionFromDepth(worldFromClip, view, 100.5f, 96.5f, d);
    const glm::vec3 b = wsPositionFromDepth(worldFromClip, view, 101.5f, 96.5f, d);
    EXPECT_NEAR(wsPixelFootprint(view, vsDepth), glm::distance(a, b), 1e-5f);
    EXPECT_FLOAT_EQ(wsPixelFootprint(view, vsDepth), 2.0f * vsDepth * std::tan(0.5f * view.yfov) / 192.0f);
}

TEST(VirtualPageMarking, ASinglePixelMarksThePagesItsFilterReadsInTheLevelOfItsFootprint) {
    const VirtualClipmapConfig config = testConfig();
    const CameraView view = groundCamera();
    Image depth(view.width, view.height, 4);
    const uint32_t x = 128, y = 150;
    const glm::vec3 wsPoint = *groundPoint(view, x, y);
    setDepth(depth, x, y, depthOf(view, wsPoint));
    const float marginTexels = 3.0f;
    const VirtualPageRequests requests = markVirtualPages(config, overheadSun(), view, depth, marginTexels);

    const glm::vec2 lsCamera = lsClipmapCentre(overheadSun(), view);
    const glm::vec2 lsPoint(overheadSun() * glm::vec4(wsPoint, 1.0f));
    const float vsDepth = -(view.viewFromWorld * glm::vec4(wsPoint, 1.0f)).z;
    const uint32_t level = levelForFootprint(config, wsPixelFootprint(view, vsDepth));
    const ClipmapLevel placed = placeClipmapLevel(config, level, lsCamera);
    const PageRect expected = receiverPages(placed, lsPoint, marginTexels);
    ASSERT_TRUE(placed.window.contains(expected));
    // And the same reach kVirtualPageFallbackLevels coarser: what serves it if its own pages overflow.
    const uint32_t fallback = level + gpu_data::kVirtualPageFallbackLevels;
    ASSERT_LT(fallback, config.levelCount);
    const PageRect coarse = receiverPages(placeClipmapLevel(config, fallback, lsCamera), lsPoint, marginTexels);
    EXPECT_EQ(requests.pageCount(), expected.pageCount() + coarse.pageCount());
    EXPECT_EQ(requests.levelPageCounts[level], expected.pageCount());
    EXPECT_EQ(requests.levelPageCounts[fallback], coarse.pageCount());
    for (const glm::ivec2& page : requestedPages(requests, placed)) {
        EXPECT_GE(page.x, expected.min.x);
        EXPECT_LE(page.x, expected.max.x);
        EXPECT_GE(page.y, expected.min.y);
        EXPECT_LE(page.y, expected.max.y);
    }
}

TEST(VirtualPageMarking, APixelWithoutGeometryMarksNothing) {
    const CameraView view = groundCamera();
    const Image nothing(view.width, view.height, 4);  // depth 0 everywhere: the cleared far plane
    const VirtualPageRequests requests = markVirtualPages(testConfig(), overheadSun(), view, nothing, 2.0f);
    EXPECT_EQ(requests.pageCount(), 0u);
    for (uint32_t count : requests.levelPageCounts) EXPECT_EQ(count, 0u);
}

TEST(VirtualPageMarking, AGroundPlaneMarksLevelZeroOnlyNearTheCamera) {
    const VirtualClipmapConfig config = testConfig();
    const CameraView view = groundCamera();
    const VirtualPageRequests requests = markVirtualPages(config, overheadSun(), view, groundDepth(view), 1.0f);
    const glm::vec2 lsCamera = lsClipmapCentre(overheadSun(), view);
    const ClipmapLevel level0 = placeClipmapLevel(config, 0, lsCamera);
    ASSERT_GT(requests.levelPageCounts[0], 0u);
    // Level 0 serves footprints below level 1's texel: receivers closer than this view depth, so
    // within it (plus a page and the margin) of the camera's light-space position.
    const float vsFarthestLevel0 = 2.0f * level0.lsTexelSize / wsFootprintPerDepth(view);
    const float lsReach = vsFarthestLevel0 + level0.lsPageSize * std::sqrt(2.0f) + level0.lsTexelSize;
    for (const glm::ivec2& page : requestedPages(requests, level0)) {
        const glm::vec2 lsPageCentre = (glm::vec2(page) + 0.5f) * level0.lsPageSize;
        EXPECT_LE(glm::distance(lsPageCentre, lsCamera), lsReach) << page.x << ", " << page.y;
    }
}

TEST(VirtualPageMarking, FartherGroundMarksCoarserLevels) {
    const VirtualClipmapConfig config = testConfig();
    const CameraView view = groundCamera();
    // The bottom rows see the ground 1.4 m ahead, the top rows (5 to 7 degrees below the horizon) 12 to 17 m.
    const VirtualPageRequests nearRows = markVirtualPages(config, overheadSun(), view, groundDepth(view, 176), 1.0f);
    const VirtualPageRequests farRows = markVirtualPages(config, overheadSun(), view, groundDepth(view, 0, 16), 1.0f);
    const std::vector<uint32_t> nearLevels = requestedLevels(nearRows), farLevels = requestedLevels(farRows);
    ASSERT_FALSE(nearLevels.empty());
    ASSERT_FALSE(farLevels.empty());
    EXPECT_EQ(nearLevels.front(), 0u);
    // Each side marks its footprints' levels and the same kVirtualPageFallbackLevels coarser.
    EXPECT_LT(nearLevels.front(), farLevels.front()) << "the near ground's finest level is finer than the far ground's";
    EXPECT_LT(nearLevels.back(), farLevels.back()) << "and so is its coarsest";
}

TEST(VirtualPageMarking, ReceiversBeyondTheLastLevelMarkNothing) {
    VirtualClipmapConfig config = testConfig();
    config.levelCount = 2;  // windows of 16 m at most, reaching 7 to 8 m from the camera
    const CameraView view = groundCamera();
    const VirtualPageRequests all = markVirtualPages(config, overheadSun(), view, groundDepth(view), 1.0f);
    // The top rows see the ground 14 to 17 m ahead: outside every window.
    const VirtualPageRequests far = markVirtualPages(config, overheadSun(), view, groundDepth(view, 0, 4), 1.0f);
    EXPECT_GT(all.pageCount(), 0u);
    EXPECT_EQ(far.pageCount(), 0u);
}

TEST(VirtualPageMarking, ALargerMarginMarksASuperset) {
    const VirtualClipmapConfig config = testConfig();
    const CameraView view = groundCamera();
    const Image depth = groundDepth(view);
    const VirtualPageRequests narrow = markVirtualPages(config, overheadSun(), view, depth, 0.0f);
    const VirtualPageRequests wide = markVirtualPages(config, overheadSun(), view, depth, 24.0f);
    ASSERT_EQ(narrow.words.size(), wide.words.size());
    for (size_t i = 0; i < narrow.words.size(); ++i)
        EXPECT_EQ(narrow.words[i] & ~wide.words[i], 0u) << "word " << i << ": a page only the narrow margin marks";
    EXPECT_GT(wide.pageCount(), narrow.pageCount());
}

TEST(VirtualPageMarking, BitsAreLaidOutByLevelThenWrapAroundSlot) {
    const VirtualClipmapConfig config = testConfig();  // 16 pages a side
    // A camera far out at negative light-space x (world x > 0 with the overhead sun), so the pixel's
    // global page is negative and its slot wraps.
    const CameraView view = groundCamera(glm::vec2(1003.7f, -5.2f));
    Image depth(view.width, view.height, 4);
    const glm::vec3 wsPoint = *groundPoint(view, 128, 150);
    setDepth(depth, 128, 150, depthOf(view, wsPoint));
    const VirtualPageRequests requests = markVirtualPages(config, overheadSun(), view, depth, 0.0f);
    ASSERT_EQ(requests.pageCount(), 2u);  // its page and its fallback level's

    const float vsDepth = -(view.viewFromWorld * glm::vec4(wsPoint, 1.0f)).z;
    const uint32_t level = levelForFootprint(config, wsPixelFootprint(view, vsDepth));
    const ClipmapLevel placed = placeClipmapLevel(config, level, lsClipmapCentre(overheadSun(), view));
    const glm::ivec2 page = pageOf(placed, glm::vec2(overheadSun() * glm::vec4(wsPoint, 1.0f)));
    ASSERT_LT(page.x, 0);
    EXPECT_EQ(requests.levelPageCounts[level], 1u);
    const glm::uvec2 slot((page.x % 16 + 16) % 16, (page.y % 16 + 16) % 16);
    const uint32_t bit = (level * 16 + slot.y) * 16 + slot.x;
    EXPECT_EQ(requests.words[bit / 32], 1u << (bit % 32));
    EXPECT_EQ(gpu_data::virtualPageBit(level, 16, slot.x, slot.y), bit);
}

TEST(VirtualPageMarking, RequestsReadFromWordsCountThePagesOfEachLevel) {
    const VirtualClipmapConfig config = testConfig();
    const CameraView view = groundCamera();
    const VirtualPageRequests marked = markVirtualPages(config, overheadSun(), view, groundDepth(view), 2.0f);
    ASSERT_EQ(marked.words.size(), virtualPageRequestWords(config));
    const VirtualPageRequests read(config, marked.words);
    EXPECT_EQ(read.levelPageCounts, marked.levelPageCounts);
    EXPECT_EQ(read.pageCount(), marked.pageCount());
    EXPECT_GT(read.pageCount(), 0u);
}

}  // namespace
}  // namespace penumbra
