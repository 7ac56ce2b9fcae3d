#version 460
// An engine's compute pass over its own ground plane (y = groundY, |x| and |z| at most groundHalfSize):
// per pixel, the camera ray's hit on the plane, and there the shadow term of one light through the
// installed shadow sampling, whose descriptors ShadowSystem filled (set 1). -1 where the ray misses it. ShadowSystemTest compares
// it with Penumbra's own shadow AOV of the same scene.
#define PENUMBRA_SHADOW_SET 1
#include <penumbra/shadows.glsl>

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, std430) writeonly buffer Shadows { float shadows[]; };
layout(push_constant) uniform Ground {
    mat4 worldFromClip;  // inverse(CameraView::clipFromWorld): reversed Z, the near plane at depth 1
    uvec2 size;
    uint light;
    float groundY;
    float groundHalfSize;
} ground;

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(p, ground.size))) return;
    vec2 pixel = vec2(p) + 0.5;
    vec2 ndc = pixel / vec2(ground.size) * 2.0 - 1.0;
    vec4 nearPoint = ground.worldFromClip * vec4(ndc, 1.0, 1.0);
    vec4 farther = ground.worldFromClip * vec4(ndc, 0.5, 1.0);
    vec3 origin = nearPoint.xyz / nearPoint.w;
    vec3 direction = farther.xyz / farther.w - origin;
    float shadow = -1.0;
    if (direction.y < 0.0) {
        vec3 wsPosition = origin + direction * ((ground.groundY - origin.y) / direction.y);
        if (max(abs(wsPosition.x), abs(wsPosition.z)) <= ground.groundHalfSize)
            shadow = penumbraShadow(ground.light, wsPosition, vec3(0.0, 1.0, 0.0), pixel);
    }
    shadows[p.y * ground.size.x + p.x] = shadow;
}
