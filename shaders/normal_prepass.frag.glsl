#version 460
// Depth prepass of the screen-space shadow path (shadows.screenSpace): depth plus the shading and the
// geometric normal (octahedral, xy and zw), which the resolve's biases need (penumbra/shadows/bias.glsl). Alpha-tested
// like the lit pass so both see the same surfaces.
#include "bindings.glsl"
#include "surface_normals.glsl"

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inInstance;
layout(location = 0) out vec4 outWsNormal;

void main() {
    vec3 wsNormal = normalize(inWsNormal);
    if (!gl_FrontFacing) wsNormal = -wsNormal;
    vec3 wsGeometricNormal = geometricNormal(inWsPosition, wsNormal);
    MaterialData material = materials[instances[inInstance].materialIndex];
    if (material.alphaMode == kAlphaMask && materialBaseColor(material, inUv).a < material.alphaCutoff) discard;
    outWsNormal = vec4(octEncode(wsNormal), octEncode(wsGeometricNormal));
}
