#include "shadows/spot_reservation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/reuse.h"

#include "shadows/caster_culling.h"
#include "shadows/spot_atlas_layout.h"
#include "shadows/spot_culling.h"
#include "shadows/spot_projection.h"

namespace penumbra {

float otherShadowFarDistance(const Light& light, const Aabb& wsSceneBounds) {
    const float near = std::max(light.shadowNearPlane, kMinOtherNearPlane);
    float far = light.range;
    if (!(far > 0.0f)) {
        far = 0.0f;
        if (wsSceneBounds.valid()) {
            const glm::vec3 offset = glm::max(glm::abs(wsSceneBounds.min - light.wsPosition),
                                              glm::abs(wsSceneBounds.max - light.wsPosition));
            far = glm::length(offset);
        }
    }
    return std::max(far, 2.0f * near);
}

float screenInfluence(const glm::vec3& wsCenter, float radius, const CameraView& camera) {
    const glm::vec3 c = glm::vec3(camera.viewFromWorld * glm::vec4(wsCenter, 1.0f));
    const float tanY = std::tan(0.5f * camera.yfov);
    const float tanX = tanY * camera.aspect;
    // Side planes through the eye (view looks along -Z): outward normals, the sphere is outside when its
    // centre is farther than the radius beyond any of them, or wholly behind the near plane.
    const glm::vec3 normals[4] = {glm::normalize(glm::vec3(1, 0, tanX)), glm::normalize(glm::vec3(-1, 0, tanX)),
                                  glm::normalize(glm::vec3(0, 1, tanY)), glm::normalize(glm::vec3(0, -1, tanY))};
    for (const glm::vec3& n : normals)
        if (glm::dot(n, c) > radius) return 0.0f;
    const float depth = -c.z;
    if (depth + radius < camera.zNear) return 0.0f;
    if (depth - radius < camera.zNear) return 1.0f;  // reaches the camera: treat as covering the view
    glm::vec2 lo(INFINITY), hi(-INFINITY);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p = c + radius * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
        const glm::vec2 ndc(p.x / (-p.z * tanX), p.y / (-p.z * tanY));
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    const glm::vec2 size = glm::max(glm::min(hi, glm::vec2(1.0f)) - glm::max(lo, glm::vec2(-1.0f)), glm::vec2(0.0f));
    return size.x * size.y / 4.0f;
}

namespace {

// The first of `casters` whose bounds meet the light's shadow volume, kNoFrustumCaster when none.
uint32_t firstCasterInShadowVolume(const Scene& scene, std::span<const uint32_t> casters, const Light& light,
                                   float near, float far) {
    if (light.type == LightType::Point) {
        // The six faces together cover every direction: casters meeting the range cube.
        const Aabb cube{light.wsPosition - glm::vec3(far), light.wsPosition + glm::vec3(far)};
        for (uint32_t index : casters) {
            const Aabb& b = scene.instances[index].wsBounds;
            if (glm::all(glm::lessThanEqual(b.min, cube.max)) && glm::all(glm::greaterThanEqual(b.max, cube.min)))
                return index;
        }
        return kNoFrustumCaster;
    }
    const float tanHalf = std::tan(std::min(light.outerConeAngle, kMaxShadowedSpotHalfAngle));
    const glm::mat4 clipFromWorld = perspectiveClipFromLight(tanHalf, near, far) *
                                    perspectiveLightFromWorld(light.wsPosition, light.wsDirection);
    return firstFrustumCaster(scene, casters, clipFromWorld, light.wsPosition);
}

// Whether any caster meets the light's shadow volume: the memo's answer while the light and the casters'
// epoch are those it was found with; else its witness if that is still a caster in the volume; else a
// walk over the casters.
bool anyCasterInShadowVolume(const Scene& scene, const std::vector<uint32_t>& casters, const Light& light, float near,
                             float far, uint64_t casterEpoch, ShadowVolumeMemo& memo, uint32_t& walks) {
    const bool sameLight = memo.type == light.type && memo.wsPosition == light.wsPosition &&
                           memo.wsDirection == light.wsDirection && memo.outerConeAngle == light.outerConeAngle &&
                           memo.nearDistance == near && memo.farDistance == far;
    if (sameLight && casterEpoch != 0 && memo.casterEpoch == casterEpoch) return memo.anyCaster;
    uint32_t found = kNoFrustumCaster;
    const uint32_t witness = memo.witness;
    if (witness < scene.instances.size() && isShadowCaster(scene, scene.instances[witness]))
        found = firstCasterInShadowVolume(scene, std::span(&witness, 1), light, near, far);
    if (found == kNoFrustumCaster) {
        found = firstCasterInShadowVolume(scene, casters, light, near, far);
        ++walks;
    }
    memo = {casterEpoch, light.type, light.wsPosition, light.wsDirection, light.outerConeAngle, near, far, found,
            found != kNoFrustumCaster};
    return memo.anyCaster;
}

constexpr uint32_t kNotKept = ~0u;  // a candidate's firstTile until the tile budget keeps it

std::string lightName(const Scene& scene, uint32_t index) {
    return "light " + std::to_string(index) + " '" + scene.lights[index].name + "'";
}

}  // namespace

void reserveOtherShadows(const Scene& scene, const CameraView& camera, const std::vector<uint32_t>& casters,
                         OtherLightReservation& result, uint64_t casterEpoch) {
    std::vector<ShadowVolumeMemo> memos = std::move(result.memos);  // kept with their contents
    resetKeepingStorage(result, &OtherLightReservation::lights, &OtherLightReservation::droppedLights,
                        &OtherLightReservation::warnings, &OtherLightReservation::candidates,
                        &OtherLightReservation::order);
    std::vector<ReservedOtherLight>& candidates = result.candidates;
    result.memos = std::move(memos);
    result.memos.resize(scene.lights.size());  // a new light starts with no memo
    result.casterWalks = 0;
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        if (light.type == LightType::Directional) continue;
        ++result.considered;
        if (light.shadows == LightShadows::None || !(light.shadowStrength > 0.0f)) continue;
        ReservedOtherLight entry;
        entry.sceneLightIndex = i;
        entry.point = light.type == LightType::Point;
        entry.soft = light.shadows != LightShadows::Hard;
        if (light.shadows == LightShadows::Pcss) entry.pcssRadius = light.shadowLightSize;
        entry.strength = std::min(light.shadowStrength, 1.0f);
        entry.normalBias = light.shadowNormalBias;
        entry.slopeScaleBias = light.shadowBias;
        entry.nearDistance = std::max(light.shadowNearPlane, kMinOtherNearPlane);
        entry.farDistance = otherShadowFarDistance(light, scene.wsBounds);
        if (!anyCasterInShadowVolume(scene, casters, light, entry.nearDistance, entry.farDistance, casterEpoch,
                                     result.memos[i], result.casterWalks))
            continue;
        entry.influence = screenInfluence(light.wsPosition, entry.farDistance, camera);
        if (entry.influence <= 0.0f) continue;  // lights nothing in view
        entry.firstTile = kNotKept;
        candidates.push_back(entry);
    }

    // Highest influence first, scene order among equals (a stable order without stable_sort's buffer).
    std::vector<uint32_t>& order = result.order;
    for (uint32_t i = 0; i < candidates.size(); ++i) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (candidates[a].influence != candidates[b].influence) return candidates[a].influence > candidates[b].influence;
        return a < b;
    });
    for (uint32_t index : order) {
        const uint32_t tiles = candidates[index].tileCount();
        if (result.tilesUsed + tiles > kMaxOtherShadowTiles) continue;
        result.tilesUsed += tiles;
        candidates[index].firstTile = 0;  // kept; its tile is assigned below, in scene order
    }
    uint32_t nextTile = 0;
    for (ReservedOtherLight& candidate : candidates) {
        if (candidate.firstTile == kNotKept) {
            const uint32_t index = candidate.sceneLightIndex;
            result.droppedLights.push_back(index);
            result.warnings.push_back(lightName(scene, index) + " casts no shadow: more than " +
                                      std::to_string(kMaxOtherShadowTiles) +
                                      " spot/point shadow tiles wanted (a spot light takes 1, a point light 6)");
            continue;
        }
        candidate.firstTile = nextTile;
        nextTile += candidate.tileCount();
        result.lights.push_back(candidate);
    }
}

OtherLightReservation reserveOtherShadows(const Scene& scene, const CameraView& camera,
                                          const std::vector<uint32_t>& casters) {
    OtherLightReservation result;
    reserveOtherShadows(scene, camera, casters, result);
    return result;
}

}  // namespace penumbra
