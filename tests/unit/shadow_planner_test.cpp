#include <cmath>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_gpu_packing.h"
#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

struct PlannerFixture {
    Scene scene = baseScene();
    CameraView camera = cameraLookingAt({0, 6, 15}, {0, 0, 0});
    ShadowSettings settings = sphereCascadeSettings();

    PlannerFixture() {
        settings.maxDistance = 40.0f;
        addBox(scene, {-20, -1, -20}, {20, 0, 20});  // ground
        addBox(scene, {-1, 0, -1}, {1, 3, 1});       // pillar
    }
    ShadowFrame plan() const { return ShadowPlanner::plan(scene, camera, settings); }
};

glm::vec4 atlasPoint(const ShadowTile& tile, glm::vec3 wsPoint) { return tile.atlasFromWorld * glm::vec4(wsPoint, 1.0f); }

}  // namespace

TEST(ShadowPlanner, NoLightsGiveNoTilesAndZeroLightCount) {
    PlannerFixture f;
    const ShadowFrame frame = f.plan();
    EXPECT_TRUE(frame.directional.tiles.empty());
    EXPECT_EQ(frame.directional.gpu.lightCount, 0u);
    EXPECT_EQ(frame.stats.casterDraws, 0u);
}

TEST(ShadowPlanner, TwoLightsWithFourCascadesFillAFourByFourAtlas) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    addDirectionalLight(f.scene, {-0.5f, -1, 0.1f});
    const ShadowFrame frame = f.plan();
    ASSERT_EQ(frame.directional.tiles.size(), 8u);
    EXPECT_EQ(frame.directional.atlas.split, 4u);
    EXPECT_EQ(frame.directional.atlas.tileSize, 256u);
    EXPECT_EQ(frame.directional.tiles[5].lightSlot, 1u);
    EXPECT_EQ(frame.directional.tiles[5].cascadeIndex, 1u);
    EXPECT_EQ(frame.directional.tiles[5].rect.offset, glm::uvec2(256, 256));
    EXPECT_EQ(frame.directional.slotOfSceneLight, (std::vector<int32_t>{0, 1}));
    EXPECT_EQ(frame.stats.castersPerTile.size(), 8u);
}

namespace {
bool rendersInstance(const ShadowTile& tile, uint32_t instance) {
    return std::find(tile.casterInstances.begin(), tile.casterInstances.end(), instance) != tile.casterInstances.end();
}
}  // namespace

TEST(ShadowPlanner, CascadesReachingThePillarRenderItUntilBlendCullingDropsIt) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    const ShadowFrame frame = f.plan();
    // The pillar is 16 units from the camera: inside sphere 1 (view depth 4..10, radius 8.2 around
    // depth 10) and sphere 2 (radius 16.3 around depth 20), and wholly inside 0.7 x sphere 2, so the
    // culling factor (Catlike Coding "Directional Shadows", Culling Bias) drops it from cascade 3.
    EXPECT_TRUE(rendersInstance(frame.directional.tiles[1], 1u));
    EXPECT_TRUE(rendersInstance(frame.directional.tiles[2], 1u));
    EXPECT_FALSE(rendersInstance(frame.directional.tiles[3], 1u));
    EXPECT_GE(frame.stats.skippedByBlendCulling, 1u);

    f.settings.directional.cascadeFade = 0.9f;  // culling factor 0: nothing is dropped
    EXPECT_TRUE(rendersInstance(f.plan().directional.tiles[3], 1u));
}

TEST(ShadowPlanner, CasterIsCloserToTheLightThanTheGroundItShadows) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0, -1, 0});
    const ShadowFrame frame = f.plan();
    const ShadowTile& tile = frame.directional.tiles[1];  // cascade 1 covers the pillar
    const glm::vec4 top = atlasPoint(tile, {0, 3, 0});
    const glm::vec4 ground = atlasPoint(tile, {0, 0, 0});
    EXPECT_NEAR(top.x, ground.x, 1e-5f);  // same texel: the light looks straight down
    EXPECT_NEAR(top.y, ground.y, 1e-5f);
    EXPECT_LT(top.z, ground.z);  // standard depth: smaller is closer to the light
    EXPECT_GE(top.z, 0.0f);
    EXPECT_LE(ground.z, 1.0f);
}

// The depth range fits the receivers, the sphere's depth span, whatever the casters;
// casters toward the light are pancaked onto the near plane by depth clamp, and shadowNearPlane pulls
// the near plane back by its length.
TEST(ShadowPlanner, DirectionalDepthRangeFitsTheReceiversNotTheCasters) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    addBox(f.scene, {-1, 500, -1}, {1, 502, 1});  // far toward the light
    const ShadowFrame frame = f.plan();
    for (const ShadowTile& tile : frame.directional.tiles) {
        const CascadeSphere& sphere = frame.directional.cascades[tile.cascadeIndex];
        const float depthRange = tile.nearDistance + tile.farDistance;
        EXPECT_GE(depthRange, 2.0f * sphere.radius) << "tile " << tile.cascadeIndex;
        EXPECT_LE(depthRange, 2.0f * sphere.radius + 8.0f * tile.wsTexelSize) << "tile " << tile.cascadeIndex;
    }
}

TEST(ShadowPlanner, CastersInFrontOfTheNearPlaneArePancakedOntoIt) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    const glm::vec3 above = f.plan().directional.cascades[0].wsCenter - 400.0f * f.scene.lights[0].wsDirection;
    const uint32_t high = addBox(f.scene, above - 1.0f, above + 1.0f);  // on the light's ray through cascade 0
    const ShadowFrame frame = f.plan();
    const ShadowTile& tile = frame.directional.tiles[0];
    ASSERT_TRUE(rendersInstance(tile, high));
    const Aabb clip = f.scene.instances[high].wsBounds.transformed(tile.clipFromWorld);
    EXPECT_LT(clip.max.z, 0.0f) << "the box lies in front of the near plane";
    EXPECT_TRUE(tile.depthClamp) << "so it must be drawn with depth clamp";
    EXPECT_GT(tile.pancakedDepth, 390.0f);  // what the depth range no longer spans
}

TEST(ShadowPlanner, ShadowNearPlanePullsTheNearPlaneBackByItsLength) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    const ShadowFrame without = f.plan();
    f.scene.lights[0].shadowNearPlane = 5.0f;
    const ShadowFrame with = f.plan();
    for (size_t i = 0; i < with.directional.tiles.size(); ++i) {
        EXPECT_NEAR(with.directional.tiles[i].nearDistance, without.directional.tiles[i].nearDistance + 5.0f, 1e-4f);
        EXPECT_EQ(with.directional.tiles[i].farDistance, without.directional.tiles[i].farDistance);
    }
}

TEST(ShadowPlanner, PointsInACullingSphereMapInsideTheirTile) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0.3f, -1, 0.2f});
    addDirectionalLight(f.scene, {-0.6f, -1, -0.4f});
    const ShadowFrame frame = f.plan();
    const float atlasSize = float(frame.directional.atlas.atlasSize);
    for (const ShadowTile& tile : frame.directional.tiles) {
        const CascadeSphere& sphere = frame.directional.cascades[tile.cascadeIndex];
        for (glm::vec3 dir : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -1, 1))}) {
            const glm::vec4 p = atlasPoint(tile, sphere.wsCenter + dir * (sphere.radius - 2.0f * tile.wsTexelSize));
            EXPECT_GE(p.x * atlasSize, float(tile.rect.offset.x));
            EXPECT_LE(p.x * atlasSize, float(tile.rect.offset.x + tile.rect.size));
            EXPECT_GE(p.y * atlasSize, float(tile.rect.offset.y));
            EXPECT_LE(p.y * atlasSize, float(tile.rect.offset.y + tile.rect.size));
            EXPECT_GT(p.z, 0.0f);
            EXPECT_LT(p.z, 1.0f);
        }
    }
}

// The caster pass writes exact depth: the light's slope-scale bias goes to the lit pass (with its normal
// bias and filter), so a second rasterizer has only depth and depth clamp to reproduce.
TEST(ShadowPlanner, TilesWriteExactDepthAndTheLitPassGetsTheLightsBiases) {
    PlannerFixture f;
    addDirectionalLight(f.scene, {0, -1, 0});
    f.scene.lights[0].shadowBias = 0.8f;
    f.scene.lights[0].shadowNormalBias = 1.5f;
    f.settings.directional.filter = ShadowFilter::PCF5x5;
    const ShadowFrame frame = f.plan();
    EXPECT_EQ(frame.directional.tiles[2].slopeScaleBias, 0.0f);
    EXPECT_TRUE(frame.directional.tiles[2].depthClamp);
    const gpu_data::DirectionalShadowLight& light = frame.directional.gpu.lights[0];
    EXPECT_EQ(light.normalBias, 1.5f);
    EXPECT_EQ(light.slopeBias, 0.8f);
    EXPECT_EQ(light.filterMode, gpu_data::kShadowFilterPcf5x5);
    EXPECT_EQ(light.pcssTanRadius, 0.0f);
    EXPECT_EQ(light.wsToLight, glm::vec4(0, 1, 0, 0));
}

// URP's per-light soft flag for directional lights too: "hard" = one hardware
// 2x2 PCF tap, "soft" = directional.filter.
TEST(ShadowPackedData, HardDirectionalLightsUseOneHardwarePcfTap) {
    PlannerFixture f;
    f.settings.directional.filter = ShadowFilter::PCF7x7;
    addDirectionalLight(f.scene, {0.3f, -1, 0}, 1.0f, LightShadows::Hard);
    addDirectionalLight(f.scene, {-0.3f, -1, 0}, 1.0f, LightShadows::Soft);
    const gpu_data::DirectionalShadowData gpu = f.plan().directional.gpu;
    EXPECT_EQ(gpu.lights[0].filterMode, gpu_data::kShadowFilterPcf2x2);
    EXPECT_EQ(gpu.lights[1].filterMode, gpu_data::kShadowFilterPcf7x7);
}

TEST(ShadowPackedData, CascadeSpheresShrinkByTheFilterSizeAndBiasByHalfOfIt) {
    PlannerFixture f;
    f.settings.directional.filter = ShadowFilter::PCF5x5;
    addDirectionalLight(f.scene, {0, -1, 0});
    const ShadowFrame frame = f.plan();
    const gpu_data::DirectionalShadowData& gpu = frame.directional.gpu;
    for (uint32_t i = 0; i < 4; ++i) {
        const CascadeSphere& sphere = frame.directional.cascades[i];
        const float texel = 2.0f * sphere.radius / 512.0f;  // 1024 atlas, 4 tiles -> 512
        const float filterWorld = texel * 3.0f;             // PCF5x5: filter + 1 = 3 (SetCascadeData)
        const float shrunk = sphere.radius - filterWorld;
        EXPECT_NEAR(gpu.cascades[i].cullingSphere.w, shrunk * shrunk, 1e-3f);
        EXPECT_NEAR(gpu.cascades[i].cullingSphere.x, sphere.wsCenter.x, 1e-5f);
        EXPECT_NEAR(gpu.cascades[i].invRadiusSquared, 1.0f / (shrunk * shrunk), 1e-6f);
        // The normal-bias unit: PCF5x5 -> 1 + 2 / 2 = 2 texel diagonals, not the tutorial's 3.
        EXPECT_NEAR(gpu.cascades[i].normalBiasUnit, texel * 2.0f * std::sqrt(2.0f), 1e-5f);
        EXPECT_NEAR(gpu.cascades[i].wsTexelSize, frame.directional.tiles[i].wsTexelSize, 1e-6f);
    }
}

TEST(ShadowPackedData, NormalBiasUnitGrowsByHalfATexelDiagonalPerFilterStep) {
    const float diagonal = std::sqrt(2.0f);
    EXPECT_FLOAT_EQ(gpu_data::normalOffsetFootprint(gpu_data::kShadowFilterPcf2x2), 1.0f * diagonal);
    EXPECT_FLOAT_EQ(gpu_data::normalOffsetFootprint(gpu_data::kShadowFilterPcf3x3), 1.5f * diagonal);
    EXPECT_FLOAT_EQ(gpu_data::normalOffsetFootprint(gpu_data::kShadowFilterPcf5x5), 2.0f * diagonal);
    EXPECT_FLOAT_EQ(gpu_data::normalOffsetFootprint(gpu_data::kShadowFilterPcf7x7), 2.5f * diagonal);
}

TEST(ShadowPackedData, HoldsLightsConfigAtlasAndMatrices) {
    PlannerFixture f;
    f.settings.directional.cascadeCount = 2;
    f.settings.directional.cascadeBlend = CascadeBlend::Soft;
    addDirectionalLight(f.scene, {0, -1, 0}, 0.0f);  // skipped: strength 0
    addDirectionalLight(f.scene, {0.2f, -1, 0}, 0.6f);
    f.scene.lights[1].shadowNormalBias = 0.3f;
    const ShadowFrame frame = f.plan();
    const gpu_data::DirectionalShadowData& gpu = frame.directional.gpu;
    EXPECT_EQ(glm::uvec4(gpu.cascadeCount, gpu.filterMode, gpu.cascadeBlend, gpu.lightCount),
              glm::uvec4(2, gpu_data::kShadowFilterPcf2x2, gpu_data::kCascadeBlendSoft, 1));
    EXPECT_EQ(gpu.lights[0].strength, 0.6f);
    EXPECT_EQ(gpu.lights[0].firstTile, 0u);
    EXPECT_EQ(gpu.lights[0].normalBias, 0.3f);
    EXPECT_EQ(gpu.lights[0].sceneLightIndex, 1u);
    EXPECT_EQ(gpu.lights[1].strength, 0.0f) << "an unused slot is zero";
    EXPECT_EQ(gpu.lights[1].wsToLight, glm::vec4(0.0f));
    EXPECT_EQ(glm::vec4(gpu.atlasSize, gpu.invAtlasSize, gpu.tileSize, gpu.invTileSize),
              glm::vec4(1024.0f, 1.0f / 1024.0f, 512.0f, 1.0f / 512.0f));
    EXPECT_EQ(gpu.atlasFromWorld[1], frame.directional.tiles[1].atlasFromWorld);
    EXPECT_EQ(gpu.atlasFromWorld[2], glm::mat4(0.0f));
}

TEST(ShadowPackedData, FadeHoldsReciprocalsOfDistanceAndFades) {
    PlannerFixture f;
    f.settings.distanceFade = 0.2f;
    f.settings.directional.cascadeFade = 0.1f;
    const gpu_data::DirectionalShadowData gpu = f.plan().directional.gpu;
    EXPECT_FLOAT_EQ(gpu.invShadowDistance, 1.0f / 40.0f);
    EXPECT_FLOAT_EQ(gpu.invDistanceFade, 5.0f);
    EXPECT_FLOAT_EQ(gpu.cascadeFadeScale, 1.0f / (1.0f - 0.81f));
    EXPECT_FLOAT_EQ(gpu.shadowDistance, 40.0f);
}

TEST(ShadowFade, DistanceFadeIsOneBeforeTheBandLinearInItAndZeroAtMaxDistance) {
    PlannerFixture f;  // maxDistance 40, distanceFade 0.1: the band is 36..40
    const gpu_data::DirectionalShadowData gpu = f.plan().directional.gpu;
    EXPECT_FLOAT_EQ(fadedShadowStrength(30.0f, gpu.invShadowDistance, gpu.invDistanceFade), 1.0f);
    EXPECT_NEAR(fadedShadowStrength(38.0f, gpu.invShadowDistance, gpu.invDistanceFade), 0.5f, 1e-5f);
    EXPECT_FLOAT_EQ(fadedShadowStrength(40.0f, gpu.invShadowDistance, gpu.invDistanceFade), 0.0f);
}

TEST(ShadowFade, CascadeSelectionPicksTheFirstContainingSphereAndFadesTheLast) {
    PlannerFixture f;
    f.settings.directional.cascadeFade = 0.2f;
    addDirectionalLight(f.scene, {0, -1, 0});
    const ShadowFrame frame = f.plan();
    const gpu_data::DirectionalShadowData& gpu = frame.directional.gpu;
    const glm::vec3 eye = f.camera.wsPosition, forward = f.camera.wsForward;
    EXPECT_EQ(selectCascade(gpu, eye + forward * 2.0f, 2.0f).cascadeIndex, 0u);
    EXPECT_EQ(selectCascade(gpu, eye + forward * 19.5f, 19.5f).cascadeIndex, 2u);  // sphere 1 ends near 18
    const CascadeSelection outside = selectCascade(gpu, eye + forward * 200.0f, 200.0f);
    EXPECT_EQ(outside.cascadeIndex, 4u);
    EXPECT_EQ(outside.strength, 0.0f);
    // On the last sphere at distance^2 = (1 - f') r'^2 with f' = 1 - (1 - 0.2)^2 the cascade fade is 1,
    // halfway into the band it is 0.5 ("Fading Cascades").
    const glm::vec4 last = gpu.cascades[3].cullingSphere;
    const float band = 1.0f - 0.8f * 0.8f;
    const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 inBand = glm::vec3(last) + side * std::sqrt((1.0f - 0.5f * band) * last.w);
    const CascadeSelection faded = selectCascade(gpu, inBand, 1.0f);
    ASSERT_EQ(faded.cascadeIndex, 3u);
    EXPECT_NEAR(faded.strength, 0.5f, 1e-3f);
}

// Cascade blend culling keeps long shadows: a 1 m post 4 m in front of the camera under an 8° sun from the
// side lies inside 0.7 x cascade 0's sphere, but its 7 m shadow reaches ground that samples cascade 1:
// cascade 1 must draw it.
TEST(ShadowPlanner, CasterWhoseShadowLeavesTheSmallerCascadeIsDrawnInTheBiggerOne) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -100}, {60, 0, 10});  // ground
    const uint32_t post = addBox(scene, {-0.05f, 0, -4.05f}, {0.05f, 1, -3.95f});
    const float elevation = glm::radians(8.0f), azimuth = glm::radians(30.0f);
    const glm::vec3 wsHorizontal(std::cos(azimuth), 0.0f, std::sin(azimuth));  // toward +X, a little toward the camera
    addDirectionalLight(scene, std::cos(elevation) * wsHorizontal - glm::vec3(0.0f, std::sin(elevation), 0.0f));
    const CameraView camera = cameraLookingAt({0, 1.6f, 0}, {0, 1.0f, -10});
    ShadowSettings settings = sphereCascadeSettings();  // 4 cascades at 0.1 / 0.25 / 0.5 of 100 m
    // Blend culling on its own: receiver culling drops the post from cascade 1 anyway, as the part of its
    // shadow that leaves sphere 0 lies outside the view and sphere 1 (tests/unit/shadow_receiver_culling_test.cpp).
    settings.directional.receiverCulling = false;
    const ShadowFrame frame = ShadowPlanner::plan(scene, camera, settings);
    const CascadeSphere& sphere0 = frame.directional.cascades[0];
    ASSERT_LT(glm::length(glm::vec3(0, 0.5f, -4.0f) - sphere0.wsCenter) + 0.5f, 0.7f * sphere0.radius)
        << "the post should be inside 0.7 x cascade 0";
    const glm::vec3 shadowTip = glm::vec3(0.0f, 0.0f, -4.0f) + wsHorizontal / std::tan(elevation);
    ASSERT_GT(glm::length(shadowTip - sphere0.wsCenter), sphere0.radius) << "its shadow should leave cascade 0";
    EXPECT_TRUE(rendersInstance(frame.directional.tiles[0], post));
    EXPECT_TRUE(rendersInstance(frame.directional.tiles[1], post));
}

// The culling still works where it is safe: a small box on the ground under a high sun, its shadow
// at its foot, is left out of the bigger cascades.
TEST(ShadowPlanner, CasterWhoseShadowStaysInTheSmallerCascadeIsLeftOutOfTheBiggerOnes) {
    Scene scene = baseScene();
    addBox(scene, {-60, -0.1f, -100}, {60, 0, 10});
    const uint32_t box = addBox(scene, {-0.2f, 0, -4.2f}, {0.2f, 0.4f, -3.8f});
    addDirectionalLight(scene, {0.2f, -1.0f, 0.1f});
    const CameraView camera = cameraLookingAt({0, 1.6f, 0}, {0, 1.0f, -10});
    const ShadowFrame frame = ShadowPlanner::plan(scene, camera, sphereCascadeSettings());
    EXPECT_TRUE(rendersInstance(frame.directional.tiles[0], box));
    EXPECT_FALSE(rendersInstance(frame.directional.tiles[1], box));
    EXPECT_FALSE(rendersInstance(frame.directional.tiles[2], box));
    EXPECT_GE(frame.stats.skippedByBlendCulling, 2u);
}

TEST(ShadowFade, NoBlendTowardANextCascadeWhoseSphereMissesThePoint) {
    gpu_data::DirectionalShadowData data{};
    data.cascadeCount = 2;
    data.cascadeBlend = uint32_t(CascadeBlend::Soft);
    data.lightCount = 1;
    data.invShadowDistance = 0.0f;
    data.invDistanceFade = 1.0f;
    data.cascadeFadeScale = 1.0f / (1.0f - 0.8f * 0.8f);  // cascade fade 0.2
    data.shadowDistance = 100.0f;
    data.cascades[0].cullingSphere = glm::vec4(0, 0, 0, 100);   // radius 10 around the origin
    data.cascades[1].cullingSphere = glm::vec4(20, 0, 0, 144);  // radius 12 around x = 20
    data.cascades[0].invRadiusSquared = 1.0f / 100.0f;
    data.cascades[1].invRadiusSquared = 1.0f / 144.0f;
    EXPECT_LT(selectCascade(data, {9.5f, 0, 0}, 1.0f).cascadeBlend, 1.0f);   // in the band, inside sphere 1
    EXPECT_EQ(selectCascade(data, {-9.5f, 0, 0}, 1.0f).cascadeBlend, 1.0f);  // in the band, outside sphere 1
}
