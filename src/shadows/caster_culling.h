#pragma once
// Which instances cast into which shadow tile (the CPU side of Unity's per-split culling as Catlike Coding
// "Directional Shadows" uses it: GetShadowCasterBounds, splitData, shadowCascadeBlendCullingFactor).
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
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

// Where the receivers that sample one cascade can be: inside the camera's frustum (four unit side
// planes, dot(plane.xyz, p) + plane.w >= 0 inside), within a range of view depth (the tight fit selects
// cascades by depth), and, for the sphere fit, inside the cascade's culling sphere (what selects it). A
// caster whose shadow cannot land there shades no pixel through this cascade, however much of the
// cascade's square it covers: receiver-based caster culling as in Bittner et al., "Shadow Caster Culling
// for Efficient Shadow Mapping" (I3D 2011), with the camera's frustum standing in for the visible receivers.
inline constexpr float kAnyDepth = 3.0e38f;  // a depth range's open end (finite: the GPU reads it too)
struct ReceiverVolume {
    std::array<glm::vec4, 4> wsSidePlanes{};   // left, right, bottom, top
    glm::vec4 wsDepthPlane{0.0f};              // view depth of p: dot(xyz, p) + w
    glm::vec2 vsDepthRange{-kAnyDepth, kAnyDepth};
    glm::vec4 wsSphere{0.0f, 0.0f, 0.0f, -1.0f};  // centre, radius; radius < 0: no sphere
    bool valid = false;
};
// The camera's sides and view depth, any depth, no sphere (the caller narrows them per cascade).
ReceiverVolume cameraReceiverVolume(const CameraView& camera);
// Whether the box meets the volume (conservative near its edges, like every box-against-planes test).
bool boxMeetsReceiverVolume(const Aabb& wsBounds, const ReceiverVolume& volume);

// Whether a caster can shade a receiver inside the volume: its bounds grown by wsReach on every side (the
// lit pass's lookups reach that far from a receiver: filter taps, normal offset) and swept along the light
// over the receivers' common bounds (shadowOnReceiver) meet the volume.
bool shadowMeetsReceiverVolume(const Aabb& wsCaster, float wsReach, const glm::vec3& wsLightDirection,
                               const Aabb& wsReceivers, const ReceiverVolume& volume);

// What receiver culling needs for one cascade; off (nothing culled) without a volume or receivers.
struct ReceiverCulling {
    const ReceiverVolume* volume = nullptr;
    const Aabb* wsReceivers = nullptr;  // the receivers' common bounds
    float wsReach = 0.0f;               // the cascade's lookup reach (shadow_gpu_packing.h lookupReachTexels)
    bool enabled() const { return volume && volume->valid && wsReceivers && wsReceivers->valid(); }
};

struct TileCasters {
    std::vector<uint32_t> instances;  // indices into Scene::instances, scene order
    uint32_t skippedByBlendCulling = 0;
    uint32_t skippedByReceiverCulling = 0;
    float lsMaxZ = -INFINITY;  // highest light-view z (closest to the light) of the kept casters
};

// What cascade blend culling ("Culling Bias") needs: the factor and where shadows can land.
struct BlendCulling {
    float factor = 0.0f;                       // cascadeBlendCullingFactor; 0 culls nothing
    const std::vector<Aabb>* wsReceivers = nullptr;  // shadowReceiverBounds(scene)
};

// Casters of cascade `cascadeIndex` of one light: those meeting the cascade's caster box, minus those
// that, with all of their shadow (shadowInsideScaledSphere), lie inside a smaller cascade's culling
// sphere scaled by the blend-culling factor (Unity's culling bias, made safe for long shadows), minus
// those whose shadow cannot reach the receiver volume (shadowMeetsReceiverVolume).
// rsBounds[i] are the rotated bounds of casters[i] (rotatedCasterBounds with the light's rotation).
TileCasters cullTileCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                            const std::vector<Aabb>& rsBounds, const CascadeLightView& view,
                            const std::vector<CascadeSphere>& spheres, uint32_t cascadeIndex,
                            const BlendCulling& blendCulling, const ReceiverCulling& receiverCulling = {});

}  // namespace penumbra
