#pragma once
// Which spot and point lights get shadow tiles this frame (as in Catlike Coding "Spotlight Shadows"),
// extended the way Unity's later pipelines did it.
//
// Budget: the other-light atlas holds kMaxOtherShadowTiles = 16 tiles. A spot light costs 1 tile, a
// point light 6 (one per cube face), so "up to 16 shadowed other lights" counts faces fairly: e.g. 16
// spots, or 2 points + 4 spots. A light qualifies when its shadows are not None, its strength is > 0,
// and a shadow caster meets its shadow frustum (spot: the cone's square frustum out to the range;
// point: any of the six faces), Unity's GetShadowCasterBounds test.
//
// Priority when more tiles are wanted than fit: qualifying lights are taken by decreasing screen-space
// influence (screenInfluence below), each one that still fits in the remaining tiles is kept (so a
// point light that doesn't fit can leave room for later spots); the rest are dropped and reported.
// Reserved lights keep scene order in the atlas, so the tiling is stable while priorities change.
#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/camera.h"
#include "penumbra/scene.h"

namespace penumbra {

struct ReservedOtherLight {
    uint32_t sceneLightIndex = 0;
    bool point = false;       // 6 tiles (cube faces) instead of 1
    bool soft = true;         // LightShadows::Soft: spot.filter; Hard: one bilinear 2x2 PCF tap
    float pcssRadius = 0.0f;  // LightShadows::Pcss: the emitter's radius (shadowLightSize), else 0
    float strength = 1.0f;
    float normalBias = 1.0f;      // Light::shadowNormalBias, in filter texels at the fragment's distance
    float slopeScaleBias = 0.0f;  // Light::shadowBias: slope-scale bias, applied by the lit pass
    float nearDistance = 0.1f;    // shadowNearPlane, at least kMinOtherNearPlane
    float farDistance = 1.0f;     // range, or the scene bounds' farthest corner when the range is infinite
    float influence = 0.0f;       // screenInfluence, the priority
    uint32_t firstTile = 0;
    uint32_t tileCount() const { return point ? 6u : 1u; }
};

// What a reservation found about one light's shadow volume and its casters, kept for the next frames
// (OtherLightReservation::memos): while neither the light nor the casters changed (the caller's caster
// epoch) the answer stands; after a change the caster found last (`witness`) is tested first, so a
// light keeps its place without a walk over every caster.
struct ShadowVolumeMemo {
    uint64_t casterEpoch = 0;  // the casters' epoch of the answer (0: none)
    LightType type = LightType::Spot;
    glm::vec3 wsPosition{0.0f};
    glm::vec3 wsDirection{0.0f};
    float outerConeAngle = 0.0f;
    float nearDistance = 0.0f;
    float farDistance = 0.0f;
    uint32_t witness = ~0u;  // a caster found in the volume (~0u: none)
    bool anyCaster = false;
};

struct OtherLightReservation {
    std::vector<ReservedOtherLight> lights;  // scene order; firstTile assigned consecutively
    std::vector<uint32_t> droppedLights;     // scene indices that qualified but did not fit, scene order
    std::vector<std::string> warnings;       // one line per dropped light
    uint32_t considered = 0;                 // spot and point lights in the scene
    uint32_t tilesUsed = 0;
    // Working storage of reserveOtherShadows (the qualifying lights and their priority order), kept
    // so that reserving into the same object again allocates nothing.
    std::vector<ReservedOtherLight> candidates;
    std::vector<uint32_t> order;
    std::vector<ShadowVolumeMemo> memos;  // per scene light, across reservations into this object
    uint32_t casterWalks = 0;             // lights whose casters were walked by the last reservation
};

inline constexpr float kMinOtherNearPlane = 0.01f;

// The far plane of a spot or point light's shadow: its range, or (infinite range) the distance to the
// farthest corner of the scene bounds, never closer than twice the near plane.
float otherShadowFarDistance(const Light& light, const Aabb& wsSceneBounds);

// Fraction (0..1) of the camera's image covered by the projected bounding box of the sphere of the
// light's influence (centre = light position, radius = far distance), clipped to the image: 0 when
// the sphere is outside the view frustum, 1 when it reaches the camera's near plane.
float screenInfluence(const glm::vec3& wsCenter, float radius, const CameraView& camera);

OtherLightReservation reserveOtherShadows(const Scene& scene, const CameraView& camera,
                                          const std::vector<uint32_t>& casters);
// The same into `result` (replaced; its storage and memos reused). casterEpoch: a number that changes
// whenever the casters or their bounds may have changed since the last call into `result` (0: unknown,
// every light's answer is found again, its witness first).
void reserveOtherShadows(const Scene& scene, const CameraView& camera, const std::vector<uint32_t>& casters,
                         OtherLightReservation& result, uint64_t casterEpoch = 0);

}  // namespace penumbra
