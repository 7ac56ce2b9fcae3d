// The depth reduction of the tight cascade fit (shadows/visible_surfaces.h) and the plan it drives.
#include <algorithm>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"
#include "shadows/visible_surfaces.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

TEST(VisibleSurfaces, ReconstructsTheVisiblePointsAndTheirDepthRange) {
    const CameraView view = cameraLookingAt({0, 3, 0}, {0, 0, -10}, 1000.0f, 64, 48);
    const VisibleSurfaces visible = visibleSurfacesFromDepth(groundDepth(view), view);
    ASSERT_GT(visible.wsPoints.size(), 64u * 10u);
    for (const glm::vec3& p : visible.wsPoints) EXPECT_NEAR(p.y, 0.0f, 2e-3f * glm::length(p - view.wsPosition));
    EXPECT_GT(visible.vsMinDepth, 2.0f);  // the nearest ground the 60° view shows
    EXPECT_LT(visible.vsMaxDepth, 60.0f);
    EXPECT_GT(visible.vsMaxDepth, 40.0f);
}

TEST(VisibleSurfaces, EmptyDepthGivesNoPoints) {
    const CameraView view = cameraLookingAt({0, 3, 0}, {0, 3, -10}, 1000.0f, 16, 16);
    EXPECT_TRUE(visibleSurfacesFromDepth(Image(16, 16, 4, 0), view).empty());
}

// The tight fit (SDSM depth reduction): every visible point of a cascade's slice lands inside its tile, the
// cascades are chosen by view depth, and the texels are smaller than the culling sphere's.
TEST(TightFit, EveryVisiblePointMapsInsideItsCascadesTileWithSmallerTexels) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -60}, {60, 0, 60});
    addBox(scene, {-1, 0, -8}, {1, 2, -6});
    addDirectionalLight(scene, {0.4f, -1.0f, 0.3f});
    const CameraView view = cameraLookingAt({0, 3, 0}, {0, 0, -10}, 1000.0f, 64, 48);
    const VisibleSurfaces visible = visibleSurfacesFromDepth(groundDepth(view), view);
    ShadowSettings settings;
    settings.directional.fit = CascadeFit::Tight;
    settings.directional.cascadeSplits = CascadeSplitMode::Log;
    const ShadowFrame tight = ShadowPlanner::plan(scene, view, settings, &visible);
    settings.directional.fit = CascadeFit::Sphere;
    const ShadowFrame sphere = ShadowPlanner::plan(scene, view, settings);
    ASSERT_TRUE(tight.directional.tight);
    EXPECT_EQ(tight.directional.gpu.cascadeFit, gpu_data::kCascadeFitTight);
    const float atlasSize = float(tight.directional.atlas.atlasSize);
    double tightTexels = 0.0, sphereTexels = 0.0;  // the texel size each visible point is shadowed with
    for (size_t i = 0; i < visible.wsPoints.size(); ++i) {
        const CascadeSelection inSphere = selectCascade(sphere.directional.gpu, visible.wsPoints[i], visible.vsDepths[i]);
        if (inSphere.cascadeIndex < 4) sphereTexels += sphere.directional.tiles[inSphere.cascadeIndex].wsTexelSize;
        const CascadeSelection selection = selectCascade(tight.directional.gpu, visible.wsPoints[i], visible.vsDepths[i]);
        ASSERT_LT(selection.cascadeIndex, 4u);
        const ShadowTile& tile = tight.directional.tiles[selection.cascadeIndex];
        tightTexels += tile.wsTexelSize;
        const glm::vec4 p = tile.atlasFromWorld * glm::vec4(visible.wsPoints[i], 1.0f);
        EXPECT_GE(p.x * atlasSize, float(tile.rect.offset.x) + 2.0f);
        EXPECT_LE(p.x * atlasSize, float(tile.rect.offset.x + tile.rect.size) - 2.0f);
        EXPECT_GE(p.y * atlasSize, float(tile.rect.offset.y) + 2.0f);
        EXPECT_LE(p.y * atlasSize, float(tile.rect.offset.y + tile.rect.size) - 2.0f);
        EXPECT_GT(p.z, 0.0f);
        EXPECT_LT(p.z, 1.0f);
    }
    for (uint32_t c = 0; c < 4; ++c)
        EXPECT_FLOAT_EQ(tight.directional.gpu.cascades[c].vsSplit, tight.directional.cascades[c].vsFar);
    std::printf("[tight fit] mean texel at the visible points: sphere %.4f m, tight %.4f m\n",
                sphereTexels / double(visible.wsPoints.size()), tightTexels / double(visible.wsPoints.size()));
    EXPECT_LT(tightTexels, 0.8 * sphereTexels);
    EXPECT_LE(tight.directional.cascades[3].vsFar, visible.vsMaxDepth * 1.002f);  // splits over the visible range
}

TEST(TightFit, WithoutVisibleSurfacesThePlanIsTheSphereFit) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -60}, {60, 0, 60});
    addDirectionalLight(scene, {0.4f, -1.0f, 0.3f});
    ShadowSettings settings;
    settings.directional.fit = CascadeFit::Tight;
    const ShadowFrame frame = ShadowPlanner::plan(scene, cameraLookingAt({0, 3, 0}, {0, 0, -10}), settings);
    EXPECT_FALSE(frame.directional.tight);
    EXPECT_EQ(frame.directional.gpu.cascadeFit, gpu_data::kCascadeFitSphere);
}

TEST(ShadowFade, SquaredFadeRunsFromTheBandsStartToTheShadowDistanceInSquaredDistance) {
    const glm::vec2 scaleBias = squaredFadeScaleBias(100.0f, 0.2f);  // band from 80 m to 100 m
    EXPECT_NEAR(80.0f * 80.0f * scaleBias.x + scaleBias.y, 0.0f, 1e-5f);
    EXPECT_NEAR(100.0f * 100.0f * scaleBias.x + scaleBias.y, 1.0f, 1e-5f);
    const float midSquared = 0.5f * (80.0f * 80.0f + 100.0f * 100.0f);
    EXPECT_NEAR(distanceFadeStrength(ShadowFadeMode::Squared, 100.0f, 0.2f, 1.0f, midSquared), 0.5f, 1e-5f);
    EXPECT_NEAR(distanceFadeStrength(ShadowFadeMode::Linear, 100.0f, 0.2f, 90.0f, 0.0f), 0.5f, 1e-5f);
}

// A camera looking nearly straight down at flat ground sees every point 8-13 m deep: the last tight
// cascade ends there, far short of the 100 m shadow distance. Its fade runs toward the shadow distance,
// where the sphere fit's last cascade would end, so the ground keeps its full shadow strength.
TEST(TightFit, AShallowViewKeepsFullShadowStrengthToItsBack) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -60}, {60, 0, 60});
    addDirectionalLight(scene, {0.4f, -1.0f, 0.3f});
    const CameraView view = cameraLookingAt({0, 10, 0}, {0, 0, -3}, 1000.0f, 64, 48);
    const VisibleSurfaces visible = visibleSurfacesFromDepth(groundDepth(view), view);
    ASSERT_FALSE(visible.empty());
    ASSERT_LT(visible.vsMaxDepth, 15.0f);
    ASSERT_GT(visible.vsMaxDepth - visible.vsMinDepth, 2.0f);
    ShadowSettings settings;  // tight fit, 100 m shadow distance, cascade fade 0.1
    const ShadowFrame frame = ShadowPlanner::plan(scene, view, settings, &visible);
    ASSERT_TRUE(frame.directional.tight);
    float weakest = 1.0f;
    uint32_t inLast = 0;
    for (size_t i = 0; i < visible.wsPoints.size(); ++i) {
        const CascadeSelection selection = selectCascade(frame.directional.gpu, visible.wsPoints[i], visible.vsDepths[i]);
        ASSERT_LT(selection.cascadeIndex, 4u);
        inLast += selection.cascadeIndex == 3u;
        weakest = std::min(weakest, selection.strength);
    }
    ASSERT_GT(inLast, 0u);
    EXPECT_FLOAT_EQ(weakest, 1.0f) << "the back of the view faded as if the shadow distance ended there";
}
