#version 460
// Forward lit pass: opaque, alpha-tested (MASK) and alpha-blended (BLEND) materials, lit or unlit,
// with up to 4 directional and 1024 spot / point lights (each pixel loops over its cluster's spot and
// point lights only: light_clusters.glsl). Also writes the debug AOVs. The shading is
// shade_surface.glsl's, which the visibility buffer's resolve shares.
#include "shade_surface.glsl"
#include "surface_normals.glsl"

layout(constant_id = 1) const bool kBlendPass = false;

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inInstance;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 wsNormal = normalize(inWsNormal);
    if (!gl_FrontFacing) wsNormal = -wsNormal;  // double-sided back faces
    // Before any discard or branch: derivatives need the whole quad (the biases use the triangle's plane).
    vec3 wsGeometricNormal = geometricNormal(inWsPosition, wsNormal);
    MaterialData material = materials[instances[inInstance].materialIndex];
    vec4 baseColor = materialBaseColor(material, inUv);
    if (material.alphaMode == kAlphaMask && baseColor.a < material.alphaCutoff) discard;
    outColor = shadeSurface(SurfaceInput(inWsPosition, wsNormal, wsGeometricNormal, gl_FragCoord.xy, material, baseColor,
                                         kBlendPass));
}
