// The geometry of spot and point lights' virtual shadow maps (src/shadows/virtual_faces.h): the mip
// chain and its page table, the faces' projections and margins, the mip a receiver's footprint picks,
// the pages a filter reads, and the page marking's CPU reference on synthetic depth images.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "shadows/spot_projection.h"
#include "shadows/virtual_faces.h"
#include "shadows/visible_surfaces.h"
#include "virtual_page_structs.h"

namespace penumbra {
namespace {

// 8 pages of 16 texels a side at mip 0: mips of 8, 4, 2 and 1 pages.
constexpr VirtualFaceConfig kConfig{.resolution = 128, .pageSize = 16};

// A spot light 4 m above the origin looking straight down, 30 degree half-angle.
VirtualFace downwardSpot(float marginTexels = 0.0f) {
    return makeVirtualFace(kConfig, glm::vec3(0.0f, 4.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f),
                           std::tan(glm::radians(30.0f)), 0.1f, 20.0f, marginTexels);
}

TEST(VirtualFaces, TheMipChainEndsAtOnePageAndItsTableHoldsEveryFaceOfEveryMip) {
    EXPECT_EQ(virtualFacePagesPerSide(kConfig), 8u);
    EXPECT_EQ(virtualFaceMipCount(kConfig), 4u);
    EXPECT_EQ(virtualFaceMipCount({.resolution = 16384, .pageSize = 128}), 8u);
    const VirtualPageTableLayout layout = virtualFaceTableLayout(kConfig, 7);
    EXPECT_EQ(layout.pagesPerSide, 8u);
    EXPECT_EQ(layout.levelCount, 28u);
    EXPECT_EQ(layout.levelsPerBucket, 7u);
    EXPECT_EQ(layout.bucketCount(), 4u) << "one bucket per mip";
    EXPECT_TRUE(layout.fixedWindows);
    EXPECT_EQ(virtualFaceLevel(2, 3, 7), 17u);
}

TEST(VirtualFaces, AFaceMapsItsAxisToTheCentreAndItsConeInsideTheFilterMargin) {
    const VirtualFace face = downwardSpot(2.0f);
    const auto centre = projectOntoFace(face, glm::vec3(0.0f, 0.0f, 0.0f));
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->ndc.x, 0.0f, 1e-6f);
    EXPECT_NEAR(centre->ndc.y, 0.0f, 1e-6f);
    EXPECT_NEAR(centre->lightDistance, 4.0f, 1e-5f);
    // The cone's edge lands 2 texels of the one-page mip (16 texels) inside the face's edge.
    const float edge = 4.0f * std::tan(glm::radians(30.0f));
    const auto onCone = projectOntoFace(face, glm::vec3(edge, 0.0f, 0.0f));
    ASSERT_TRUE(onCone);
    EXPECT_NEAR(std::abs(onCone->ndc.x), 1.0f - 2.0f * 2.0f / 16.0f, 1e-5f);
}

TEST(VirtualFaces, DepthRunsFromTheNearPlaneToTheFarPlaneAndNothingBehindProjects) {
    const VirtualFace face = downwardSpot();
    EXPECT_NEAR(projectOntoFace(face, glm::vec3(0.0f, 3.9f, 0.0f))->depth, 0.0f, 1e-5f);
    EXPECT_NEAR(projectOntoFace(face, glm::vec3(0.0f, -15.99f, 0.0f))->depth, 1.0f, 1e-4f);
    EXPECT_FALSE(projectOntoFace(face, glm::vec3(0.0f, 5.0f, 0.0f))) << "behind the light";
    EXPECT_FALSE(projectOntoFace(face, glm::vec3(10.0f, 0.0f, 0.0f))) << "outside the frustum";
}

TEST(VirtualFaces, AFootprintPicksTheFinestMipWhoseTexelsAreNoSmaller) {
    const VirtualFace face = downwardSpot();
    // At 4 m, mip 0's texel (2 / 128 NDC) is 4 * tanHalfFov / 64 metres wide.
    const float texel0 = 4.0f * face.tanHalfFov / 64.0f;
    EXPECT_EQ(faceMipForFootprint(kConfig, face.tanHalfFov, 4.0f, 0.5f * texel0), 0u);
    EXPECT_EQ(faceMipForFootprint(kConfig, face.tanHalfFov, 4.0f, 1.5f * texel0), 0u);
    EXPECT_EQ(faceMipForFootprint(kConfig, face.tanHalfFov, 4.0f, 2.5f * texel0), 1u);
    EXPECT_EQ(faceMipForFootprint(kConfig, face.tanHalfFov, 8.0f, 2.5f * texel0), 0u) << "twice as far: texels twice as wide";
    EXPECT_EQ(faceMipForFootprint(kConfig, face.tanHalfFov, 4.0f, 1000.0f * texel0), 3u) << "clamped to the last mip";
}

TEST(VirtualFaces, AFilterReadsThePagesItsReachCrossesWithinTheMip) {
    // NDC 0.1 is texel 70.4 of mip 0's 128: one texel either way stays in page 4 (texels 64 to 80).
    EXPECT_EQ(facePages(kConfig, 0, glm::vec2(0.1f), 1.0f).min, glm::ivec2(4));
    EXPECT_EQ(facePages(kConfig, 0, glm::vec2(0.1f), 1.0f).max, glm::ivec2(4));
    // Page 4 starts at NDC 0: a reach of one texel from just past it crosses into page 3.
    const PageRect crossing = facePages(kConfig, 0, glm::vec2(0.001f, 0.55f), 1.0f);
    EXPECT_EQ(crossing.min, glm::ivec2(3, 6));
    EXPECT_EQ(crossing.max, glm::ivec2(4, 6));
    const PageRect corner = facePages(kConfig, 1, glm::vec2(-0.999f, 0.999f), 3.0f);
    EXPECT_EQ(corner.min, glm::ivec2(0, 3)) << "clamped to mip 1's 4 pages";
    EXPECT_EQ(corner.max, glm::ivec2(0, 3));
}

TEST(VirtualFaces, APageProjectionMapsThePageSquareOfItsMipOntoTheWholeClipSquare) {
    const VirtualFace face = downwardSpot();
    // A ground point at NDC (0.3, -0.6) of the face lies in page (2, 0) of mip 1 (4 pages: NDC [0, 0.5] x
    // [-1, -0.5]), at 60 % and 80 % of that page's square.
    const glm::vec4 onFace(0.3f, -0.6f, 0.5f, 1.0f);
    const glm::vec4 world = glm::inverse(face.clipFromWorld) * onFace;
    const glm::vec4 clip = virtualFacePageClipFromWorld(face, 8, 1, {2, 0}) * world;
    EXPECT_NEAR(clip.x / clip.w, 0.2f, 1e-4f);
    EXPECT_NEAR(clip.y / clip.w, 0.6f, 1e-4f);
    EXPECT_NEAR(clip.z / clip.w, 0.5f, 1e-4f) << "depth as the face's";
    EXPECT_EQ(facePages(kConfig, 1, glm::vec2(0.3f, -0.6f), 0.0f).min, glm::ivec2(2, 0));
}

TEST(VirtualFaces, AMovedCasterInvalidatesThePagesItsBoundsCoverInEveryMip) {
    const VirtualFace face = downwardSpot();
    LevelPageRect rects[4];
    // A 1.2 m box on the ground right below the light: the middle of the face, a few pages of mip 0.
    const Aabb below{glm::vec3(-0.6f, 0.0f, -0.6f), glm::vec3(0.6f, 0.4f, 0.6f)};
    ASSERT_EQ(casterFacePageRects(kConfig, face, 2, 3, below, rects), 4u);
    for (uint32_t mip = 0; mip < 4; ++mip) {
        EXPECT_EQ(rects[mip].level, mip * 3 + 2);
        const int32_t centre = int32_t(4u >> mip);  // the page right of the face's centre line
        EXPECT_LE(rects[mip].pages.min.x, centre - (mip < 3 ? 1 : 0)) << mip;
        EXPECT_GE(rects[mip].pages.max.x, std::min(centre, int32_t(8u >> mip) - 1)) << mip;
    }
    EXPECT_LE(rects[0].pages.max.x - rects[0].pages.min.x, 3) << "a small box covers few pages of mip 0";
    // Every projected corner lies within the rectangle: the box's shadow cannot change depth elsewhere.
    for (uint32_t i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? below.max.x : below.min.x, (i & 2) ? below.max.y : below.min.y,
                               (i & 4) ? below.max.z : below.min.z);
        const auto p = projectOntoFace(face, corner);
        ASSERT_TRUE(p);
        const PageRect at = facePages(kConfig, 0, p->ndc, 0.0f);
        EXPECT_TRUE(rects[0].pages.contains(at));
    }
    // Far to the side: outside the cone's frustum, nothing to redraw.
    EXPECT_EQ(casterFacePageRects(kConfig, face, 2, 3, {glm::vec3(30.0f, 0.0f, 0.0f), glm::vec3(31.0f, 1.0f, 1.0f)}, rects), 0u);
    // Reaching above the light: its projection is unbounded, every page of every mip.
    ASSERT_EQ(casterFacePageRects(kConfig, face, 0, 1, {glm::vec3(-0.1f, 3.0f, -0.1f), glm::vec3(0.1f, 5.0f, 0.1f)}, rects), 4u);
    EXPECT_EQ(rects[0].pages.min, glm::ivec2(0));
    EXPECT_EQ(rects[0].pages.max, glm::ivec2(7));
}

// 2 m above the ground looking 40 degrees down along -z at 64 x 48.
CameraView groundCamera() {
    Camera camera;
    const glm::vec3 eye(0.0f, 2.0f, 3.0f);
    const glm::vec3 target = eye + glm::vec3(0.0f, -std::sin(glm::radians(40.0f)), -std::cos(glm::radians(40.0f)));
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.yfov = glm::radians(60.0f);
    camera.zNear = 0.05f;
    return makeCameraView(camera, 64, 48);
}

// The view's reversed-Z depth of the ground plane y = 0.
Image groundDepth(const CameraView& view) {
    Image depth(view.width, view.height, 4);
    for (uint32_t y = 0; y < view.height; ++y)
        for (uint32_t x = 0; x < view.width; ++x) {
            const glm::vec3 ray = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            if (ray.y > -1e-3f) continue;
            const glm::vec4 clip = view.clipFromWorld * glm::vec4(view.wsPosition + ray * (-view.wsPosition.y / ray.y), 1.0f);
            const float d = clip.z / clip.w;
            std::memcpy(&depth.pixels[(size_t(y) * depth.width + x) * 4], &d, sizeof(float));
        }
    return depth;
}

using Page = std::tuple<uint32_t, int32_t, int32_t>;  // level, page x, y

std::set<Page> requestedPages(const std::vector<uint32_t>& words, const VirtualPageTableLayout& layout) {
    std::set<Page> pages;
    const uint32_t perLevel = layout.pagesPerSide * layout.pagesPerSide;
    for (uint32_t bit = 0; bit < layout.entryCount(); ++bit)
        if ((words[bit / 32] >> (bit % 32)) & 1u)
            pages.insert({bit / perLevel, int32_t(bit % perLevel % layout.pagesPerSide), int32_t(bit % perLevel / layout.pagesPerSide)});
    return pages;
}

TEST(VirtualFaces, ASpotMarksThePagesOfItsLitGroundAndTheirFallbackMip) {
    const CameraView view = groundCamera();
    const VirtualFace faces[] = {downwardSpot()};
    const VirtualFaceLight lights[] = {{0, false}};
    const std::vector<uint32_t> words = markVirtualFacePages(kConfig, faces, lights, view, groundDepth(view), 1.0f, 1.0f);
    const std::set<Page> pages = requestedPages(words, virtualFaceTableLayout(kConfig, 1));
    ASSERT_FALSE(pages.empty());
    // The ground point below the light is seen (the camera looks at it), so the face's centre pages of
    // its mip and of the mip kVirtualPageFallbackLevels coarser are requested.
    std::set<uint32_t> mips;
    for (const auto& [level, x, y] : pages) mips.insert(level);
    EXPECT_TRUE(mips.contains(3u)) << "the last mip, every fine mip's fallback";
    EXPECT_GE(mips.size(), 2u);
    EXPECT_TRUE(pages.contains({3u, 0, 0}));
}

TEST(VirtualFaces, APointLightMarksOnlyTheFaceOfTheMajorAxisTowardEachReceiver) {
    const CameraView view = groundCamera();
    std::vector<VirtualFace> faces;
    for (const glm::vec3& direction : pointLightFaceDirections())
        faces.push_back(makeVirtualFace(kConfig, glm::vec3(0.0f, 0.5f, 0.0f), direction, 1.0f, 0.05f, 20.0f, 2.0f));
    const VirtualFaceLight lights[] = {{0, true}};
    const std::vector<uint32_t> words = markVirtualFacePages(kConfig, faces, lights, view, groundDepth(view), 1.0f, 1.0f);
    std::set<uint32_t> faceOf;
    for (const auto& [level, x, y] : requestedPages(words, virtualFaceTableLayout(kConfig, 6))) faceOf.insert(level % 6);
    // Ground within 0.5 m of the light's foot is seen through -Y (face 3); farther ground through the
    // side faces +X, -X, -Z, +Z; never +Y.
    EXPECT_TRUE(faceOf.contains(3u));
    EXPECT_TRUE(faceOf.contains(5u)) << "-Z: the ground ahead of the camera beyond the light";
    EXPECT_FALSE(faceOf.contains(2u)) << "+Y sees no ground";
}

TEST(VirtualFaces, NothingOutsideTheConeIsMarked) {
    const CameraView view = groundCamera();
    const VirtualFace narrow = makeVirtualFace(kConfig, glm::vec3(0.0f, 4.0f, -30.0f), glm::vec3(0.0f, -1.0f, 0.0f),
                                               std::tan(glm::radians(5.0f)), 0.1f, 20.0f, 0.0f);
    const VirtualFace faces[] = {narrow};  // lights a spot 30 m away, beyond the camera's view of the ground
    const VirtualFaceLight lights[] = {{0, false}};
    const std::vector<uint32_t> words = markVirtualFacePages(kConfig, faces, lights, view, groundDepth(view), 1.0f, 1.0f);
    EXPECT_TRUE(requestedPages(words, virtualFaceTableLayout(kConfig, 1)).empty());
}

}  // namespace
}  // namespace penumbra
