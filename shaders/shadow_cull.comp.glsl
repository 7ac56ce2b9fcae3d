#version 460
// GPU shadow-caster culling (cull_structs.h): one invocation per (instance, tile). The tests are the CPU
// planner's, operation for operation: the cascade's caster box, cascade blend culling (after Unity's
// per-split culling) and receiver culling (shadows/caster_culling.cpp) for directional tiles, the frustum planes and
// bounds (shadows/spot_culling.cpp) for spot and point faces. Survivors are appended to their (tile, mesh)
// list. The main view's two phases (cull_structs.h) use the same lists after the tiles': the camera frustum,
// then occlusion by the depth pyramid of what the early list drew.
#extension GL_KHR_shader_subgroup_ballot : require
#include "pass_bindings.h"
#include "cull_structs.h"
#include "scene_structs.h"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kCullBindingFrame, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = kPassSet, binding = kCullBindingInstances, std430) readonly buffer CullInstanceBlock { CullInstance cullInstances[]; };
layout(set = kPassSet, binding = kCullBindingMeshes, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = kPassSet, binding = kCullBindingMaterials, std430) readonly buffer MaterialBlock { MaterialData materials[]; };
layout(set = kPassSet, binding = kCullBindingListCounts, std430) buffer ListCountBlock { uint listCounts[]; };  // [tile * meshes + mesh]
layout(set = kPassSet, binding = kCullBindingVisibleInstances, std430) writeonly buffer VisibleBlock { uint entries[]; }
    visibleLists[kVisibleListBuffers];  // cull_structs.h: the lists split over buffers
layout(set = kPassSet, binding = kCullBindingViewHistory, std430) buffer ViewHistoryBlock { uint viewHistory[]; };  // kView* bits per instance
layout(set = kPassSet, binding = kCullBindingPyramid, std430) readonly buffer PyramidBlock { float pyramid[]; };
layout(set = kPassSet, binding = kCullBindingTileStats, std430) buffer TileStatsBlock { CullTileStats tileStats[]; };
// The tiles (CPU- or GPU-written, cull_structs.h); the shadow dispatch is tileList.cullDispatch.
layout(set = kPassSet, binding = kCullBindingTiles, std430) readonly buffer CullTileBlock {
    CullTileListHeader tileList;
    CullTile tiles[];
};
layout(push_constant) uniform CullConstantsBlock { CullConstants constants; };

// Cascade blend culling (caster_culling.cpp insideScaledSphere): the box wholly inside the scaled sphere.
bool insideScaledSphere(vec3 wsMin, vec3 wsMax, vec4 sphere, float factor) {
    vec3 farthest = max(abs(wsMin - sphere.xyz), abs(wsMax - sphere.xyz));
    float radius = sphere.w * factor;
    return dot(farthest, farthest) <= radius * radius;
}

// caster_culling.cpp shadowOnReceiver with the receivers' common bounds: the box the caster's shadow can
// reach on them, false when it reaches none.
bool shadowOnReceivers(vec3 casterMin, vec3 casterMax, vec3 direction, out vec3 clippedMin, out vec3 clippedMax) {
    vec3 receiverMin = cull.wsReceiverMin.xyz, receiverMax = cull.wsReceiverMax.xyz;
    clippedMin = vec3(0.0);
    clippedMax = vec3(0.0);
    float t0 = 0.0, t1 = uintBitsToFloat(0x7f800000u);  // +infinity
    for (int axis = 0; axis < 3; ++axis) {
        float d = direction[axis];
        if (abs(d) < 1e-12) {
            if (casterMin[axis] > receiverMax[axis] || casterMax[axis] < receiverMin[axis]) return false;
            continue;
        }
        float enter = (receiverMin[axis] - casterMax[axis]) / d;
        float leave = (receiverMax[axis] - casterMin[axis]) / d;
        if (enter > leave) { float swap = enter; enter = leave; leave = swap; }
        t0 = max(t0, enter);
        t1 = min(t1, leave);
    }
    if (!(t0 <= t1)) return false;
    vec3 sweptMin = min(casterMin + t0 * direction, casterMin + t1 * direction);
    sweptMin = min(sweptMin, min(casterMax + t0 * direction, casterMax + t1 * direction));
    vec3 sweptMax = max(casterMin + t0 * direction, casterMin + t1 * direction);
    sweptMax = max(sweptMax, max(casterMax + t0 * direction, casterMax + t1 * direction));
    clippedMin = max(sweptMin, receiverMin);
    clippedMax = min(sweptMax, receiverMax);
    return all(lessThanEqual(clippedMin, clippedMax));
}

// caster_culling.cpp shadowInsideScaledSphere: everything the caster's shadow can reach lies inside the scaled sphere.
bool shadowInsideScaledSphere(vec3 casterMin, vec3 casterMax, vec3 direction, vec4 sphere, float factor) {
    vec3 shadowMin, shadowMax;
    return !shadowOnReceivers(casterMin, casterMax, direction, shadowMin, shadowMax) ||
           insideScaledSphere(shadowMin, shadowMax, sphere, factor);
}

// The box corner farthest along `normal` (spot_culling.cpp farthestCorner).
vec3 farthestCorner(vec3 boxMin, vec3 boxMax, vec3 normal) {
    return vec3(normal.x >= 0.0 ? boxMax.x : boxMin.x, normal.y >= 0.0 ? boxMax.y : boxMin.y, normal.z >= 0.0 ? boxMax.z : boxMin.z);
}

// caster_culling.cpp shadowMeetsReceiverVolume: the caster grown by the lookups' reach, swept over the
// receivers, meets the camera's sides, the cascade's depth range and its culling sphere (if any).
bool shadowMeetsReceiverVolume(CullTile tile, vec3 casterMin, vec3 casterMax) {
    float reach = tile.receiverDepth.z;
    vec3 boxMin, boxMax;
    if (!shadowOnReceivers(casterMin - reach, casterMax + reach, tile.wsLightDirection.xyz, boxMin, boxMax)) return false;
    for (int i = 0; i < 4; ++i) {
        vec4 plane = tile.planes[i];
        if (dot(plane.xyz, farthestCorner(boxMin, boxMax, plane.xyz)) + plane.w < 0.0) return false;
    }
    vec4 depthPlane = tile.planes[4];
    float deepest = dot(depthPlane.xyz, farthestCorner(boxMin, boxMax, depthPlane.xyz)) + depthPlane.w;
    float shallowest = dot(depthPlane.xyz, farthestCorner(boxMin, boxMax, -depthPlane.xyz)) + depthPlane.w;
    if (deepest < tile.receiverDepth.x || shallowest > tile.receiverDepth.y) return false;
    vec4 sphere = tile.receiverSphere;
    if (sphere.w < 0.0) return true;
    vec3 closest = clamp(sphere.xyz, boxMin, boxMax);
    return dot(closest - sphere.xyz, closest - sphere.xyz) <= sphere.w * sphere.w;
}

// caster_culling.cpp cullTileCasters for one caster and cascade.
bool directionalKeeps(CullTile tile, vec3 wsMin, vec3 wsMax) {
    mat3 rotation = mat3(tile.lightFromWorld);
    mat3 absRotation = mat3(abs(rotation[0]), abs(rotation[1]), abs(rotation[2]));
    vec3 center = rotation * (0.5 * (wsMin + wsMax));
    vec3 halfExtent = absRotation * (0.5 * (wsMax - wsMin));
    vec3 translation = tile.lightFromWorld[3].xyz;
    vec3 lsMin = (center - halfExtent) + translation, lsMax = (center + halfExtent) + translation;
    float h = tile.halfExtent, farDistance = tile.farDistance;
    if (!(lsMax.z >= -farDistance && lsMin.x <= h && lsMax.x >= -h && lsMin.y <= h && lsMax.y >= -h)) return false;
    float factor = tile.blendCullingFactor;
    int cascade = int(tile.cascadeIndex);
    for (int j = 0; j < cascade && factor > 0.0; ++j) {
        if (insideScaledSphere(wsMin, wsMax, cull.spheres[j], factor) &&
            shadowInsideScaledSphere(wsMin, wsMax, tile.wsLightDirection.xyz, cull.spheres[j], factor))
            return false;  // a smaller cascade holds the caster and all of its shadow
    }
    return tile.receiverDepth.w == 0.0 || shadowMeetsReceiverVolume(tile, wsMin, wsMax);
}

// spot_culling.cpp frustumCasters for one caster and tile.
bool perspectiveKeeps(CullTile tile, vec3 wsMin, vec3 wsMax) {
    if (any(greaterThan(wsMin, tile.frustumMax.xyz)) || any(lessThan(wsMax, tile.frustumMin.xyz))) return false;
    for (int i = 0; i < 5; ++i) {
        vec4 plane = tile.planes[i];
        if (dot(plane.xyz, farthestCorner(wsMin, wsMax, plane.xyz)) + plane.w < 0.0) return false;
    }
    return true;
}

// ---- the main view

// The 8 corners of a world box in the camera's clip space (both tests below read them).
void cameraClipCorners(vec3 wsMin, vec3 wsMax, out vec4 corners[8]) {
    for (int i = 0; i < 8; ++i)
        corners[i] = cull.camera.clipFromWorld * vec4((i & 1) != 0 ? wsMax.x : wsMin.x, (i & 2) != 0 ? wsMax.y : wsMin.y,
                                                      (i & 4) != 0 ? wsMax.z : wsMin.z, 1.0);
}

// Where the box lies on screen, if it lies wholly beyond the near plane: the pixel rectangle
// (inclusive) of its projected corners and the nearest (largest, reversed Z) depth of any of them.
bool projectBox(vec4 corners[8], out ivec4 pixels, out float nearestDepth) {
    vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
    nearestDepth = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec4 clip = corners[i];
        if (!(clip.w > 0.0) || clip.z > clip.w) return false;  // a corner before the near plane
        ndcMin = min(ndcMin, clip.xy / clip.w);
        ndcMax = max(ndcMax, clip.xy / clip.w);
        nearestDepth = max(nearestDepth, clip.z / clip.w);
    }
    vec2 size = vec2(cull.camera.width, cull.camera.height);
    // Window coordinates as the rasterizer's (raster_core.glsl setupTriangle); a pixel is covered when
    // its centre is, so every pixel the box can cover lies in floor(min) .. floor(max).
    vec2 windowMin = clamp((ndcMin * 0.5 + 0.5) * size, vec2(0.0), size - 1.0);
    vec2 windowMax = clamp((ndcMax * 0.5 + 0.5) * size, vec2(0.0), size - 1.0);
    pixels = ivec4(floor(windowMin), floor(windowMax));
    return true;
}

float pyramidTexel(uint level, ivec2 texel) {
    uvec2 size = uvec2(cull.camera.pyramidWidth, cull.camera.pyramidHeight);
    uint offset = 0u;
    for (uint l = 0u; l < level; ++l) {
        offset += size.x * size.y;
        size = (size + 1u) / 2u;
    }
    texel = min(texel, ivec2(size) - 1);
    return pyramid[offset + uint(texel.y) * size.x + uint(texel.x)];
}

// Whether what the early list drew hides the whole box: at the pyramid level where the box's pixel
// rectangle spans at most 2 x 2 texels, the farthest depth there is nearer than the box's nearest.
// (Those texels cover the rectangle: texel x of level L covers pixels x * 2^(L+1) .. + 2^(L+1) - 1.)
bool occluded(vec4 corners[8]) {
    ivec4 pixels;
    float nearestDepth;
    if (!projectBox(corners, pixels, nearestDepth)) return false;
    uint level = 0u;
    while (level + 1u < cull.camera.pyramidLevels &&
           any(greaterThan((pixels.zw >> int(level + 1u)) - (pixels.xy >> int(level + 1u)), ivec2(1))))
        ++level;
    ivec4 texels = pixels >> int(level + 1u);
    float farthest = min(min(pyramidTexel(level, texels.xy), pyramidTexel(level, texels.zy)),
                         min(pyramidTexel(level, texels.xw), pyramidTexel(level, texels.zw)));
    // A margin of 1e-4 of the depth: a surface drawn early stays visible through its own bounds
    // (whose front face may round a little behind the rasterized depth of the same plane).
    return nearestDepth * 1.0001 < farthest;
}

// The visibility rasterizer's frustum test (0 <= z <= w, |x|, |y| <= w): no plane has all 8 corners outside.
bool boxInCameraFrustum(vec4 corners[8]) {
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

// Appends `instance` to its mesh's part of list `list` (a tile's or the main view's); the list is the
// same for the whole workgroup, as indexing the buffer array needs. The invocations of a subgroup that
// append to one mesh share one atomic (a million boxes of one mesh would otherwise queue a million
// atomics on one counter): each round takes the mesh of the first invocation still pending. With
// `countStats`, the list's instance and triangle counts grow the same way.
void appendToList(uint list, uint instance, CullMesh mesh, uint meshSlot, bool countStats) {
    uint listsPerBuffer = constants.listsPerBuffer;
    for (bool pending = true; pending;) {
        if (meshSlot != subgroupBroadcastFirst(meshSlot)) continue;
        uvec4 sharing = subgroupBallot(true);
        uint count = subgroupBallotBitCount(sharing), first = 0u;
        if (subgroupElect()) {
            first = atomicAdd(listCounts[list * cull.meshCount + meshSlot], count);
            if (countStats) {
                atomicAdd(tileStats[list].instances, count);
                atomicAdd(tileStats[list].triangles, count * (mesh.indexCount / 3u));
            }
        }
        uint slot = subgroupBroadcastFirst(first) + subgroupBallotExclusiveBitCount(sharing);
        visibleLists[visibleListBuffer(list, listsPerBuffer)]
            .entries[visibleListStart(list, listsPerBuffer, cull.instanceCount) + mesh.firstListSlot + slot] = instance;
        pending = false;
    }
}

void appendToView(uint list, uint instance, CullMesh mesh, uint meshSlot) { appendToList(list, instance, mesh, meshSlot, true); }

// The early phase: the frustum's instances visible last frame (every one in frustum without
// occlusion culling, every one without it at all); the late phase: the frustum's instances the
// pyramid does not hide, less those drawn early. Unbounded instances are always drawn early.
void cullCamera(uint instance) {
    CullInstance candidate = cullInstances[instance];
    if ((candidate.flags & kCullInstanceHasMesh) == 0u) return;
    uint meshSlot = candidate.meshSlot;
    CullMesh mesh = cullMeshes[meshSlot];
    if (materials[mesh.materialIndex].alphaMode == kAlphaBlend) return;  // the forward pass draws them afterwards
    uint culling = cull.camera.culling;
    bool bounded = (candidate.flags & kCullInstanceBounded) != 0u;
    vec4 corners[8];
    cameraClipCorners(candidate.wsMin.xyz, candidate.wsMax.xyz, corners);
    bool inFrustum = culling == kViewCullingNone || !bounded || boxInCameraFrustum(corners);
    uint history = viewHistory[instance];
    if (constants.pass == kCullPassCameraEarly) {
        bool early = inFrustum && (culling != kViewCullingOcclusion || !bounded || (history & kViewVisible) != 0u);
        viewHistory[instance] = (history & kViewVisible) | (early ? kViewDrawnEarly : 0u);
        if (early) appendToView(kCullListCameraEarly, instance, mesh, meshSlot);
        return;
    }
    bool visible = inFrustum && (!bounded || !occluded(corners));
    viewHistory[instance] = visible ? kViewVisible : 0u;
    if (visible && (history & kViewDrawnEarly) == 0u) appendToView(kCullListCameraLate, instance, mesh, meshSlot);
}

void main() {
    if (constants.pass != kCullPassShadows) {
        if (gl_GlobalInvocationID.x < cull.instanceCount) cullCamera(gl_GlobalInvocationID.x);
        return;
    }
    uint instance = gl_GlobalInvocationID.x;
    uint tileIndex = gl_WorkGroupID.y;
    if (instance >= cull.instanceCount || tileIndex >= tileList.count) return;
    CullInstance caster = cullInstances[instance];
    if ((caster.flags & kCullInstanceCasts) == 0u) return;
    CullMesh mesh = cullMeshes[caster.meshSlot];
    if (materials[mesh.materialIndex].shadowMode == kShadowModeOff) return;
    CullTile tile = tiles[tileIndex];
    bool keep = tile.kind == kCullTileDirectional ? directionalKeeps(tile, caster.wsMin.xyz, caster.wsMax.xyz)
                                                               : perspectiveKeeps(tile, caster.wsMin.xyz, caster.wsMax.xyz);
    if (keep) appendToList(tileIndex, instance, mesh, caster.meshSlot, false);
}
