#include "shadows/caster_culling.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "shadows/spot_culling.h"

namespace penumbra {

bool isShadowCaster(const Scene& scene, const Instance& instance) {
    if (!instance.castShadows || !instance.wsBounds.valid()) return false;
    if (instance.meshIndex >= scene.meshes.size()) return false;
    const uint32_t materialIndex = scene.meshes[instance.meshIndex].materialIndex;
    if (materialIndex < scene.materials.size() &&
        scene.materials[materialIndex].shadows == MaterialShadowMode::Off) {
        return false;
    }
    return true;
}

void shadowCasterInstances(const Scene& scene, std::vector<uint32_t>& casters) {
    casters.clear();
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        if (isShadowCaster(scene, scene.instances[i])) casters.push_back(i);
    }
}

std::vector<uint32_t> shadowCasterInstances(const Scene& scene) {
    std::vector<uint32_t> casters;
    casters.reserve(scene.instances.size());
    shadowCasterInstances(scene, casters);
    return casters;
}

std::vector<Aabb> rotatedCasterBounds(const Scene& scene, const std::vector<uint32_t>& casters,
                                      const glm::mat4& lightRotation) {
    // Exact bounds of a rotated box: per output axis, sum of |row| x half extents (cheaper than 8 corners).
    const glm::mat3 rotation(lightRotation);
    const glm::mat3 absRotation(glm::abs(rotation[0]), glm::abs(rotation[1]), glm::abs(rotation[2]));
    std::vector<Aabb> bounds(casters.size());
    for (size_t i = 0; i < casters.size(); ++i) {
        const Aabb& ws = scene.instances[casters[i]].wsBounds;
        const glm::vec3 center = rotation * ws.center();
        const glm::vec3 halfExtent = absRotation * (0.5f * ws.extent());
        bounds[i].min = center - halfExtent;
        bounds[i].max = center + halfExtent;
    }
    return bounds;
}

bool intersectsExtrudedSphere(const Aabb& rsBounds, const glm::vec3& rsCenter, float radius) {
    if (rsBounds.max.z < rsCenter.z - radius) return false;  // wholly beyond the sphere, away from the light
    const glm::vec2 closest = glm::clamp(glm::vec2(rsCenter), glm::vec2(rsBounds.min), glm::vec2(rsBounds.max));
    const glm::vec2 d = closest - glm::vec2(rsCenter);
    return glm::dot(d, d) <= radius * radius;
}

bool intersectsCasterBox(const Aabb& lsBounds, float halfExtent, float farDistance) {
    return lsBounds.max.z >= -farDistance && lsBounds.min.x <= halfExtent && lsBounds.max.x >= -halfExtent &&
           lsBounds.min.y <= halfExtent && lsBounds.max.y >= -halfExtent;
}

float cascadeBlendCullingFactor(float cascadeFade) { return std::max(0.0f, 0.8f - cascadeFade); }

bool insideScaledSphere(const Aabb& wsBounds, const CascadeSphere& sphere, float factor) {
    const glm::vec3 farthest = glm::max(glm::abs(wsBounds.min - sphere.wsCenter), glm::abs(wsBounds.max - sphere.wsCenter));
    const float radius = sphere.radius * factor;
    return glm::dot(farthest, farthest) <= radius * radius;
}

bool isShadowReceiver(const Scene& scene, const Instance& instance) {
    if (!instance.wsBounds.valid() || instance.meshIndex >= scene.meshes.size()) return false;
    const uint32_t material = scene.meshes[instance.meshIndex].materialIndex;
    return material >= scene.materials.size() || scene.materials[material].receiveShadows;
}

std::vector<Aabb> shadowReceiverBounds(const Scene& scene) {
    std::vector<Aabb> bounds;
    for (const Instance& instance : scene.instances)
        if (isShadowReceiver(scene, instance)) bounds.push_back(instance.wsBounds);
    return bounds;
}

Aabb shadowReceiverUnion(const Scene& scene) {
    Aabb bounds;
    for (const Instance& instance : scene.instances)
        if (isShadowReceiver(scene, instance)) bounds.extend(instance.wsBounds);
    return bounds;
}

Aabb shadowOnReceiver(const Aabb& wsCaster, const glm::vec3& wsLightDirection, const Aabb& wsReceiver) {
    // The sweep wsCaster + t * direction (t >= 0) overlaps the receiver on each axis for t in an
    // interval; the shadow can reach the receiver for t in the intersection [t0, t1] of the three.
    float t0 = 0.0f, t1 = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
        const float d = wsLightDirection[axis];
        if (std::abs(d) < 1e-12f) {
            if (wsCaster.min[axis] > wsReceiver.max[axis] || wsCaster.max[axis] < wsReceiver.min[axis]) return Aabb{};
            continue;
        }
        float enter = (wsReceiver.min[axis] - wsCaster.max[axis]) / d;
        float leave = (wsReceiver.max[axis] - wsCaster.min[axis]) / d;
        if (enter > leave) std::swap(enter, leave);
        t0 = std::max(t0, enter);
        t1 = std::min(t1, leave);
    }
    if (!(t0 <= t1)) return Aabb{};
    Aabb swept;
    for (float t : {t0, t1}) {
        swept.extend(wsCaster.min + t * wsLightDirection);
        swept.extend(wsCaster.max + t * wsLightDirection);
    }
    Aabb clipped{glm::max(swept.min, wsReceiver.min), glm::min(swept.max, wsReceiver.max)};
    return clipped.valid() ? clipped : Aabb{};
}

bool shadowInsideScaledSphere(const Aabb& wsCaster, const glm::vec3& wsLightDirection,
                              const std::vector<Aabb>& wsReceivers, const CascadeSphere& sphere, float factor) {
    for (const Aabb& receiver : wsReceivers) {
        const Aabb shadow = shadowOnReceiver(wsCaster, wsLightDirection, receiver);
        if (shadow.valid() && !insideScaledSphere(shadow, sphere, factor)) return false;
    }
    return true;
}

ReceiverVolume cameraReceiverVolume(const CameraView& camera) {
    ReceiverVolume volume;
    const std::array<glm::vec4, 5> clip = clipFrustumPlanes(camera.clipFromWorld);
    for (int i = 0; i < 4; ++i) {  // the sides; clip's fifth plane is reversed Z's near plane
        const float length = glm::length(glm::vec3(clip[i]));
        if (!(length > 0.0f) || !std::isfinite(length)) return volume;
        volume.wsSidePlanes[i] = clip[i] / length;
    }
    const glm::vec3 forward = glm::normalize(camera.wsForward);
    volume.wsDepthPlane = glm::vec4(forward, -glm::dot(forward, camera.wsPosition));
    volume.valid = true;
    return volume;
}

bool boxMeetsReceiverVolume(const Aabb& wsBounds, const ReceiverVolume& volume) {
    if (!aabbMeetsPlanes(wsBounds, volume.wsSidePlanes)) return false;  // false for an invalid box too
    const glm::vec3 depthNormal(volume.wsDepthPlane);
    const float deepest = glm::dot(depthNormal, farthestCorner(wsBounds, depthNormal)) + volume.wsDepthPlane.w;
    const float shallowest = glm::dot(depthNormal, farthestCorner(wsBounds, -depthNormal)) + volume.wsDepthPlane.w;
    if (deepest < volume.vsDepthRange.x || shallowest > volume.vsDepthRange.y) return false;
    if (volume.wsSphere.w < 0.0f) return true;
    const glm::vec3 centre(volume.wsSphere), closest = glm::clamp(centre, wsBounds.min, wsBounds.max);
    return glm::dot(closest - centre, closest - centre) <= volume.wsSphere.w * volume.wsSphere.w;
}

bool shadowMeetsReceiverVolume(const Aabb& wsCaster, float wsReach, const glm::vec3& wsLightDirection,
                               const Aabb& wsReceivers, const ReceiverVolume& volume) {
    const Aabb grown{wsCaster.min - wsReach, wsCaster.max + wsReach};
    return boxMeetsReceiverVolume(shadowOnReceiver(grown, wsLightDirection, wsReceivers), volume);
}

TileCasters cullTileCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                            const std::vector<Aabb>& rsBounds, const CascadeLightView& view,
                            const std::vector<CascadeSphere>& spheres, uint32_t cascadeIndex,
                            const BlendCulling& blendCulling, const ReceiverCulling& receiverCulling) {
    PENUMBRA_ASSERT(casters.size() == rsBounds.size() && cascadeIndex < spheres.size());
    // lightFromWorld = translate(t) * rotation, so light-view bounds are the rotated bounds shifted by t.
    const glm::vec3 translation(view.lightFromWorld[3]);
    const float farDistance = view.receiversFar;
    // The light travels along -Z of its view: the third row of the rotation, negated.
    const glm::vec3 wsLightDirection = -glm::vec3(view.lightFromWorld[0][2], view.lightFromWorld[1][2],
                                                  view.lightFromWorld[2][2]);
    const float cullingFactor = blendCulling.wsReceivers ? blendCulling.factor : 0.0f;
    TileCasters result;
    for (size_t i = 0; i < casters.size(); ++i) {
        const Aabb ls{rsBounds[i].min + translation, rsBounds[i].max + translation};
        if (!intersectsCasterBox(ls, view.halfExtent, farDistance)) continue;
        const Aabb& ws = scene.instances[casters[i]].wsBounds;
        bool coveredBySmaller = false;
        for (uint32_t j = 0; j < cascadeIndex && cullingFactor > 0.0f && !coveredBySmaller; ++j) {
            coveredBySmaller = insideScaledSphere(ws, spheres[j], cullingFactor) &&
                               shadowInsideScaledSphere(ws, wsLightDirection, *blendCulling.wsReceivers, spheres[j],
                                                        cullingFactor);
        }
        if (coveredBySmaller) {
            ++result.skippedByBlendCulling;
            continue;
        }
        if (receiverCulling.enabled() && !shadowMeetsReceiverVolume(ws, receiverCulling.wsReach, wsLightDirection,
                                                                    *receiverCulling.wsReceivers, *receiverCulling.volume)) {
            ++result.skippedByReceiverCulling;
            continue;
        }
        result.instances.push_back(casters[i]);
        result.lsMaxZ = std::max(result.lsMaxZ, ls.max.z);
    }
    return result;
}

}  // namespace penumbra
