#include "scene/meshlets.h"

#include <algorithm>
#include <limits>
#include <utility>

#include <meshoptimizer.h>

#include "core/error.h"
#include "scene/surface_distance.h"

namespace penumbra {

namespace {

// meshoptimizer's limit on a meshlet's vertices (255, "not 256"): with it the triangle count binds
// first on all but the most fragmented meshes.
constexpr size_t kMaxMeshletVertices = 255;
// How much the builder favours meshlets whose normals agree (tighter cones, more meshlets facing away)
// over full ones; meshoptimizer suggests 0.25 for cone culling.
constexpr float kConeWeight = 0.25f;

bool degenerate(const uint32_t* t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

void appendMeshlet(const Mesh& mesh, MeshletMesh& out, size_t firstIndex) {
    const size_t indexCount = out.indices.size() - firstIndex;
    if (indexCount == 0) return;
    Meshlet meshlet;
    meshlet.firstTriangle = uint32_t(firstIndex / 3);
    meshlet.triangleCount = uint32_t(indexCount / 3);
    meshlet.osMin = glm::vec3(std::numeric_limits<float>::max());
    meshlet.osMax = glm::vec3(-std::numeric_limits<float>::max());
    for (size_t i = firstIndex; i < out.indices.size(); ++i) {
        meshlet.osMin = glm::min(meshlet.osMin, mesh.vertices[out.indices[i]].osPosition);
        meshlet.osMax = glm::max(meshlet.osMax, mesh.vertices[out.indices[i]].osPosition);
    }
    const meshopt_Bounds bounds = meshopt_computeClusterBounds(out.indices.data() + firstIndex, indexCount,
                                                               &mesh.vertices[0].osPosition.x, mesh.vertices.size(),
                                                               sizeof(Vertex));
    meshlet.coneApex = glm::vec3(bounds.cone_apex[0], bounds.cone_apex[1], bounds.cone_apex[2]);
    meshlet.coneAxis = glm::vec3(bounds.cone_axis[0], bounds.cone_axis[1], bounds.cone_axis[2]);
    meshlet.coneCutoff = bounds.cone_cutoff;
    out.meshlets.push_back(meshlet);
}

// Appends `triangles` (none degenerate) to `out` as meshlets of at most `maxTriangles`.
void appendMeshlets(const Mesh& mesh, const std::vector<uint32_t>& triangles, uint32_t maxTriangles, MeshletMesh& out) {
    if (triangles.empty()) return;
    const size_t bound = meshopt_buildMeshletsBound(triangles.size(), kMaxMeshletVertices, maxTriangles);
    std::vector<meshopt_Meshlet> meshlets(bound);
    std::vector<unsigned int> meshletVertices(bound * kMaxMeshletVertices);
    std::vector<unsigned char> meshletTriangles(bound * maxTriangles * 3);
    const size_t count = meshopt_buildMeshlets(meshlets.data(), meshletVertices.data(), meshletTriangles.data(),
                                               triangles.data(), triangles.size(), &mesh.vertices[0].osPosition.x,
                                               mesh.vertices.size(), sizeof(Vertex), kMaxMeshletVertices, maxTriangles,
                                               kConeWeight);
    for (size_t m = 0; m < count; ++m) {
        const meshopt_Meshlet& meshlet = meshlets[m];
        const size_t first = out.indices.size();
        for (size_t i = 0; i < size_t(meshlet.triangle_count) * 3; ++i)
            out.indices.push_back(meshletVertices[meshlet.vertex_offset + meshletTriangles[meshlet.triangle_offset + i]]);
        appendMeshlet(mesh, out, first);
    }
}

// `indices` without its degenerate triangles.
std::vector<uint32_t> properTriangles(const std::vector<uint32_t>& indices) {
    std::vector<uint32_t> proper;
    for (size_t i = 0; i + 2 < indices.size(); i += 3)
        if (!degenerate(&indices[i])) proper.insert(proper.end(), indices.begin() + i, indices.begin() + i + 3);
    return proper;
}

// One simplified level of `welded` (positions shared) with at most about `targetIndices`.
std::vector<uint32_t> simplifiedLevel(const Mesh& mesh, const std::vector<uint32_t>& welded, size_t targetIndices) {
    const float* positions = &mesh.vertices[0].osPosition.x;
    std::vector<uint32_t> level(welded.size());
    level.resize(meshopt_simplify(level.data(), welded.data(), welded.size(), positions, mesh.vertices.size(),
                                  sizeof(Vertex), targetIndices, 1.0f, 0, nullptr));
    if (level.size() > targetIndices * 2) {  // edge collapses stalled (many small parts): cluster vertices
        std::vector<uint32_t> sloppy(welded.size());
        sloppy.resize(meshopt_simplifySloppy(sloppy.data(), welded.data(), welded.size(), positions,
                                             mesh.vertices.size(), sizeof(Vertex), targetIndices, 1.0f, nullptr));
        if (!sloppy.empty() && sloppy.size() < level.size()) level.swap(sloppy);
    }
    return properTriangles(level);
}

// The full mesh as the levels are measured against: its positions, the vertices its triangles use (each
// once) and the grid of its triangles, made once for all the levels.
struct FullSurface {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> vertices;
    TriangleGrid grid;
    FullSurface(std::vector<glm::vec3> p, const std::vector<uint32_t>& triangles)
        : positions(std::move(p)), vertices(usedVertices(triangles, positions.size())), grid(positions, triangles) {}
    FullSurface(const FullSurface&) = delete;  // the grid points into positions
    static std::vector<uint32_t> usedVertices(const std::vector<uint32_t>& triangles, size_t vertexCount) {
        std::vector<bool> used(vertexCount, false);
        for (uint32_t i : triangles) used[i] = true;
        std::vector<uint32_t> list;
        for (uint32_t i = 0; i < vertexCount; ++i)
            if (used[i]) list.push_back(i);
        return list;
    }
};

// How far the two surfaces lie apart, measured both ways: every vertex of the full mesh from the level,
// and the corners, edge midpoints and centre of every triangle of the level from the full mesh.
// (meshoptimizer's own error estimate is a quadric's: on a sphere the true distance is 2-2.5 times it.)
float measuredError(const FullSurface& full, const std::vector<uint32_t>& level) {
    const std::vector<glm::vec3>& positions = full.positions;
    const TriangleGrid levelGrid(positions, level);
    float error = 0.0f;
    for (uint32_t i : full.vertices) error = std::max(error, levelGrid.distance(positions[i]));
    const TriangleGrid& fullGrid = full.grid;
    for (size_t t = 0; t + 2 < level.size(); t += 3) {
        const glm::vec3 &a = positions[level[t]], &b = positions[level[t + 1]], &c = positions[level[t + 2]];
        for (const glm::vec3& p : {0.5f * (a + b), 0.5f * (b + c), 0.5f * (c + a), (a + b + c) / 3.0f})
            error = std::max(error, fullGrid.distance(p));
    }
    return error;
}

}  // namespace

MeshletMesh buildMeshlets(const Mesh& mesh, uint32_t maxTriangles) {
    PENUMBRA_ASSERT(maxTriangles % 4 == 0 && maxTriangles > 0 && maxTriangles <= 512);
    MeshletMesh out;
    if (mesh.indices.size() < 3 || mesh.vertices.empty()) return out;
    // meshoptimizer skips nothing, but a triangle with a repeated vertex has no normal: keep those apart
    // so they widen no cone (they draw nothing either way).
    std::vector<uint32_t> degenerates;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        if (degenerate(&mesh.indices[i])) degenerates.insert(degenerates.end(), mesh.indices.begin() + i, mesh.indices.begin() + i + 3);
    out.indices.reserve(mesh.indices.size());
    appendMeshlets(mesh, properTriangles(mesh.indices), maxTriangles, out);
    for (size_t first = 0; first < degenerates.size(); first += size_t(maxTriangles) * 3) {
        const size_t start = out.indices.size();
        const size_t end = std::min(degenerates.size(), first + size_t(maxTriangles) * 3);
        out.indices.insert(out.indices.end(), degenerates.begin() + first, degenerates.begin() + end);
        appendMeshlet(mesh, out, start);
        out.meshlets.back().coneCutoff = 1.0f;
    }
    PENUMBRA_ASSERT(out.indices.size() == mesh.indices.size() / 3 * 3);
    out.fullIndexCount = uint32_t(out.indices.size());
    return out;
}

void addShadowLods(const Mesh& mesh, uint32_t maxTriangles, uint32_t maxLevels, MeshletMesh& out) {
    const size_t fullTriangles = mesh.indices.size() / 3;
    if (out.meshlets.size() < 2 || !out.lods.empty()) return;  // one meshlet is one work item at any level
    std::vector<uint32_t> welded(mesh.indices.size());
    meshopt_generateShadowIndexBuffer(welded.data(), mesh.indices.data(), mesh.indices.size(), &mesh.vertices[0].osPosition.x,
                                      mesh.vertices.size(), sizeof(glm::vec3), sizeof(Vertex));
    welded = properTriangles(welded);
    std::vector<glm::vec3> positions(mesh.vertices.size());
    for (size_t i = 0; i < positions.size(); ++i) positions[i] = mesh.vertices[i].osPosition;
    const FullSurface full(std::move(positions), welded);
    size_t previous = fullTriangles;
    for (uint32_t level = 0; level < maxLevels; ++level) {
        const std::vector<uint32_t> triangles = simplifiedLevel(mesh, welded, previous / 4 * 3);
        if (triangles.empty() || float(triangles.size() / 3) > kLodKeepAtMost * float(previous)) return;
        MeshletLod lod;
        lod.firstMeshlet = uint32_t(out.meshlets.size());
        lod.triangleCount = uint32_t(triangles.size() / 3);
        lod.osError = std::max(measuredError(full, triangles), out.lods.empty() ? 0.0f : out.lods.back().osError);
        appendMeshlets(mesh, triangles, maxTriangles, out);
        lod.meshletCount = uint32_t(out.meshlets.size()) - lod.firstMeshlet;
        out.lods.push_back(lod);
        previous = lod.triangleCount;
    }
}

}  // namespace penumbra
