#pragma once
// Distance from a point to the nearest of a set of triangles, through a uniform grid of the triangles'
// boxes (cells about as wide as an average triangle): what measures how far a simplified level of a
// mesh lies from the full mesh, both ways (scene/meshlets.h addShadowLods). Closest point on a
// triangle: Ericson, "Real-Time Collision Detection", 5.1.5. CPU only.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra {

float pointTriangleDistance(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

class TriangleGrid {
public:
    // `indices`: a triangle list into `positions` (both kept by reference: they must outlive the grid).
    TriangleGrid(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);
    // The distance from `p` to the nearest triangle (0 without triangles).
    float distance(const glm::vec3& p) const;

private:
    glm::ivec3 cellOf(const glm::vec3& p) const;
    // The nearest triangle in the cells of the box [lo, hi]: its distance, or `limit` if none is nearer.
    float nearestIn(const glm::vec3& p, glm::ivec3 lo, glm::ivec3 hi, float limit) const;
    std::span<const glm::vec3> positions_;
    std::span<const uint32_t> indices_;
    glm::vec3 origin_{0.0f};
    float cell_ = 1.0f;
    glm::ivec3 cells_{1};
    std::vector<uint32_t> cellStart_;  // per cell (x fastest), its first entry in cellTriangles_; one more at the end
    std::vector<uint32_t> cellTriangles_;
};

}  // namespace penumbra
