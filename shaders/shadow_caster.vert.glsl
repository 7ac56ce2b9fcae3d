#version 460
// Shadow caster pass (Catlike Coding "Directional Shadows", Shadow Caster Pass): positions into one atlas
// tile's clip space. Shadow pancaking (same tutorial, Shadow Pancaking) is done by the pipeline's depth
// clamp, which flattens casters in front of the near plane onto it instead of clipping them.
#include "pass_bindings.h"
#include "bindings.glsl"

layout(push_constant) uniform CasterBlock { CasterConstants caster; };

// The tile's visible casters (cull_structs.h): gl_InstanceIndex = the draw's firstInstance + i
// indexes the list the culling pass wrote, in the buffer of the lists that holds this tile's.
layout(set = kPassSet, binding = kCasterBindingVisibleInstances, std430) readonly buffer VisibleBlock { uint visibleInstances[]; };

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;

void main() {
    VertexData vertex = vertices[gl_VertexIndex];
    uint instanceIndex = visibleInstances[gl_InstanceIndex];
    InstanceData instance = instances[instanceIndex];
    outUv = vec2(vertex.u, vertex.v);
    outInstance = instanceIndex;
    gl_Position = caster.clipFromWorld * (instanceWorldFromObject(instance) * vec4(vertex.osPosition, 1.0));
}
