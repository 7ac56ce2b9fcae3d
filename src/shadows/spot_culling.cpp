#include "shadows/spot_culling.h"

namespace penumbra {

std::array<glm::vec4, 5> clipFrustumPlanes(const glm::mat4& clipFromWorld) {
    // Rows of the matrix (Gribb & Hartmann): clip = (r0.p, r1.p, r2.p, r3.p) for p = (x, y, z, 1).
    const glm::mat4 t = glm::transpose(clipFromWorld);
    const glm::vec4 r0 = t[0], r1 = t[1], r2 = t[2], r3 = t[3];
    return {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 - r2};
}

glm::vec3 farthestCorner(const Aabb& wsBounds, const glm::vec3& normal) {
    return glm::vec3(normal.x >= 0.0f ? wsBounds.max.x : wsBounds.min.x, normal.y >= 0.0f ? wsBounds.max.y : wsBounds.min.y,
                     normal.z >= 0.0f ? wsBounds.max.z : wsBounds.min.z);
}

bool aabbMeetsPlanes(const Aabb& wsBounds, std::span<const glm::vec4> planes) {
    if (!wsBounds.valid()) return false;
    for (const glm::vec4& plane : planes) {
        // The box corner farthest along the plane normal: if even it is outside, the whole box is.
        const glm::vec3 normal(plane);
        if (glm::dot(normal, farthestCorner(wsBounds, normal)) + plane.w < 0.0f) return false;
    }
    return true;
}

Aabb perspectiveFrustumBounds(const glm::mat4& clipFromWorld, const glm::vec3& wsApex) {
    const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
    Aabb bounds;
    bounds.extend(wsApex);
    for (int corner = 0; corner < 4; ++corner) {
        const glm::vec4 h = worldFromClip * glm::vec4(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, 1.0f, 1.0f);
        bounds.extend(glm::vec3(h) / h.w);
    }
    return bounds;
}

namespace {

// Calls keep(index) for each listed caster meeting the frustum until keep returns false.
template <typename Keep>
void forEachFrustumCaster(const Scene& scene, std::span<const uint32_t> casters, const glm::mat4& clipFromWorld,
                          const glm::vec3& wsApex, Keep&& keep) {
    const std::array<glm::vec4, 5> planes = clipFrustumPlanes(clipFromWorld);
    const Aabb frustum = perspectiveFrustumBounds(clipFromWorld, wsApex);
    for (uint32_t index : casters) {
        const Aabb& b = scene.instances[index].wsBounds;
        const bool overlaps = glm::all(glm::lessThanEqual(b.min, frustum.max)) &&
                              glm::all(glm::greaterThanEqual(b.max, frustum.min));
        if (overlaps && aabbMeetsPlanes(b, planes) && !keep(index)) return;
    }
}

}  // namespace

std::vector<uint32_t> frustumCasters(const Scene& scene, const std::vector<uint32_t>& casters,
                                     const glm::mat4& clipFromWorld, const glm::vec3& wsApex) {
    std::vector<uint32_t> inside;
    forEachFrustumCaster(scene, casters, clipFromWorld, wsApex, [&](uint32_t index) {
        inside.push_back(index);
        return true;
    });
    return inside;
}

uint32_t firstFrustumCaster(const Scene& scene, std::span<const uint32_t> casters, const glm::mat4& clipFromWorld,
                            const glm::vec3& wsApex) {
    uint32_t found = kNoFrustumCaster;
    forEachFrustumCaster(scene, casters, clipFromWorld, wsApex, [&](uint32_t index) {
        found = index;
        return false;
    });
    return found;
}

}  // namespace penumbra
