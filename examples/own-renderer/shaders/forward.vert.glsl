#version 460
// The engine's vertex shader: its own vertex layout (position, normal, uv) and per-draw transform.
layout(location = 0) in vec3 inOsPosition;
layout(location = 1) in vec3 inOsNormal;
layout(location = 2) in vec2 inUv;

layout(set = 0, binding = 0) uniform Frame {
    mat4 clipFromWorld;
    vec4 wsLight0;  // light 0: w = 0 the direction toward a sun, w = 1 a spot or point light's position
} frame;
layout(push_constant) uniform Draw {
    mat4 worldFromObject;
    vec4 baseColorFactor;
    float alphaCutoff;  // < 0: opaque
    uint flags;         // 1: receives shadows
} draw;

layout(location = 0) out vec3 outWsPosition;
layout(location = 1) out vec3 outWsNormal;
layout(location = 2) out vec2 outUv;

void main() {
    // precise: the forward pass tests against the depth prepass's depth (equal in effect), so both
    // pipelines must compute the very same position (no fused multiply-adds in one and not the other).
    precise vec4 wsPosition = draw.worldFromObject * vec4(inOsPosition, 1.0);
    outWsPosition = wsPosition.xyz;
    outWsNormal = transpose(inverse(mat3(draw.worldFromObject))) * inOsNormal;
    outUv = inUv;
    precise vec4 clipPosition = frame.clipFromWorld * wsPosition;
    gl_Position = clipPosition;
}
