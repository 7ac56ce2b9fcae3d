#pragma once
// Perspective shadow views of spot lights and of the six faces of point lights (Catlike Coding "Spotlight
// Shadows" asks Unity's ComputeSpotShadowMatricesAndCullingPrimitives for them; here the matrices are
// computed).
//
// Same conventions as the directional tiles (shaders/shared/shadow_structs.h): light view space looks
// along -Z with +Y up; shadow clip space is Vulkan's (x right, y DOWN, z in [0, 1]); STANDARD depth,
// 0 at the near plane and 1 at the far plane. Perspective: the lit pass divides by w before sampling.
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

namespace penumbra {

// World -> light view of a light at wsPosition looking along wsDirection (unit not required).
glm::mat4 perspectiveLightFromWorld(const glm::vec3& wsPosition, const glm::vec3& wsDirection);

// Vulkan perspective for a square frustum with half-angle tangent tanHalfFov, standard depth:
// ndc.z = far (d - near) / ((far - near) d) for view distance d = -z, ndc.y = -y / (d tanHalfFov).
glm::mat4 perspectiveClipFromLight(float tanHalfFov, float nearDistance, float farDistance);

// The frustum's half-angle tangent for a cone of half-angle coneTangent (tan of the outer cone angle;
// 1 for a 90° point-light face) such that the cone lands `marginTexels` inside each edge of a tile of
// tileSize texels: the border plus the filter's reach, so filtering near the cone's edge reads texels
// that were rendered (Unity's later "fov bias" for point faces does the same).
float tanHalfFovWithMargin(float coneTangent, uint32_t tileSize, float marginTexels);

// The six faces of a point light, in tile order +X, -X, +Y, -Y, +Z, -Z: the cube-map face directions.
// The lit pass picks face = 2 * axis + (component < 0) by the major axis of light -> fragment.
const std::array<glm::vec3, 6>& pointLightFaceDirections();
uint32_t pointLightFaceOf(const glm::vec3& wsFromLight);

// The largest spot cone half-angle whose shadow map is still useful; wider cones are shadowed only
// within it (tan of ~89° would spread a tile over an almost infinite plane).
inline constexpr float kMaxShadowedSpotHalfAngle = 1.4835298642f;  // 85°

}  // namespace penumbra
