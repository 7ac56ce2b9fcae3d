#version 460
// GPU shadow-caster culling (issue 10; cull_structs.h): one invocation per (instance, tile). The
// tests are the CPU planner's, operation for operation: the cascade's caster box and cascade blend
// culling (seed 000 §1.4, §4.9; shadows/caster_culling.cpp) for directional tiles, the frustum planes
// and bounds (shadows/spot_culling.cpp) for spot and point faces. Survivors are appended to their
// (tile, mesh) list.
#include "cull_structs.h"
#include "scene_structs.h"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std140) uniform CullFrameBlock { CullFrame cull; };
layout(set = 0, binding = 1, std430) readonly buffer CullInstanceBlock { CullInstance cullInstances[]; };
layout(set = 0, binding = 2, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = 0, binding = 3, std430) readonly buffer MaterialBlock { MaterialData materials[]; };
layout(set = 0, binding = 4, std430) buffer ListCountBlock { uint listCounts[]; };  // [tile * meshes + mesh]
layout(set = 0, binding = 5, std430) writeonly buffer VisibleBlock { uint visibleInstances[]; };

// seed 000 §4.9 (caster_culling.cpp insideScaledSphere): the box wholly inside the scaled sphere.
bool insideScaledSphere(vec3 wsMin, vec3 wsMax, vec4 sphere, float factor) {
    vec3 farthest = max(abs(wsMin - sphere.xyz), abs(wsMax - sphere.xyz));
    float radius = sphere.w * factor;
    return dot(farthest, farthest) <= radius * radius;
}

// caster_culling.cpp shadowOnReceiver + shadowInsideScaledSphere with the receivers' common bounds:
// everything the caster's shadow can reach lies inside the scaled sphere.
bool shadowInsideScaledSphere(vec3 casterMin, vec3 casterMax, vec3 direction, vec4 sphere, float factor) {
    vec3 receiverMin = cull.wsReceiverMin.xyz, receiverMax = cull.wsReceiverMax.xyz;
    float t0 = 0.0, t1 = uintBitsToFloat(0x7f800000u);  // +infinity
    for (int axis = 0; axis < 3; ++axis) {
        float d = direction[axis];
        if (abs(d) < 1e-12) {
            if (casterMin[axis] > receiverMax[axis] || casterMax[axis] < receiverMin[axis]) return true;  // no shadow there
            continue;
        }
        float enter = (receiverMin[axis] - casterMax[axis]) / d;
        float leave = (receiverMax[axis] - casterMin[axis]) / d;
        if (enter > leave) { float swap = enter; enter = leave; leave = swap; }
        t0 = max(t0, enter);
        t1 = min(t1, leave);
    }
    if (!(t0 <= t1)) return true;
    vec3 sweptMin = min(casterMin + t0 * direction, casterMin + t1 * direction);
    sweptMin = min(sweptMin, min(casterMax + t0 * direction, casterMax + t1 * direction));
    vec3 sweptMax = max(casterMin + t0 * direction, casterMin + t1 * direction);
    sweptMax = max(sweptMax, max(casterMax + t0 * direction, casterMax + t1 * direction));
    vec3 clippedMin = max(sweptMin, receiverMin), clippedMax = min(sweptMax, receiverMax);
    if (any(greaterThan(clippedMin, clippedMax))) return true;
    return insideScaledSphere(clippedMin, clippedMax, sphere, factor);
}

// caster_culling.cpp cullTileCasters for one caster and cascade.
bool directionalKeeps(CullTile tile, vec3 wsMin, vec3 wsMax) {
    mat3 rotation = mat3(tile.lightFromWorld);
    mat3 absRotation = mat3(abs(rotation[0]), abs(rotation[1]), abs(rotation[2]));
    vec3 center = rotation * (0.5 * (wsMin + wsMax));
    vec3 halfExtent = absRotation * (0.5 * (wsMax - wsMin));
    vec3 translation = tile.lightFromWorld[3].xyz;
    vec3 lsMin = (center - halfExtent) + translation, lsMax = (center + halfExtent) + translation;
    float h = tile.params.x, farDistance = tile.params.y;
    if (!(lsMax.z >= -farDistance && lsMin.x <= h && lsMax.x >= -h && lsMin.y <= h && lsMax.y >= -h)) return false;
    float factor = tile.params.w;
    int cascade = int(tile.params.z);
    for (int j = 0; j < cascade && factor > 0.0; ++j) {
        if (insideScaledSphere(wsMin, wsMax, cull.spheres[j], factor) &&
            shadowInsideScaledSphere(wsMin, wsMax, tile.wsLightDirection.xyz, cull.spheres[j], factor))
            return false;  // a smaller cascade holds the caster and all of its shadow
    }
    return true;
}

// spot_culling.cpp frustumCasters for one caster and tile.
bool perspectiveKeeps(CullTile tile, vec3 wsMin, vec3 wsMax) {
    if (any(greaterThan(wsMin, tile.frustumMax.xyz)) || any(lessThan(wsMax, tile.frustumMin.xyz))) return false;
    for (int i = 0; i < 5; ++i) {
        vec4 plane = tile.planes[i];
        vec3 corner = vec3(plane.x >= 0.0 ? wsMax.x : wsMin.x, plane.y >= 0.0 ? wsMax.y : wsMin.y,
                           plane.z >= 0.0 ? wsMax.z : wsMin.z);
        if (dot(plane.xyz, corner) + plane.w < 0.0) return false;
    }
    return true;
}

void main() {
    uint instance = gl_GlobalInvocationID.x;
    uint tileIndex = gl_WorkGroupID.y;
    uint instanceCount = cull.counts.y, meshCount = cull.counts.z;
    if (instance >= instanceCount || tileIndex >= cull.counts.x) return;
    CullInstance caster = cullInstances[instance];
    if ((caster.info.y & kCullInstanceCasts) == 0u) return;
    CullMesh mesh = cullMeshes[caster.info.x];
    if (materials[mesh.draw.w].flags.w == kShadowModeOff) return;
    CullTile tile = cull.tiles[tileIndex];
    bool keep = uint(tile.frustumMin.w) == kCullTileDirectional ? directionalKeeps(tile, caster.wsMin.xyz, caster.wsMax.xyz)
                                                               : perspectiveKeeps(tile, caster.wsMin.xyz, caster.wsMax.xyz);
    if (!keep) return;
    uint slot = atomicAdd(listCounts[tileIndex * meshCount + caster.info.x], 1u);
    visibleInstances[tileIndex * instanceCount + mesh.counts.x + slot] = instance;
}
