#version 460
// The engine's depth prepass: depth only, alpha cut-outs discarded as the forward pass does. Its depth
// buffer then serves ShadowSystem (the virtual pages' marking, the tight cascade fit) and the forward
// pass, which tests against it.
layout(location = 2) in vec2 inUv;

layout(set = 1, binding = 0) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Draw {
    mat4 worldFromObject;
    vec4 baseColorFactor;
    float alphaCutoff;
    uint flags;
} draw;

void main() {
    float alpha = draw.baseColorFactor.a * texture(baseColorTexture, inUv).a;
    if (draw.alphaCutoff >= 0.0 && alpha < draw.alphaCutoff) discard;
}
