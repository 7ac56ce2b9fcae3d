#include "shadows/spot_shadow_planner.h"

#include <algorithm>
#include <cmath>

#include "core/reuse.h"
#include "core/stopwatch.h"
#include "shadows/shadow_fade.h"
#include "shadows/shadow_gpu_packing.h"
#include "shadows/spot_culling.h"
#include "shadows/spot_projection.h"

namespace penumbra {

float otherShadowFilterReach(bool soft, ShadowFilter filter) { return soft ? filterSize(filter) + 1.0f : 1.0f; }

namespace {

// The half-angle tangent of what a light's tile or face must cover: the spot's cone (at most 85°), or a
// point light's 90° cube face.
float shadowConeTangent(const Light& light, const ReservedOtherLight& reserved) {
    return reserved.point ? 1.0f : std::tan(std::min(light.outerConeAngle, kMaxShadowedSpotHalfAngle));
}

struct LightTiles {
    float tanHalfFov = 1.0f;
    float reach = 1.0f;  // filter reach in texels
};

// The frustum's half-angle: the cone (spot) or 45° (point face) plus a margin of the tile border and
// twice the filter reach (the second reach covers the normal-bias offset), so every texel a filter at
// the cone's edge reads was rendered.
LightTiles lightTileShape(const Light& light, const ReservedOtherLight& reserved, const SpotAtlasLayout& layout,
                          ShadowFilter filter) {
    LightTiles shape;
    shape.reach = otherShadowFilterReach(reserved.soft, filter);
    shape.tanHalfFov = tanHalfFovWithMargin(shadowConeTangent(light, reserved), layout.tileSize,
                                            float(layout.border) + 2.0f * shape.reach);
    return shape;
}

ShadowTile planOtherTile(const Scene& scene, const std::vector<uint32_t>& casters, const SpotAtlasLayout& layout,
                         const ReservedOtherLight& reserved, const LightTiles& shape, uint32_t slot, uint32_t face,
                         const glm::vec3& wsDirection, bool cullCasters, double& cullingMilliseconds) {
    const Light& light = scene.lights[reserved.sceneLightIndex];
    const uint32_t tileIndex = reserved.firstTile + face;
    ShadowTile tile;
    tile.lightSlot = slot;
    tile.cascadeIndex = face;
    tile.rect = spotTileViewport(layout, tileIndex);
    tile.scissorInset = layout.border;
    tile.lightFromWorld = perspectiveLightFromWorld(light.wsPosition, wsDirection);
    tile.nearDistance = reserved.nearDistance;
    tile.farDistance = reserved.farDistance;
    tile.clipFromLight = perspectiveClipFromLight(shape.tanHalfFov, tile.nearDistance, tile.farDistance);
    tile.clipFromWorld = tile.clipFromLight * tile.lightFromWorld;
    tile.atlasFromWorld = spotAtlasFromClip(layout, tileIndex) * tile.clipFromWorld;
    tile.wsTexelSize = 2.0f * shape.tanHalfFov / float(layout.tileSize);
    tile.slopeScaleBias = 0.0f;  // the light's shadowBias is applied by the lit pass (penumbra/shadows/bias.glsl)
    tile.depthClamp = true;  // pancaking onto the near plane, as for directional tiles
    tile.perspective = true;
    tile.wsApex = light.wsPosition;
    const Stopwatch cullingTime;
    if (cullCasters) tile.casterInstances = frustumCasters(scene, casters, tile.clipFromWorld, light.wsPosition);
    cullingMilliseconds += cullingTime.milliseconds();
    return tile;
}

void packLight(gpu_data::OtherShadowData& data, const Light& light, const ReservedOtherLight& reserved,
               const LightTiles& shape, const SpotAtlasLayout& layout, const ShadowSettings& settings, uint32_t slot) {
    gpu_data::OtherShadowLight& packed = data.lights[slot];
    packed.strength = reserved.strength;
    packed.firstTile = reserved.firstTile;
    packed.soft = reserved.soft ? 1u : 0u;
    packed.point = reserved.point ? 1u : 0u;
    // World texel size grows linearly with the distance d along the tile's axis: 2 d tan(fov/2) / tileSize.
    // The lit pass scales its biases by it, with the directional lights' rule (penumbra/shadows/bias.glsl).
    const float texelPerDistance = 2.0f * shape.tanHalfFov / float(layout.tileSize);
    const ShadowFilter filter = reserved.soft ? settings.spot.filter : ShadowFilter::PCF2x2;
    packed.wsPosition = glm::vec4(light.wsPosition, 0.0f);
    packed.wsAxis = glm::vec4(glm::normalize(light.wsDirection), 0.0f);
    packed.depthBias = settings.spot.depthBias;
    packed.normalBias = reserved.normalBias;
    packed.slopeBias = reserved.slopeScaleBias;
    packed.wsTexelPerDistance = texelPerDistance;
    packed.filterMode = uint32_t(filter);
    packed.pcssRadius = reserved.pcssRadius;
    packed.nearDistance = reserved.nearDistance;
    packed.farDistance = reserved.farDistance;
}

// The most a virtual face's frustum is widened for a lookup's reach, in texels of its coarsest mip (one
// page a side): a PCSS search reaching further at that mip reads beyond the face as lit, where finer
// mips (what a receiver near the light reads) reach a fraction of a coarse texel.
constexpr float kMaxFaceMarginTexels = 8.0f;

// shadows.spot.mode = virtual: the faces of every reserved light (tile i's place), widened for the
// light's lookup reach.
void planVirtualFaces(const Scene& scene, const ShadowSettings& settings, OtherShadowPlan& plan) {
    plan.faceConfig = {settings.virtualMaps.faceResolution, settings.virtualMaps.pageSize};
    plan.faceMarginTexels = 0.0f;
    for (const ReservedOtherLight& reserved : plan.lights) {
        const Light& light = scene.lights[reserved.sceneLightIndex];
        const ShadowFilter filter = reserved.soft ? settings.spot.filter : ShadowFilter::PCF2x2;
        const float reach = lookupReachTexels(reserved.normalBias, reserved.pcssRadius > 0.0f, filter);
        plan.faceMarginTexels = std::max(plan.faceMarginTexels, reach);
        const float margin = std::min(reach, kMaxFaceMarginTexels);
        const float coneTangent = shadowConeTangent(light, reserved);
        plan.faceLights.push_back({reserved.firstTile, reserved.point});
        for (uint32_t face = 0; face < reserved.tileCount(); ++face) {
            const glm::vec3 direction = reserved.point ? pointLightFaceDirections()[face] : light.wsDirection;
            plan.faces.push_back(makeVirtualFace(plan.faceConfig, light.wsPosition, direction, coneTangent,
                                                 reserved.nearDistance, reserved.farDistance, margin));
        }
    }
}

}  // namespace

void planOtherShadows(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                      const std::vector<uint32_t>& casters, float shadowDistance, bool cullCasters, OtherShadowPlan& plan,
                      OtherLightReservation& reservation, uint64_t casterEpoch) {
    resetKeepingStorage(plan, &OtherShadowPlan::lights, &OtherShadowPlan::tiles, &OtherShadowPlan::slotOfSceneLight,
                        &OtherShadowPlan::droppedLights, &OtherShadowPlan::warnings, &OtherShadowPlan::faces,
                        &OtherShadowPlan::faceLights);
    plan.virtualFaces = settings.spot.mode == SpotShadowMode::Virtual;
    reserveOtherShadows(scene, camera, casters, reservation, casterEpoch);
    plan.lights.assign(reservation.lights.begin(), reservation.lights.end());
    plan.droppedLights.assign(reservation.droppedLights.begin(), reservation.droppedLights.end());
    plan.warnings.assign(reservation.warnings.begin(), reservation.warnings.end());
    plan.lightsConsidered = reservation.considered;
    plan.slotOfSceneLight.assign(scene.lights.size(), -1);
    plan.atlas = makeSpotAtlasLayout(settings.spot.atlasSize, plan.virtualFaces ? 0u : reservation.tilesUsed);

    gpu_data::OtherShadowData& data = plan.gpu;
    for (uint32_t slot = 0; slot < plan.lights.size(); ++slot) {
        const ReservedOtherLight& reserved = plan.lights[slot];
        const Light& light = scene.lights[reserved.sceneLightIndex];
        plan.slotOfSceneLight[reserved.sceneLightIndex] = int32_t(slot);
        plan.specializationMode |= reserved.soft ? gpu_data::kOtherShadowsSoft : gpu_data::kOtherShadowsHard;
        const LightTiles shape = lightTileShape(light, reserved, plan.atlas, settings.spot.filter);
        for (uint32_t face = 0; face < (plan.virtualFaces ? 0u : reserved.tileCount()); ++face) {
            const glm::vec3 direction = reserved.point ? pointLightFaceDirections()[face] : light.wsDirection;
            ShadowTile tile = planOtherTile(scene, casters, plan.atlas, reserved, shape, slot, face, direction,
                                            cullCasters, plan.cullingMilliseconds);
            const uint32_t tileIndex = reserved.firstTile + face;
            data.atlasFromWorld[tileIndex] = tile.atlasFromWorld;
            data.tileBounds[tileIndex] = spotTileSampleBounds(plan.atlas, tileIndex, shape.reach);
            plan.tiles.push_back(std::move(tile));
        }
        packLight(data, light, reserved, shape, plan.atlas, settings, slot);
    }
    if (plan.virtualFaces) {
        planVirtualFaces(scene, settings, plan);
        // One lit variant for every virtual frame: its sampling takes each light's filter from the data.
        if (!plan.lights.empty()) plan.specializationMode = gpu_data::kOtherShadowsVirtual;
    }
    const glm::vec2 squaredFade = squaredFadeScaleBias(shadowDistance, settings.distanceFade);
    data.invShadowDistance = 1.0f / shadowDistance;
    data.invDistanceFade = 1.0f / settings.distanceFade;
    data.squaredFadeScale = squaredFade.x;
    data.squaredFadeBias = squaredFade.y;
    data.biasMode = uint32_t(settings.bias);
    data.fadeMode = uint32_t(settings.fadeMode);
    data.lightCount = uint32_t(plan.lights.size());
    data.filterMode = uint32_t(settings.spot.filter);
    data.tilesUsed = plan.atlas.tileCount;
    data.split = plan.atlas.split;
    const float atlasSize = float(std::max(plan.atlas.atlasSize, 1u));
    const float tileSize = float(std::max(plan.atlas.tileSize, 1u));
    data.atlasSize = atlasSize;
    data.invAtlasSize = 1.0f / atlasSize;
    data.tileSize = tileSize;
    data.invTileSize = 1.0f / tileSize;
}

OtherShadowPlan planOtherShadows(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                                 const std::vector<uint32_t>& casters, float shadowDistance, bool cullCasters) {
    OtherShadowPlan plan;
    OtherLightReservation reservation;
    planOtherShadows(scene, camera, settings, casters, shadowDistance, cullCasters, plan, reservation);
    return plan;
}

}  // namespace penumbra
