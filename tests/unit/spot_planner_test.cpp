#include <cmath>
// The spot/point part of the shadow plan: tiles, matrices into the right tile, packed GPU data.
#include <gtest/gtest.h>

#include "shadows/shadow_planner.h"
#include "shadows/spot_projection.h"
#include "spot_test_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

ShadowFrame planFor(const Scene& scene, const ShadowSettings& settings = {}) {
    return ShadowPlanner::plan(scene, resolveCameraView(scene, 128, 128), settings);
}

glm::vec3 toAtlas(const glm::mat4& atlasFromWorld, const glm::vec3& wsPoint) {
    const glm::vec4 h = atlasFromWorld * glm::vec4(wsPoint, 1.0f);
    return glm::vec3(h) / h.w;
}

bool insideScissor(const OtherShadowPlan& plan, uint32_t tileIndex, const glm::vec2& uv) {
    const AtlasTileRect scissor = spotTileScissor(plan.atlas, tileIndex);
    const glm::vec2 texel = uv * float(plan.atlas.atlasSize);
    return texel.x > float(scissor.offset.x) && texel.y > float(scissor.offset.y) &&
           texel.x < float(scissor.offset.x + scissor.size) && texel.y < float(scissor.offset.y + scissor.size);
}

}  // namespace

TEST(SpotShadowPlan, EveryLightCountFromOneToSixteenMapsEachConeIntoItsOwnTile) {
    for (uint32_t count = 1; count <= 16; ++count) {
        const Scene scene = spotGridScene(count);
        const OtherShadowPlan plan = planFor(scene).other;
        ASSERT_EQ(plan.tiles.size(), count);
        ASSERT_EQ(plan.atlas.tileCount, count);
        for (uint32_t i = 0; i < count; ++i) {
            const ShadowTile& tile = plan.tiles[i];
            const Light& light = scene.lights[plan.lights[tile.lightSlot].sceneLightIndex];
            EXPECT_EQ(tile.rect.offset, spotTileViewport(plan.atlas, i).offset);
            EXPECT_EQ(tile.scissorInset, count > 1 ? 4u : 0u);
            // The light's axis lands in the tile's centre; a point on the cone's edge stays inside the
            // scissored interior.
            const glm::vec3 axisPoint = light.wsPosition + 3.0f * light.wsDirection;
            const glm::vec3 centre = toAtlas(tile.atlasFromWorld, axisPoint);
            const AtlasTileRect rect = spotTileViewport(plan.atlas, i);
            const glm::vec2 expected = (glm::vec2(rect.offset) + 0.5f * float(rect.size)) / float(plan.atlas.atlasSize);
            EXPECT_NEAR(centre.x, expected.x, 1e-4f) << count << " lights, tile " << i;
            EXPECT_NEAR(centre.y, expected.y, 1e-4f) << count << " lights, tile " << i;
            EXPECT_GT(centre.z, 0.0f);
            EXPECT_LT(centre.z, 1.0f);
            const glm::vec3 edge = light.wsPosition + 3.0f * glm::vec3(std::sin(light.outerConeAngle), -std::cos(light.outerConeAngle), 0.0f);
            EXPECT_TRUE(insideScissor(plan, i, glm::vec2(toAtlas(tile.atlasFromWorld, edge))))
                << count << " lights, tile " << i;
            EXPECT_EQ(plan.gpu.atlasFromWorld[i], tile.atlasFromWorld);
        }
    }
}

TEST(SpotShadowPlan, TileCastersAreThoseInsideTheLightsFrustum) {
    const Scene scene = spotGridScene(2);  // instances: ground, box0, box1
    const OtherShadowPlan plan = planFor(scene).other;
    ASSERT_EQ(plan.tiles.size(), 2u);
    EXPECT_EQ(plan.tiles[0].casterInstances, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(plan.tiles[1].casterInstances, (std::vector<uint32_t>{0, 2}));
}

TEST(SpotShadowPlan, PackedLightDataCarriesStrengthKindAndBias) {
    Scene scene = spotGridScene(2);
    scene.lights[0].shadows = LightShadows::Hard;
    scene.lights[1].shadowStrength = 0.5f;
    scene.lights[1].shadowNormalBias = 2.0f;
    ShadowSettings settings;
    settings.spot.filter = ShadowFilter::PCF3x3;
    const OtherShadowPlan plan = planFor(scene, settings).other;
    EXPECT_EQ(plan.gpu.lights[0].strength, 1.0f);
    EXPECT_EQ(plan.gpu.lights[0].firstTile, 0u);
    EXPECT_EQ(plan.gpu.lights[0].soft, 0u);
    EXPECT_EQ(plan.gpu.lights[0].point, 0u);
    EXPECT_EQ(plan.gpu.lights[1].strength, 0.5f);
    EXPECT_EQ(plan.gpu.lights[1].firstTile, 1u);
    EXPECT_EQ(plan.gpu.lights[1].soft, 1u);
    EXPECT_EQ(plan.gpu.lights[1].point, 0u);
    EXPECT_EQ(plan.specializationMode, gpu_data::kOtherShadowsHard | gpu_data::kOtherShadowsSoft);
    EXPECT_EQ(plan.gpu.lightCount, 2u);
    EXPECT_EQ(plan.gpu.filterMode, uint32_t(ShadowFilter::PCF3x3));
    EXPECT_EQ(plan.gpu.tilesUsed, 2u);
    EXPECT_EQ(plan.gpu.split, 2u);
    // Biases: normal-bias multiplier, slope-scale bias, world texel per unit distance (2 tan(fov/2) /
    // tileSize), the light's filter: spot.filter when soft, PCF2x2 when hard.
    for (uint32_t slot : {0u, 1u}) {
        const gpu_data::OtherShadowLight& light = plan.gpu.lights[slot];
        EXPECT_EQ(light.normalBias, slot == 1 ? 2.0f : 1.0f);
        EXPECT_EQ(light.slopeBias, 0.0f);
        EXPECT_EQ(light.wsTexelPerDistance, plan.tiles[slot].wsTexelSize);
        EXPECT_EQ(light.filterMode, slot == 1 ? gpu_data::kShadowFilterPcf3x3 : gpu_data::kShadowFilterPcf2x2);
    }
    EXPECT_EQ(plan.slotOfSceneLight, (std::vector<int32_t>{0, 1}));
}

// One normal-bias rule. The lit pass's unit is normalOffsetFootprint(filter) x the
// world texel at the fragment for every light type; a soft spot with the directional filter gets the
// directional unit, not the old 1 + filter.
TEST(SpotShadowPlan, SpotNormalBiasUnitIsTheDirectionalRule) {
    Scene scene = spotGridScene(1);
    ShadowSettings settings;
    settings.spot.filter = ShadowFilter::PCF5x5;
    const OtherShadowPlan plan = planFor(scene, settings).other;
    const uint32_t filter = plan.gpu.lights[0].filterMode;
    EXPECT_EQ(filter, gpu_data::kShadowFilterPcf5x5);
    EXPECT_FLOAT_EQ(gpu_data::normalOffsetFootprint(filter), 2.0f * std::sqrt(2.0f));  // not (1 + 2) sqrt(2)
}

TEST(SpotShadowPlan, NoShadowedOtherLightGivesNoTilesAndModeZero) {
    const OtherShadowPlan plan = planFor(spotGridScene(3, LightShadows::None)).other;
    EXPECT_TRUE(plan.tiles.empty());
    EXPECT_EQ(plan.atlas.tileCount, 0u);
    EXPECT_EQ(plan.specializationMode, 0u);
    EXPECT_EQ(plan.gpu.lightCount, 0u);
}

TEST(SpotShadowPlan, PointLightHasSixFaceTilesEachSeeingItsOwnDirection) {
    Scene scene = spotGridScene(1);
    scene.lights.push_back(makePointLight({0.0f, 3.0f, 0.0f}, 50.0f, 10.0f));
    const OtherShadowPlan plan = planFor(scene).other;
    ASSERT_EQ(plan.tiles.size(), 7u);
    EXPECT_EQ(plan.atlas.split, 3u);
    const auto& faces = pointLightFaceDirections();
    for (uint32_t face = 0; face < 6; ++face) {
        const ShadowTile& tile = plan.tiles[1 + face];
        EXPECT_EQ(tile.cascadeIndex, face);
        const glm::vec3 point = glm::vec3(0.0f, 3.0f, 0.0f) + 2.0f * faces[face];
        const glm::vec2 uv(toAtlas(tile.atlasFromWorld, point));
        const AtlasTileRect rect = spotTileViewport(plan.atlas, 1 + face);
        const glm::vec2 expected = (glm::vec2(rect.offset) + 0.5f * float(rect.size)) / float(plan.atlas.atlasSize);
        EXPECT_NEAR(uv.x, expected.x, 1e-4f) << "face " << face;
        EXPECT_NEAR(uv.y, expected.y, 1e-4f) << "face " << face;
    }
    EXPECT_EQ(plan.gpu.lights[1].point, 1u);
    EXPECT_EQ(plan.gpu.lights[1].firstTile, 1u);
}

// shadows.spot.mode = virtual: the lights are reserved and packed as for the atlas, but no atlas tile is
// planned; face i of the virtual maps stands where tile i would (a spot light's cone around its axis, a
// point light's six faces along the cube directions), each from the light's position.
TEST(SpotShadowPlan, VirtualModePlansFacesWhereTheAtlasWouldPlanTiles) {
    Scene scene = spotGridScene(2);
    scene.lights.push_back(makePointLight({0.0f, 3.0f, 0.0f}, 50.0f, 10.0f));
    ShadowSettings settings;
    settings.spot.mode = SpotShadowMode::Virtual;
    settings.virtualMaps.faceResolution = 4096;
    const OtherShadowPlan atlas = planFor(scene).other;
    const OtherShadowPlan plan = planFor(scene, settings).other;
    EXPECT_TRUE(plan.virtualFaces);
    EXPECT_TRUE(plan.tiles.empty());
    EXPECT_EQ(plan.atlas.tileCount, 0u);
    EXPECT_EQ(plan.faceConfig.resolution, 4096u);
    ASSERT_EQ(plan.faces.size(), atlas.tiles.size());
    ASSERT_EQ(plan.faceLights.size(), plan.lights.size());
    EXPECT_EQ(plan.gpu.lightCount, atlas.gpu.lightCount);
    EXPECT_GT(plan.faceMarginTexels, 0.0f);
    for (uint32_t slot = 0; slot < plan.lights.size(); ++slot) {
        EXPECT_EQ(plan.faceLights[slot].firstFace, plan.gpu.lights[slot].firstTile);
        EXPECT_EQ(plan.faceLights[slot].point, plan.lights[slot].point);
    }
    for (uint32_t face = 0; face < plan.faces.size(); ++face) {
        const ShadowTile& tile = atlas.tiles[face];
        const Light& light = scene.lights[plan.lights[tile.lightSlot].sceneLightIndex];
        const glm::vec3 axis = plan.lights[tile.lightSlot].point ? pointLightFaceDirections()[tile.cascadeIndex]
                                                                : light.wsDirection;
        EXPECT_EQ(plan.faces[face].wsPosition, light.wsPosition);
        // The axis lands at the face's centre, between the near and far planes.
        const std::optional<FacePoint> centre = projectOntoFace(plan.faces[face], light.wsPosition + 2.0f * axis);
        ASSERT_TRUE(centre.has_value()) << "face " << face;
        EXPECT_NEAR(centre->ndc.x, 0.0f, 1e-4f) << "face " << face;
        EXPECT_NEAR(centre->ndc.y, 0.0f, 1e-4f) << "face " << face;
        // A spot's cone edge (or a point face's 45° edge) lies inside the face, near its border.
        const float coneTangent = plan.lights[tile.lightSlot].point ? 1.0f : std::tan(light.outerConeAngle);
        EXPECT_GT(plan.faces[face].tanHalfFov, coneTangent) << "widened for the filter's reach";
        EXPECT_LT(plan.faces[face].tanHalfFov, coneTangent * 1.2f) << "by a few coarse texels only";
    }
}
