#version 460
// Main-view vertex shader: pulls vertices and instances from storage buffers (no vertex input state),
// so a compute rasterizer can consume the same data.
#include "bindings.glsl"

layout(location = 0) out vec3 outWsPosition;
layout(location = 1) out vec3 outWsNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) flat out uint outInstance;

void main() {
    VertexData vertex = vertices[gl_VertexIndex];
    InstanceData instance = instances[gl_InstanceIndex];
    vec4 wsPosition = instanceWorldFromObject(instance) * vec4(vertex.osPosition, 1.0);
    outWsPosition = wsPosition.xyz;
    outWsNormal = instanceNormalFromObject(instance) * vertex.osNormal;
    outUv = vec2(vertex.u, vertex.v);
    outInstance = gl_InstanceIndex;
    gl_Position = frame.clipFromWorld * wsPosition;
}
