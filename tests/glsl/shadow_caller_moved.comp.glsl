#version 460
// The installed shadow sampling in a compute shader, in set 2 from binding 8 on (an engine whose set 0
// and 1 are its own), with the geometric normal given apart from the shading normal.
#define PENUMBRA_SHADOW_SET 2
#define PENUMBRA_SHADOW_BINDING_BASE 8
#include <penumbra/shadows.glsl>

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer Receivers { vec4 wsPositions[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Shadows { float shadows[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    vec3 wsNormal = vec3(0.0, 1.0, 0.0);
    shadows[i] = penumbraShadowWithGeometricNormal(0u, wsPositions[i].xyz, wsNormal, wsNormal, vec2(gl_GlobalInvocationID.xy));
}
