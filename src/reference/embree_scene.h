#pragma once
// The scene as an Embree 3 BVH, for the ray-traced shadow reference. One triangle geometry per
// Instance, with world-space vertices; Embree's geomID is the instance index.
//
// Which surfaces each kind of ray sees:
// - Camera rays (intersectCamera) see OPAQUE surfaces, and MASK surfaces where the base colour alpha
//   >= alphaCutoff. BLEND surfaces are invisible to camera rays: the shadow AOV describes the opaque
//   surface behind them (the rasterizer draws that AOV from opaque and mask geometry only).
//   Single-sided materials are seen from the front only (counter-clockwise winding in world space,
//   as the rasterizer's main pass culls back faces); double-sided ones from both sides.
// - Shadow rays (occluded) are blocked by both faces of a triangle (the caster pass doesn't cull),
//   following the material's shadow mode: On always blocks, Clip blocks where alpha
//   >= alphaCutoff, Dither blocks when ditherValue(hit) < alpha, Off never blocks. An instance with
//   castShadows == false never blocks. These rules hold whatever the material's alphaMode.
#include <cstdint>
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

struct SurfaceHit {
    uint32_t instanceIndex = 0;
    uint32_t triangleIndex = 0;
    float t = 0.0f;                      // ray parameter (the direction is unit, so a distance)
    glm::vec3 wsPosition{0.0f};          // from the barycentrics, more precise than origin + t * dir
    glm::vec3 wsGeometricNormal{0.0f};   // unit, on the front (counter-clockwise) side
    glm::vec3 wsShadingNormal{0.0f};     // unit, interpolated vertex normal, front side as authored
    bool frontFacing = true;             // the ray arrived on the front side
    const Material* material = nullptr;  // the EmbreeScene's copy, valid while it lives
};

class EmbreeScene {
public:
    // Copies what it needs from `scene`, which may be destroyed afterwards.
    // Throws penumbra::Error when Embree fails or an instance names a mesh or material that doesn't exist.
    explicit EmbreeScene(const Scene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest surface a camera ray sees in (tNear, tFar); `wsDirection` must be unit length.
    std::optional<SurfaceHit> intersectCamera(const glm::vec3& wsOrigin, const glm::vec3& wsDirection,
                                              float tNear, float tFar) const;
    // Whether a shadow caster blocks the segment (tNear, tFar) of the ray.
    bool occluded(const glm::vec3& wsOrigin, const glm::vec3& wsDirection, float tNear, float tFar) const;

    // Bounds of all triangles (invalid when there are none) and their largest extent (>= 1e-6).
    const Aabb& wsBounds() const { return wsBounds_; }
    float sceneScale() const;
    uint32_t triangleCount() const { return triangleCount_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    Aabb wsBounds_;
    uint32_t triangleCount_ = 0;
};

}  // namespace penumbra
