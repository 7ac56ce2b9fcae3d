#pragma once
// Meshlets: a mesh's triangles split into small groups of neighbours (meshoptimizer's meshlet
// builder), each with the bounds that let a compute rasterizer skip it whole (render.meshletCulling): its
// object-space box and its normal cone (apex, axis, cutoff: every triangle faces away from an eye
// for which dot(normalize(apex - eye), axis) >= cutoff; meshopt_computeClusterBounds). CPU only.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

struct Meshlet {
    uint32_t firstTriangle = 0;  // in MeshletMesh::indices / 3
    uint32_t triangleCount = 0;
    glm::vec3 osMin{0.0f}, osMax{0.0f};
    glm::vec3 coneApex{0.0f}, coneAxis{0.0f, 0.0f, 1.0f};
    float coneCutoff = 1.0f;  // >= 1: the normals spread too far for a cone test
};

struct MeshletMesh {
    std::vector<uint32_t> indices;  // the mesh's triangles, meshlet by meshlet, each with its own winding
    std::vector<Meshlet> meshlets;
};

// Splits `mesh` into meshlets of at most `maxTriangles` triangles (a multiple of 4, <= 512) and
// reorders its triangles so that each meshlet's are consecutive. Every triangle is kept once, with its
// vertices in the same cyclic order (degenerate ones in a meshlet of their own at the end).
MeshletMesh buildMeshlets(const Mesh& mesh, uint32_t maxTriangles);

}  // namespace penumbra
