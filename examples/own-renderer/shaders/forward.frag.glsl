#version 460
// The engine's forward pass: its own materials (base colour, alpha cut-out) and a Lambert sun, with
// the shadow of light 0 from Penumbra's shadow sampling (set 2, bound as ShadowSystem hands it over).
// Writes the colour and, to a second target, light 0's shadow term (what `penumbra render --aov shadow`
// shows).
#define PENUMBRA_SHADOW_SET 2
#include <penumbra/shadows.glsl>

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) in vec2 inUv;

layout(set = 0, binding = 0) uniform Frame {
    mat4 clipFromWorld;
    vec4 wsLight0;
} frame;
layout(set = 1, binding = 0) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Draw {
    mat4 worldFromObject;
    vec4 baseColorFactor;
    float alphaCutoff;
    uint flags;
} draw;

layout(location = 0) out vec4 outColor;
layout(location = 1) out float outShadow;

void main() {
    vec3 wsNormal = normalize(inWsNormal);
    if (!gl_FrontFacing) wsNormal = -wsNormal;  // double-sided back faces
    // The triangle's plane from the position's derivatives (before the discard: the quad must be whole),
    // on the side of the shading normal: the receiver-plane bias tilts with it.
    vec3 n = cross(dFdx(inWsPosition), dFdy(inWsPosition));
    vec3 wsGeometricNormal = dot(n, n) > 1e-30 ? normalize(n) : wsNormal;
    if (dot(wsGeometricNormal, wsNormal) < 0.0) wsGeometricNormal = -wsGeometricNormal;
    vec4 baseColor = draw.baseColorFactor * texture(baseColorTexture, inUv);
    if (draw.alphaCutoff >= 0.0 && baseColor.a < draw.alphaCutoff) discard;

    bool receives = (draw.flags & 1u) != 0u;
    float shadow = receives ? penumbraShadowWithGeometricNormal(0u, inWsPosition, wsNormal, wsGeometricNormal,
                                                                gl_FragCoord.xy)
                            : 1.0;
    // The engine's own lighting (Lambert and a constant ambient) from light 0, shadowed by its term.
    vec3 wsToLight = frame.wsLight0.w == 0.0 ? frame.wsLight0.xyz : normalize(frame.wsLight0.xyz - inWsPosition);
    float lambert = max(dot(wsNormal, wsToLight), 0.0);
    outColor = vec4(baseColor.rgb * (0.25 + 0.75 * lambert * shadow), 1.0);
    outShadow = shadow;
}
