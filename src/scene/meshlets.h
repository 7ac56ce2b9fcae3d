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

// A simplified level of a mesh for the shadow rasterizer: its meshlets follow the full mesh's.
struct MeshletLod {
    uint32_t firstMeshlet = 0;  // in MeshletMesh::meshlets
    uint32_t meshletCount = 0;
    uint32_t triangleCount = 0;
    float osError = 0.0f;  // how far (object space) the level's surface may lie from the full mesh's
};

struct MeshletMesh {
    std::vector<uint32_t> indices;  // the mesh's triangles, meshlet by meshlet, each with its own winding
    std::vector<Meshlet> meshlets;
    uint32_t fullIndexCount = 0;     // indices of the full mesh; its simplified levels' follow
    std::vector<MeshletLod> lods;    // simplified levels, each coarser than the one before
};

// Splits `mesh` into meshlets of at most `maxTriangles` triangles (a multiple of 4, <= 512) and
// reorders its triangles so that each meshlet's are consecutive. Every triangle is kept once, with its
// vertices in the same cyclic order (degenerate ones in a meshlet of their own at the end).
MeshletMesh buildMeshlets(const Mesh& mesh, uint32_t maxTriangles);

// Appends up to `maxLevels` simplified levels of `mesh` to `out` (built by buildMeshlets), each with
// about a quarter of the triangles of the one before (meshoptimizer's edge-collapse simplifier on the
// positions alone, welded with meshopt_generateShadowIndexBuffer; its sloppy simplifier where edge
// collapses stall) and its error: how far its surface and the full mesh's lie apart, measured both ways
// (scene/surface_distance.h). A level that would keep
// more than kLodKeepAtMost of the one before ends the chain; a mesh of one meshlet gets none. The
// shadow rasterizer draws an instance with the coarsest level whose error is below a fraction of a texel
// (shadows.lodErrorTexels): the idea of Nanite's and every engine's error-bounded levels of detail.
constexpr float kLodKeepAtMost = 0.6f;
void addShadowLods(const Mesh& mesh, uint32_t maxTriangles, uint32_t maxLevels, MeshletMesh& out);

}  // namespace penumbra
