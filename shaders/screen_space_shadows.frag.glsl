#version 460
// Screen-space shadow resolve in the manner of Unity URP's screen-space shadows (its
// _ScreenSpaceShadowmapTexture): the main directional light's shadow term per pixel, from the depth
// prepass, with exactly the forward path's sampling (penumbra/shadows.glsl).
#include "pass_bindings.h"
#include "bindings.glsl"
#include "lit_shadows.glsl"
#include "surface_normals.glsl"

layout(set = kPassSet, binding = kScreenShadowBindingSceneDepth) uniform sampler2D sceneDepth;
layout(set = kPassSet, binding = kScreenShadowBindingSceneNormals) uniform sampler2D sceneNormals;
layout(push_constant) uniform ScreenShadowBlock { ScreenShadowConstants resolve; };

layout(location = 0) in vec2 inUv;
layout(location = 0) out float outAttenuation;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(sceneDepth, pixel, 0).r;
    if (depth <= 0.0) { outAttenuation = 1.0; return; }  // reversed Z: 0 = nothing drawn
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 wsPosition = frame.worldFromClip * vec4(ndc, depth, 1.0);
    vec4 normals = texelFetch(sceneNormals, pixel, 0);
    ShadowReceiver receiver = ShadowReceiver(wsPosition.xyz / wsPosition.w, octDecode(normals.xy), octDecode(normals.zw));
    outAttenuation = directionalShadow(resolve.lightSlot, receiver, gl_FragCoord.xy).attenuation;
}
