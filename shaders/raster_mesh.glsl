// What both compute rasterizers (shadow_raster.glsl, visibility_raster.glsl) read of the scene's
// meshes and share of their queues: the work items of pass 1 (every mesh slot's instances x meshlets,
// CullMesh.counts), the meshlets, the queue of large pieces (pass 2) and of their chunks (pass 3).
#ifndef PENUMBRA_RASTER_MESH_GLSL
#define PENUMBRA_RASTER_MESH_GLSL
#include "pass_bindings.h"
#include "cull_structs.h"
#include "meshlet_culling.glsl"
#include "raster_core.glsl"

layout(set = kPassSet, binding = kRasterBindingMeshes, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = kPassSet, binding = kRasterBindingIndices, std430) readonly buffer IndexBlock { uint indices[]; };
layout(set = kPassSet, binding = kRasterBindingCounters, std430) buffer CounterBlock { RasterCounters counters; };
layout(set = kPassSet, binding = kRasterBindingLargePieces, std430) buffer LargeBlock { RasterPiece largePieces[]; };
layout(set = kPassSet, binding = kRasterBindingChunks, std430) buffer ChunkBlock { uvec2 chunks[]; };  // (large piece, chunk x | y << 16)
layout(set = kPassSet, binding = kRasterBindingMeshlets, std430) readonly buffer MeshletBlock { Meshlet meshlets[]; };

// Both rasterizers' constants have largeCapacity and chunkCapacity (the queues' sizes).
#ifdef PENUMBRA_VIEW_RASTER
#include "visibility_structs.h"
layout(push_constant) uniform RasterBlock { VisibilityConstants raster; };
#else
layout(push_constant) uniform RasterBlock { ShadowRasterConstants raster; };
#endif

// The mesh slot whose run holds `index`, in mesh order: its work items (instances x meshlets:
// firstRasterItem) or, with listSlots, its slots of a culled list (firstListSlot); both are prefix sums.
uint meshOfRun(uint index, uint meshCount, bool listSlots) {
    uint lo = 0u, hi = meshCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) / 2u;
        if ((listSlots ? cullMeshes[mid].firstListSlot : cullMeshes[mid].firstRasterItem) <= index) lo = mid;
        else hi = mid - 1u;
    }
    return lo;
}

RasterVertex casterVertex(uint vertexIndex, mat4 clipFromObject) {
    VertexData vertex = vertices[vertexIndex];
    RasterVertex v;
    v.clip = clipFromObject * vec4(vertex.osPosition, 1.0);
    v.uv = vec2(vertex.u, vertex.v);
    return v;
}

// Fetches triangle `triangle` of `mesh` in the tile's clip space (clipFromObject = the tile's
// clipFromWorld x the instance's worldFromObject).
void fetchTriangle(CullMesh mesh, uint triangle, mat4 clipFromObject, out RasterVertex v[3]) {
    for (int i = 0; i < 3; ++i) {
        uint index = indices[mesh.firstIndex + triangle * 3u + uint(i)];
        v[i] = casterVertex(uint(int(index) + mesh.vertexOffset), clipFromObject);
    }
}

RasterPiece packPiece(RasterTriangleSetup t, float slopeBias) {
    RasterPiece piece;
    piece.points01 = ivec4(t.p[0], t.p[1]);
    piece.point2 = ivec4(t.p[2], int(t.materialIndex), t.alphaTested ? 1 : 0);
    piece.depth = vec4(t.z, t.area);
    piece.inverseW = vec4(t.invW, slopeBias);
    piece.uvOverW01 = vec4(t.uvOverW[0], t.uvOverW[1]);
    piece.uvOverW2Slope = vec4(t.uvOverW[2], t.depthSlope);
    piece.bounds = t.bounds;
    return piece;
}

RasterTriangleSetup unpackPiece(RasterPiece piece) {
    RasterTriangleSetup t;
    t.p[0] = piece.points01.xy;
    t.p[1] = piece.points01.zw;
    t.p[2] = piece.point2.xy;
    t.materialIndex = uint(piece.point2.z);
    t.alphaTested = piece.point2.w != 0;
    t.z = piece.depth.xyz;
    t.area = piece.depth.w;
    t.invW = piece.inverseW.xyz;
    t.uvOverW[0] = piece.uvOverW01.xy;
    t.uvOverW[1] = piece.uvOverW01.zw;
    t.uvOverW[2] = piece.uvOverW2Slope.xy;
    t.depthSlope = piece.uvOverW2Slope.zw;
    t.bounds = piece.bounds;
    return t;
}

#endif
