#version 460
// Scattered scene update (render/gpu_scene.h, recordUpdates): one thread per changed instance copies
// its packed records from the frame's staging to its place in the scene's instance and culling
// buffers, so an edit of N instances costs the CPU N packings and one dispatch, wherever they lie.
#include "pass_bindings.h"
#include "scene_structs.h"
#include "cull_structs.h"

layout(local_size_x = 64) in;

layout(set = kPassSet, binding = kScatterBindingIndices, std430) readonly buffer ScatterIndexBlock { uint sceneIndices[]; };
layout(set = kPassSet, binding = kScatterBindingInstanceData, std430) readonly buffer ScatterInstanceBlock { InstanceData changedInstances[]; };
layout(set = kPassSet, binding = kScatterBindingCullData, std430) readonly buffer ScatterCullBlock { CullInstance changedCullInstances[]; };
layout(set = kPassSet, binding = kScatterBindingInstances, std430) writeonly buffer SceneInstanceBlock { InstanceData instances[]; };
layout(set = kPassSet, binding = kScatterBindingCullInstances, std430) writeonly buffer SceneCullInstanceBlock { CullInstance cullInstances[]; };
layout(push_constant) uniform ScatterBlock { ScatterConstants scatter; };

void main() {
    uint changed = scatter.first + gl_GlobalInvocationID.x;
    if (changed >= scatter.count) return;
    uint instance = sceneIndices[changed];
    instances[instance] = changedInstances[changed];
    cullInstances[instance] = changedCullInstances[changed];
}
