#pragma once
// Which instances cast into which shadow tile (the CPU side of Unity's per-split culling as Catlike Coding
// "Directional Shadows" uses it: GetShadowCasterBounds, splitData, shadowCascadeBlendCullingFactor).
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "shadows/cascades.h"

namespace penumbra {

// An instance casts shadows when the node allows it and its material's shadow mode is not Off
// ("Directional Shadows", No Shadows), and it has geometry (valid bounds).
bool isShadowCaster(const Scene& scene, const Instance& instance);
// Indices (into Scene::instances) of every shadow caster, in scene order.
std::vector<uint32_t> shadowCasterInstances(const Scene& scene);
void shadowCasterInstances(const Scene& scene, std::vector<uint32_t>& casters);  // replaced, storage reused

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

// Unity's shadowCascadeBlendCullingFactor as "Directional Shadows", Culling Bias sets it: 0.8 minus the
// cascade fade so casters in the blend region are never culled, at least 0.
float cascadeBlendCullingFactor(float cascadeFade);
// Whether wsBounds lies wholly inside the sphere with its radius scaled by factor.
bool insideScaledSphere(const Aabb& wsBounds, const CascadeSphere& sphere, float factor);

// Whether an instance receives shadows: it has bounds and a mesh, and its material receives shadows.
bool isShadowReceiver(const Scene& scene, const Instance& instance);
// Bounds of every instance whose material receives shadows, in scene order: where shadows can land.
std::vector<Aabb> shadowReceiverBounds(const Scene& scene);
// Their union (invalid when there is none).
Aabb shadowReceiverUnion(const Scene& scene);

// The part of a receiver's bounds that a caster's shadow can reach: the caster's bounds swept along
// the light (wsLightDirection, the way it travels) over the stretch where the sweep overlaps the
// receiver's bounds, clipped to those bounds. Invalid (empty) when the sweep misses the receiver.
Aabb shadowOnReceiver(const Aabb& wsCaster, const glm::vec3& wsLightDirection, const Aabb& wsReceiver);

// Whether everything a caster's shadow can reach on the receivers lies inside the sphere scaled by
// factor: only then may cascade blend culling drop the caster from bigger cascades (testing the
// caster's own bounds, as Unity does, drops posts whose long shadows leave the smaller cascade).
bool shadowInsideScaledSphere(const Aabb& wsCaster, const glm::vec3& wsLightDirection,
                              const std::vector<Aabb>& wsReceivers, const CascadeSphere& sphere, float factor);

struct TileCasters {
    std::vector<uint32_t> instances;  // indices into Scene::instances, scene order
    uint32_t skippedByBlendCulling = 0;
    float lsMaxZ = -INFINITY;  // highest light-view z (closest to the light) of the kept casters
};

// What cascade blend culling ("Culling Bias") needs: the factor and where shadows can land.
struct BlendCulling {
    float factor = 0.0f;                       // cascadeBlendCullingFactor; 0 culls nothing
    const std::vector<Aabb>* wsReceivers = nullptr;  // shadowReceiverBounds(scene)
};

// Casters of cascade `cascadeIndex` of one light: those meeting the cascade's caster box, minus those
// that, with all of their shadow (shadowInsideScaledSphere), lie inside a smaller cascade's culling
// sphere scaled by the blend-culling factor (Unity's culling bias, made safe for long shadows).
// rsBounds[i] are the rotated bounds of casters[i] (rotatedCasterBounds with the light's rotation).
TileCasters cullTileCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                            const std::vector<Aabb>& rsBounds, const CascadeLightView& view,
                            const std::vector<CascadeSphere>& spheres, uint32_t cascadeIndex,
                            const BlendCulling& blendCulling);

}  // namespace penumbra
