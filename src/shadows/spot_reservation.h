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
// The same into `result` (replaced; its storage reused).
void reserveOtherShadows(const Scene& scene, const CameraView& camera, const std::vector<uint32_t>& casters,
                         OtherLightReservation& result);

}  // namespace penumbra
