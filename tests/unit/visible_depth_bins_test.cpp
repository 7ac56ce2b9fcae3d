// The tight fit's binned visible surfaces (shadows/visible_surfaces.h VisibleDepthBins): the form the
// GPU's depth reduction reads back (visible_bounds.comp; binVisibleSurfaces is its CPU reference) and
// the bounds the planner asks of it.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/cascades.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"
#include "shadows/visible_surfaces.h"
#include "visible_bounds_structs.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

constexpr float kBinFar = 100.0f;  // where the test views' bins end (the default shadow distance)

bool holds(const Aabb& outer, const Aabb& inner, float tolerance = 1e-4f) {
    return glm::all(glm::lessThanEqual(outer.min, inner.min + tolerance)) &&
           glm::all(glm::greaterThanEqual(outer.max, inner.max - tolerance));
}

// 480 rows: most of the 1024 bins within the ground's depths hold points.
CameraView groundView() { return cameraLookingAt({0, 3, 0}, {0, 0, -10}, 1000.0f, 640, 480); }

glm::mat4 sunRotation() { return lightRotationFromWorld(glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f))); }

// The exact bounds of the points within [vsNear, vsFar] widened by `bins` bins on either side (the
// first and last bins reach to zero and to infinity).
Aabb exactBoundsWidened(const VisibleSurfaces& exact, const VisibleDepthBins& bins, const glm::mat4& rotation,
                        float vsNear, float vsFar, float widenBins) {
    const float step = std::exp(widenBins / bins.binsPerLogDepth);
    const bool lastBin = vsFar * step >= kBinFar;
    return rotatedVisibleBounds(exact, rotation, vsNear / step, lastBin ? std::numeric_limits<float>::max() : vsFar * step);
}

// The view depth of the visible point nearest `vsDepth` deep.
float depthOfRowNear(const VisibleSurfaces& exact, float vsDepth) {
    float nearest = exact.vsDepths.front();
    for (float d : exact.vsDepths)
        if (std::abs(d - vsDepth) < std::abs(nearest - vsDepth)) nearest = d;
    return nearest;
}

uint32_t keyOf(float value) {  // visible_bounds.comp's visibleBoundsKey
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

}  // namespace

// A slice's bounds from the bins hold every point of the slice, and no point beyond the bins next to
// the slice's ends (one for the rounding of a depth's bin, one more), in the light's space and in the
// world's (where the slice's nearest row of ground is its box's side toward the camera).
TEST(VisibleDepthBins, ASlicesBoundsHoldItsPointsAndNothingBeyondTheNeighbouringBins) {
    const CameraView view = groundView();
    const VisibleSurfaces exact = visibleSurfacesFromDepth(groundDepth(view), view);
    const std::vector<glm::mat4> spaces = {sunRotation(), glm::mat4(1.0f)};
    const VisibleSurfaces binned = binVisibleSurfaces(exact, spaces, view.zNear, kBinFar);
    ASSERT_TRUE(binned.wsPoints.empty());
    // Slices from round depths, and one from a row of pixels to another (its ends' bins hold points).
    const float vsRow6 = depthOfRowNear(exact, 6.0f), vsRow20 = depthOfRowNear(exact, 20.0f);
    const float slices[][2] = {{-1e9f, 5.0f}, {5.0f, 12.0f}, {12.0f, 30.0f}, {30.0f, 1000.0f}, {7.0f, 7.5f}, {vsRow6, vsRow20}};
    for (const glm::mat4& rotation : spaces)
        for (const auto& slice : slices) {
            const Aabb exactBox = rotatedVisibleBounds(exact, rotation, slice[0], slice[1]);
            const Aabb binnedBox = rotatedVisibleBounds(binned, rotation, slice[0], slice[1]);
            ASSERT_TRUE(exactBox.valid()) << slice[0];
            EXPECT_TRUE(holds(binnedBox, exactBox)) << "slice from " << slice[0] << " m";
            EXPECT_TRUE(holds(exactBoundsWidened(exact, binned.bins, rotation, slice[0], slice[1], 2.0f), binnedBox))
                << "slice from " << slice[0] << " m";
        }
    EXPECT_FALSE(rotatedVisibleBounds(binned, spaces[0], 200.0f, 300.0f).valid()) << "nothing that far";
}

TEST(VisibleDepthBins, KeepTheExactViewDepthRange) {
    const CameraView view = groundView();
    const VisibleSurfaces exact = visibleSurfacesFromDepth(groundDepth(view), view);
    const VisibleSurfaces binned = binVisibleSurfaces(exact, std::vector<glm::mat4>{sunRotation()}, view.zNear, kBinFar);
    EXPECT_FALSE(binned.empty());
    EXPECT_EQ(binned.vsMinDepth, exact.vsMinDepth);
    EXPECT_EQ(binned.vsMaxDepth, exact.vsMaxDepth);
    EXPECT_TRUE(binVisibleSurfaces(VisibleSurfaces{}, std::vector<glm::mat4>{}, view.zNear, kBinFar).empty());
}

// A light that turned since the bins were made (or one they were not made for) gets the bounds of the
// closest space's box, rotated: they hold every point, and the closest space keeps them tight.
TEST(VisibleDepthBins, ARotationOfNoSpaceGetsTheClosestSpacesBoxRotatedAround) {
    const CameraView view = groundView();
    const VisibleSurfaces exact = visibleSurfacesFromDepth(groundDepth(view), view);
    const glm::vec3 wsSun = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    const glm::vec3 wsTurned = glm::normalize(glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(0.5f), glm::vec3(0, 1, 0)) *
                                                        glm::vec4(wsSun, 0.0f)));
    const glm::mat4 turned = lightRotationFromWorld(wsTurned);
    const VisibleSurfaces binned =
        binVisibleSurfaces(exact, std::vector<glm::mat4>{sunRotation(), glm::mat4(1.0f)}, view.zNear, kBinFar);
    const Aabb exactBox = rotatedVisibleBounds(exact, turned, 5.0f, 30.0f);
    const Aabb binnedBox = rotatedVisibleBounds(binned, turned, 5.0f, 30.0f);
    EXPECT_TRUE(holds(binnedBox, exactBox));
    // Through the sun's space (0.5 degrees away) a little larger; through the world's (60 degrees) far more.
    const glm::vec3 growth = binnedBox.extent() - exactBox.extent();
    EXPECT_LT(glm::max(growth.x, growth.y), 0.05f * glm::max(exactBox.extent().x, exactBox.extent().y));
}

// The GPU's words: minima from 0xffffffff down, maxima from 0 up, keys ordered as their floats.
TEST(VisibleDepthBins, WordsDecodeToTheirBoundsAndViewDepthRange) {
    std::vector<uint32_t> words(gpu_data::kVisibleBoundsWords, 0u);
    std::fill(words.begin(), words.begin() + gpu_data::kVisibleBoundsMinWords, 0xffffffffu);
    uint32_t* maxima = words.data() + gpu_data::kVisibleBoundsMinWords;
    words[0] = keyOf(2.5f);
    maxima[0] = keyOf(40.0f);
    const uint32_t space = 1, bin = 300, first = 1 + (space * gpu_data::kVisibleDepthBins + bin) * 3;
    const float lo[3] = {-7.25f, -0.5f, 3.0f}, hi[3] = {-1.0f, 0.0f, 12.5f};
    for (int axis = 0; axis < 3; ++axis) {
        words[first + axis] = keyOf(lo[axis]);
        maxima[first + axis] = keyOf(hi[axis]);
    }
    const std::vector<glm::mat4> spaces = {sunRotation(), glm::mat4(1.0f)};
    VisibleSurfaces visible;
    visibleSurfacesFromBoundsWords(words.data(), 0.1f, visibleBinsPerLogDepth(0.1f, kBinFar), spaces, visible);
    EXPECT_EQ(visible.vsMinDepth, 2.5f);
    EXPECT_EQ(visible.vsMaxDepth, 40.0f);
    ASSERT_EQ(visible.bins.spaceCount, 2u);
    ASSERT_EQ(visible.bins.rsBounds.size(), 2u * VisibleDepthBins::kBins);
    const Aabb& decoded = visible.bins.rsBounds[space * VisibleDepthBins::kBins + bin];
    EXPECT_EQ(decoded.min, glm::vec3(lo[0], lo[1], lo[2]));
    EXPECT_EQ(decoded.max, glm::vec3(hi[0], hi[1], hi[2]));
    size_t filled = 0;
    for (const Aabb& box : visible.bins.rsBounds) filled += box.valid();
    EXPECT_EQ(filled, 1u);
    std::fill(words.begin(), words.begin() + gpu_data::kVisibleBoundsMinWords, 0xffffffffu);
    visibleSurfacesFromBoundsWords(words.data(), 0.1f, visibleBinsPerLogDepth(0.1f, kBinFar), spaces, visible);
    EXPECT_TRUE(visible.empty()) << "no surface: nothing lowered the minima";
}

// The tight fit planned from bins puts every visible point inside its cascade's tile, as from points.
TEST(VisibleDepthBins, TheTightFitPlannedFromBinsPutsEveryPointInsideItsCascadesTile) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -60}, {60, 0, 60});
    addBox(scene, {-1, 0, -8}, {1, 2, -6});
    addDirectionalLight(scene, {0.4f, -1.0f, 0.3f});
    const CameraView view = groundView();
    const VisibleSurfaces exact = visibleSurfacesFromDepth(groundDepth(view), view);
    const VisibleSurfaces binned =
        binVisibleSurfaces(exact, std::vector<glm::mat4>{sunRotation(), glm::mat4(1.0f)}, view.zNear, kBinFar);
    ShadowSettings settings;
    settings.directional.fit = CascadeFit::Tight;
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings, &binned);
    ASSERT_TRUE(plan.directional.tight);
    const ShadowFrame fromPoints = ShadowPlanner::plan(scene, view, settings, &exact);
    const float atlasSize = float(plan.directional.atlas.atlasSize);
    for (size_t i = 0; i < exact.wsPoints.size(); ++i) {
        const CascadeSelection selection = selectCascade(plan.directional.gpu, exact.wsPoints[i], exact.vsDepths[i]);
        ASSERT_LT(selection.cascadeIndex, 4u);
        const ShadowTile& tile = plan.directional.tiles[selection.cascadeIndex];
        const glm::vec4 p = tile.atlasFromWorld * glm::vec4(exact.wsPoints[i], 1.0f);
        ASSERT_GE(p.x * atlasSize, float(tile.rect.offset.x) + 2.0f);
        ASSERT_LE(p.x * atlasSize, float(tile.rect.offset.x + tile.rect.size) - 2.0f);
        ASSERT_GE(p.y * atlasSize, float(tile.rect.offset.y) + 2.0f);
        ASSERT_LE(p.y * atlasSize, float(tile.rect.offset.y + tile.rect.size) - 2.0f);
    }
    // The bins' few percent of extent cost at most one step of the tile's quantized size (2^(1/8)).
    for (uint32_t c = 0; c < 4; ++c) {
        EXPECT_EQ(plan.directional.cascades[c].vsFar, fromPoints.directional.cascades[c].vsFar);
        EXPECT_GE(plan.directional.tiles[c].wsTexelSize, fromPoints.directional.tiles[c].wsTexelSize * 0.999f);
        EXPECT_LE(plan.directional.tiles[c].wsTexelSize, fromPoints.directional.tiles[c].wsTexelSize * std::exp2(1.0f / 8.0f) * 1.001f) << c;
    }
}
