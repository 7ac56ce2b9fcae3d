#include "scene/meshlets.h"

#include <algorithm>
#include <limits>

#include <meshoptimizer.h>

#include "core/error.h"

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

}  // namespace

MeshletMesh buildMeshlets(const Mesh& mesh, uint32_t maxTriangles) {
    PENUMBRA_ASSERT(maxTriangles % 4 == 0 && maxTriangles > 0 && maxTriangles <= 512);
    MeshletMesh out;
    if (mesh.indices.size() < 3 || mesh.vertices.empty()) return out;
    // meshoptimizer skips nothing, but a triangle with a repeated vertex has no normal: keep those apart
    // so they widen no cone (they draw nothing either way).
    std::vector<uint32_t> proper, degenerates;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        std::vector<uint32_t>& list = degenerate(&mesh.indices[i]) ? degenerates : proper;
        list.insert(list.end(), mesh.indices.begin() + i, mesh.indices.begin() + i + 3);
    }
    const size_t bound = meshopt_buildMeshletsBound(proper.size(), kMaxMeshletVertices, maxTriangles);
    std::vector<meshopt_Meshlet> meshlets(bound);
    std::vector<unsigned int> meshletVertices(bound * kMaxMeshletVertices);
    std::vector<unsigned char> meshletTriangles(bound * maxTriangles * 3);
    const size_t count = proper.empty() ? 0
                                        : meshopt_buildMeshlets(meshlets.data(), meshletVertices.data(), meshletTriangles.data(),
                                                                proper.data(), proper.size(), &mesh.vertices[0].osPosition.x,
                                                                mesh.vertices.size(), sizeof(Vertex), kMaxMeshletVertices,
                                                                maxTriangles, kConeWeight);
    out.indices.reserve(mesh.indices.size());
    for (size_t m = 0; m < count; ++m) {
        const meshopt_Meshlet& meshlet = meshlets[m];
        const size_t first = out.indices.size();
        for (size_t i = 0; i < size_t(meshlet.triangle_count) * 3; ++i)
            out.indices.push_back(meshletVertices[meshlet.vertex_offset + meshletTriangles[meshlet.triangle_offset + i]]);
        appendMeshlet(mesh, out, first);
    }
    for (size_t first = 0; first < degenerates.size(); first += size_t(maxTriangles) * 3) {
        const size_t start = out.indices.size();
        const size_t end = std::min(degenerates.size(), first + size_t(maxTriangles) * 3);
        out.indices.insert(out.indices.end(), degenerates.begin() + first, degenerates.begin() + end);
        appendMeshlet(mesh, out, start);
        out.meshlets.back().coneCutoff = 1.0f;
    }
    PENUMBRA_ASSERT(out.indices.size() == mesh.indices.size() / 3 * 3);
    return out;
}

}  // namespace penumbra
