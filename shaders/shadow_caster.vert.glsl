#version 460
// Shadow caster pass (seed 000 §1.6): positions into one atlas tile's clip space. Pancaking (seed 000
// §4.5) is done by the pipeline's depth clamp, which flattens casters in front of the near plane onto
// it instead of clipping them.
#include "bindings.glsl"

layout(push_constant) uniform CasterConstants {
    mat4 clipFromWorld;
} caster;

layout(location = 0) out vec2 outUv;
layout(location = 1) flat out uint outInstance;

void main() {
    VertexData vertex = vertices[gl_VertexIndex];
    InstanceData instance = instances[gl_InstanceIndex];
    outUv = vec2(vertex.osPositionU.w, vertex.osNormalV.w);
    outInstance = gl_InstanceIndex;
    gl_Position = caster.clipFromWorld * (instance.worldFromObject * vec4(vertex.osPositionU.xyz, 1.0));
}
