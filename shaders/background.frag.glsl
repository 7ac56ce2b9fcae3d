#version 460
// The background of the colour output (render.background: gradient): drawn by the main pass as a
// full-screen triangle at reversed-Z depth 0 after the opaque draws, with the depth test
// GreaterOrEqual against the cleared depth 0, so it fills only the pixels no surface covers.
// Exposed and tone mapped like the lit pass (tone_mapping.glsl).
#include "pass_bindings.h"
#include "scene_structs.h"
#include "tone_mapping.glsl"

layout(set = kPassSet, binding = kSceneBindingFrame, std140) uniform FrameBlock { FrameData frame; };

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
    // The pixel's ray: from the camera through its point on the near plane (reversed Z: depth 1).
    vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec4 wsNear = frame.worldFromClip * vec4(ndc, 1.0, 1.0);
    vec3 wsDirection = wsNear.xyz / wsNear.w - frame.wsCameraPosition.xyz;
    outColor = vec4(toneMap(backgroundRadiance(wsDirection) * frame.exposure, frame.toneMapping), 1.0);
}
