#pragma once
// Caster culling for perspective shadow tiles (spot lights, point-light faces): a caster is drawn
// into a tile when its world bounds meet the tile's frustum, the near plane left open so casters
// between the light and the near plane are pancaked onto it (depth clamp) rather than lost.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// The frustum of a Vulkan clip space (-w <= x, y <= w, z <= w) as 5 planes (left, right, bottom, top,
// far), each (normal, d) with dot(normal, p) + d >= 0 inside; not normalized.
std::array<glm::vec4, 5> clipFrustumPlanes(const glm::mat4& clipFromWorld);

// The box corner farthest along `normal` (the one a plane test decides by).
glm::vec3 farthestCorner(const Aabb& wsBounds, const glm::vec3& normal);
// Whether the box meets all of the planes (conservative: may accept boxes near frustum corners).
bool aabbMeetsPlanes(const Aabb& wsBounds, std::span<const glm::vec4> planes);

// World bounds of a perspective frustum from its apex (the light) to its far plane.
Aabb perspectiveFrustumBounds(const glm::mat4& clipFromWorld, const glm::vec3& wsApex);

// Indices into Scene::instances of the listed casters whose bounds meet the frustum, list order: the
// plane test plus an overlap test with the frustum's bounds, which rejects large boxes (a ground
// plane behind the light) that pass every plane separately.
std::vector<uint32_t> frustumCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                                     const glm::mat4& clipFromWorld, const glm::vec3& wsApex);
// The first instance frustumCasters would keep, kNoFrustumCaster when none: stops there (light
// reservation needs no list).
inline constexpr uint32_t kNoFrustumCaster = ~0u;
uint32_t firstFrustumCaster(const Scene& scene, std::span<const uint32_t> casters, const glm::mat4& clipFromWorld,
                            const glm::vec3& wsApex);

}  // namespace penumbra
