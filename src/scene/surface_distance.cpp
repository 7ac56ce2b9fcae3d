#include "scene/surface_distance.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

float pointTriangleDistance(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // The closest point by the Voronoi regions of the vertices, edges and face.
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return glm::length(ap);
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return glm::length(bp);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return glm::distance(p, a + d1 / (d1 - d3) * ab);
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return glm::length(cp);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return glm::distance(p, a + d2 / (d2 - d6) * ac);
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f)
        return glm::distance(p, b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b));
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) return std::min({glm::length(ap), glm::length(bp), glm::length(cp)});  // degenerate
    return glm::distance(p, a + ab * (vb / sum) + ac * (vc / sum));
}

TriangleGrid::TriangleGrid(std::span<const glm::vec3> positions, std::span<const uint32_t> indices)
    : positions_(positions), indices_(indices) {
    const size_t triangles = indices.size() / 3;
    if (triangles == 0) return;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (uint32_t i : indices) lo = glm::min(lo, positions[i]), hi = glm::max(hi, positions[i]);
    const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-6f));
    // About one triangle a cell for a surface: cells as wide as the area per triangle, at most 128 a side.
    const float area = 2.0f * (extent.x * extent.y + extent.y * extent.z + extent.z * extent.x);
    cell_ = std::max({std::sqrt(area / float(triangles)), glm::max(extent.x, glm::max(extent.y, extent.z)) / 128.0f, 1e-6f});
    origin_ = lo;
    cells_ = glm::max(glm::ivec3(glm::floor(extent / cell_)) + 1, glm::ivec3(1));
    std::vector<uint32_t> counts(size_t(cells_.x) * cells_.y * cells_.z + 1, 0);
    auto forCells = [&](size_t t, auto&& f) {
        const glm::vec3 &a = positions[indices[t * 3]], &b = positions[indices[t * 3 + 1]], &c = positions[indices[t * 3 + 2]];
        const glm::ivec3 first = cellOf(glm::min(a, glm::min(b, c))), last = cellOf(glm::max(a, glm::max(b, c)));
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x) f((size_t(z) * cells_.y + y) * cells_.x + x);
    };
    for (size_t t = 0; t < triangles; ++t) forCells(t, [&](size_t cell) { ++counts[cell + 1]; });
    for (size_t i = 1; i < counts.size(); ++i) counts[i] += counts[i - 1];
    cellStart_ = counts;
    cellTriangles_.resize(counts.back());
    for (size_t t = 0; t < triangles; ++t) forCells(t, [&](size_t cell) { cellTriangles_[counts[cell]++] = uint32_t(t); });
}

glm::ivec3 TriangleGrid::cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - origin_) / cell_)), glm::ivec3(0), cells_ - 1);
}

float TriangleGrid::nearestIn(const glm::vec3& p, glm::ivec3 lo, glm::ivec3 hi, float limit) const {
    float nearest = limit;
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                const size_t cell = (size_t(z) * cells_.y + y) * cells_.x + x;
                for (uint32_t i = cellStart_[cell]; i < cellStart_[cell + 1]; ++i) {
                    const uint32_t t = cellTriangles_[i];
                    nearest = std::min(nearest, pointTriangleDistance(p, positions_[indices_[t * 3]], positions_[indices_[t * 3 + 1]],
                                                                      positions_[indices_[t * 3 + 2]]));
                }
            }
    return nearest;
}

float TriangleGrid::distance(const glm::vec3& p) const {
    if (cellTriangles_.empty()) return 0.0f;
    // Every triangle within r of p has its box in the cells of p's box grown by r: widen r until one is.
    for (float r = cell_;; r *= 2.0f) {
        const glm::ivec3 lo = cellOf(p - r), hi = cellOf(p + r);
        const float nearest = nearestIn(p, lo, hi, INFINITY);
        const bool wholeGrid = lo == glm::ivec3(0) && hi == cells_ - 1;
        if (nearest <= r || wholeGrid) return nearest;
    }
}

}  // namespace penumbra
