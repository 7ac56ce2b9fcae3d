#version 460
// Visibility rasterizer, pass 1 (visibility_raster.glsl): one workgroup per batch of kRasterBatch
// triangles of an instance (every instance with geometry, raster_mesh.glsl's work items); blended
// materials and instances outside the frustum leave at once. Small pieces are rasterized by their
// thread; large ones are queued, set up, for passes 2 and 3 (or rasterized here when the queue is full).
#include "visibility_raster.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = kBindingRasterInstances, std430) readonly buffer CullInstanceBlock { CullInstance cullInstances[]; };
layout(set = 0, binding = kBindingMeshInstances, std430) readonly buffer MeshInstanceBlock { uint meshInstances[]; };

shared mat4 clipFromObject;
shared bool instanceVisible;

// Whether the world box may show: no clip plane (x, y within w, 0 <= z <= w) has all 8 corners outside.
bool boxInFrustum(vec3 wsMin, vec3 wsMax) {
    vec4 corners[8];
    for (int i = 0; i < 8; ++i)
        corners[i] = frame.clipFromWorld * vec4((i & 1) != 0 ? wsMax.x : wsMin.x, (i & 2) != 0 ? wsMax.y : wsMin.y,
                                                (i & 4) != 0 ? wsMax.z : wsMin.z, 1.0);
    for (int plane = 0; plane < 6; ++plane) {
        bool allOutside = true;
        for (int i = 0; i < 8; ++i) {
            vec4 c = corners[i];
            float d = plane == 0 ? c.w - c.x : plane == 1 ? c.w + c.x : plane == 2 ? c.w - c.y
                    : plane == 3 ? c.w + c.y : plane == 4 ? c.w - c.z : c.z;
            allOutside = allOutside && d < 0.0;
        }
        if (allOutside) return false;
    }
    return true;
}

void rasterizeOrQueue(RasterTriangleSetup t, uint materialIndex, uint payload) {
    t.materialIndex = materialIndex;
    t.alphaTested = materials[materialIndex].flags.z == kAlphaMask;
    if (boundsArea(t.bounds) > kRasterSmallArea) {
        uint queued = atomicAdd(counters.counts.x, 1u);
        if (queued < raster.capacity.x) {
            largePieces[queued] = packViewPiece(t, payload);
            return;
        }
        atomicAdd(counters.counts.z, 1u);  // full: this thread draws it (slower, nothing lost)
    }
    rasterizePiece(t, payload);
}

void main() {
    uint item = gl_WorkGroupID.x + gl_WorkGroupID.y * kRasterDispatchWidth;
    uint meshSlot = meshOfWorkItem(item, raster.capacity.w);
    CullMesh mesh = cullMeshes[meshSlot];
    uint local = item - mesh.counts.z;
    if (mesh.counts.w == 0u || local >= mesh.counts.y * mesh.counts.w) return;  // past the last item
    uint instance = meshInstances[mesh.counts.x + local / mesh.counts.w], batch = local % mesh.counts.w;
    MaterialData material = materials[mesh.draw.w];
    if (material.flags.z == kAlphaBlend) return;  // drawn by the forward pass afterwards
    if (gl_LocalInvocationID.x == 0u) {
        clipFromObject = frame.clipFromWorld * instances[instance].worldFromObject;
        CullInstance bounds = cullInstances[instance];
        instanceVisible = (bounds.info.y & kCullInstanceBounded) == 0u || boxInFrustum(bounds.wsMin.xyz, bounds.wsMax.xyz);
    }
    barrier();
    if (!instanceVisible) return;
    bool doubleSided = (material.flags.y & kMaterialDoubleSided) != 0u;
    vec4 viewport = vec4(0.0, 0.0, float(viewWidth()), float(viewHeight()));
    uvec4 scissor = uvec4(0u, 0u, viewWidth(), viewHeight());
    uint lastTriangle = min((batch + 1u) * kRasterBatch, mesh.draw.x / 3u);
    for (uint triangle = batch * kRasterBatch + gl_LocalInvocationID.x; triangle < lastTriangle; triangle += 64u) {
        RasterVertex v[3];
        fetchTriangle(mesh, triangle, clipFromObject, v);
        if (!facesShown(v, doubleSided)) continue;
        uint payload = ((instance << raster.pass.z) | triangle) + 1u;
        RasterTriangleSetup t;
        if (!needsClipping(v, kViewClipPlanes)) {
            if (setupTriangle(viewport, scissor, v[0], v[1], v[2], t)) rasterizeOrQueue(t, mesh.draw.w, payload);
            continue;
        }
        RasterVertex polygon[kMaxClipped];
        int vertexCount = clipTriangle(v, kViewClipPlanes, polygon);
        for (int i = 1; i + 1 < vertexCount; ++i)
            if (setupTriangle(viewport, scissor, polygon[0], polygon[i], polygon[i + 1], t))
                rasterizeOrQueue(t, mesh.draw.w, payload);
    }
}
