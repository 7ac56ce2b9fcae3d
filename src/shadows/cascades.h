#pragma once
// Cascade geometry of the directional shadows (Catlike Coding "Directional Shadows", Cascaded Shadow Maps):
// split distances along the view axis, one culling sphere per cascade around the camera frustum slice
// (light-independent, as Unity's ComputeDirectionalShadowMatricesAndCullingPrimitives gives them), and the
// stabilized orthographic light view fitted to a sphere.
//
// Light view space: the light looks along -Z (its wsDirection), +Y up, like the camera. Shadow clip
// space: Vulkan's (y down), standard depth 0 at the near plane (toward the light), 1 at the far plane.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/shadow_settings.h"

namespace penumbra {

// A cascade's slice of the camera frustum and the sphere that encloses it.
struct CascadeSphere {
    float vsNear = 0.0f;  // view depth where the slice begins
    float vsFar = 0.0f;   // view depth of the split (the last cascade ends at the shadow distance)
    glm::vec3 wsCenter{0.0f};
    float radius = 0.0f;
};

// The shadow distance actually used: min(maxDistance, camera zFar) ("Max Distance").
float shadowDistance(const CameraView& camera, float maxDistance);

// Far split of each cascade: ratios x shadow distance, the last cascade at the full distance
// (cascadeRatios). Kept non-decreasing and within [zNear, distance] so every slice is valid.
std::vector<float> cascadeSplitDistances(const CameraView& camera, float distance, uint32_t cascadeCount,
                                         const std::array<float, 3>& ratios);

// Minimal sphere around the 8 corners of the frustum slice between view depths vsNear and vsFar. The
// corners of a symmetric frustum at depth d lie on a circle of radius k*d around the view axis
// (k = half-diagonal of the unit-depth image plane), so the centre is on the axis at
// c = min(vsFar, (vsNear + vsFar)(1 + k^2) / 2): equidistant to both rings, or the far ring's own
// centre once the slice is wide enough. The radius depends on the slice only: rotating the camera
// moves the centre but never resizes the sphere, which keeps texels stable.
CascadeSphere frustumSliceSphere(const CameraView& camera, float vsNear, float vsFar);

// Far split of each cascade by the settings' cascadeSplits: manual = the ratios
// above; log = vsNear (f / n)^(i / N); practical = lambda log + (1 - lambda) uniform, over [vsNear,
// vsFar] (the camera's near plane and the shadow distance, or the visible depth range of a tight fit).
// The last split is vsFar.
std::vector<float> cascadeSplitDistances(const CameraView& camera, float vsNear, float vsFar,
                                         const DirectionalShadowSettings& settings, float shadowDistance);

// One culling sphere per slice; vsNear / vsFar bound the split range (see cascadeSplitDistances), the
// slices start at the camera's near plane.
std::vector<CascadeSphere> computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings,
                                                 float vsNear, float vsFar);
std::vector<CascadeSphere> computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings);
// The same into `spheres` (replaced; its storage reused: no allocation once it holds 4).
void computeCascadeSpheres(const CameraView& camera, const ShadowSettings& settings, float vsNear, float vsFar,
                           std::vector<CascadeSphere>& spheres);

// World -> light view rotation for a light travelling along wsDirection (no translation).
glm::mat4 lightRotationFromWorld(const glm::vec3& wsDirection);

// The light view of one cascade: lightFromWorld = translate(-snapped centre) * rotation. The sphere
// centre is rounded to whole texels in the light's x/y (texel = 2r / tileSize), so world geometry
// always lands on the same sub-texel position while the camera moves and static shadows don't shimmer.
struct CascadeLightView {
    glm::mat4 lightFromWorld{1.0f};
    glm::vec3 lsSphereCenter{0.0f};  // sphere (or box) centre in this light view: within half a texel of the origin
    float halfExtent = 0.0f;         // the ortho box is [-halfExtent, halfExtent]^2 = the sphere radius
    float wsTexelSize = 0.0f;        // 2r / tileSize
    // Light-view distances from the origin to the receivers' side toward the light (+z) and away from
    // it (-z): the sphere's, or the tight box's. The planner adds its margins to the first.
    float receiversNear = 0.0f;
    float receiversFar = 0.0f;
};
CascadeLightView fitCascadeLightView(const glm::mat4& lightRotation, const CascadeSphere& sphere,
                                     uint32_t tileSize);

// The light view of a tight cascade (fit = tight): the visible receivers' box rsBounds (light
// rotation space) grown by marginTexels texels per side, its half-size rounded up to the next 1/8
// octave (so it changes only when the view changes by more than that, not every frame) and its centre
// snapped to whole texels of that size, as the sphere fit does.
CascadeLightView fitTightLightView(const glm::mat4& lightRotation, const Aabb& rsBounds, uint32_t tileSize,
                                   float marginTexels);
// The 1/8-octave step a tight half-size is rounded up to.
float quantizedHalfExtent(float halfExtent);

// Orthographic Vulkan projection of the box [-h, h]^2 x z in [-farDistance, nearDistance]
// (light view z grows toward the light): depth = (nearDistance - z) / (nearDistance + farDistance).
glm::mat4 orthoClipFromLight(float halfExtent, float nearDistance, float farDistance);

}  // namespace penumbra
