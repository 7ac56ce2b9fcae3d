#pragma once
// Which instances cast into which shadow tile (the CPU side of Unity's per-split culling, seed 000
// §1.4 GetShadowCasterBounds, §3.2 splitData, §4.9 shadowCascadeBlendCullingFactor).
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "shadows/cascades.h"

namespace penumbra {

// An instance casts shadows when the node allows it and its material's shadow mode is not Off
// (seed 000 §5.4), and it has geometry (valid bounds).
bool isShadowCaster(const Scene& scene, const Instance& instance);
// Indices (into Scene::instances) of every shadow caster, in scene order.
std::vector<uint32_t> shadowCasterInstances(const Scene& scene);

// Bounds of each listed caster after a rotation (the light's rotation-only view), in list order.
std::vector<Aabb> rotatedCasterBounds(const Scene& scene, const std::vector<uint32_t>& casters,
                                      const glm::mat4& lightRotation);

// Whether rsBounds (light rotation space) meets the sphere extruded toward the light: the circle of
// the sphere in light x/y, from the sphere's far side (z = centre - r) to infinity toward the light
// (+z). Casters anywhere between the light and the shadow region can shade it.
bool intersectsExtrudedSphere(const Aabb& rsBounds, const glm::vec3& rsCenter, float radius);

// Whether lsBounds (one cascade's light view) meets the cascade's caster volume: the ortho box
// [-h, h]^2 extended without limit toward the light, ending at z = -farDistance.
bool intersectsCasterBox(const Aabb& lsBounds, float halfExtent, float farDistance);

// Unity's shadowCascadeBlendCullingFactor as seed 000 §4.9 sets it: 0.8 minus the cascade fade so
// casters in the blend region are never culled, at least 0.
float cascadeBlendCullingFactor(float cascadeFade);
// Whether wsBounds lies wholly inside the sphere with its radius scaled by factor.
bool insideScaledSphere(const Aabb& wsBounds, const CascadeSphere& sphere, float factor);

struct TileCasters {
    std::vector<uint32_t> instances;  // indices into Scene::instances, scene order
    uint32_t skippedByBlendCulling = 0;
    float lsMaxZ = -INFINITY;  // highest light-view z (closest to the light) of the kept casters
};

// Casters of cascade `cascadeIndex` of one light: those meeting the cascade's caster box, minus those
// wholly inside a smaller cascade's culling sphere scaled by cullingFactor (seed 000 §4.9).
// rsBounds[i] are the rotated bounds of casters[i] (rotatedCasterBounds with the light's rotation).
TileCasters cullTileCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                            const std::vector<Aabb>& rsBounds, const CascadeLightView& view,
                            const std::vector<CascadeSphere>& spheres, uint32_t cascadeIndex,
                            float cullingFactor);

}  // namespace penumbra
