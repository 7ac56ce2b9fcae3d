#version 460
// An engine's fragment shader as docs/engine-integration.md shows it: the installed shadow sampling
// with its default set and bindings, one call per pixel. tests/unit/shadow_glsl_test.cpp reflects its
// SPIR-V (and scripts/test_embed.sh compiles it against the installed headers alone).
#include <penumbra/shadows.glsl>

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) flat in uint inLight;
layout(location = 0) out float outShadow;

void main() { outShadow = penumbraShadow(inLight, inWsPosition, normalize(inWsNormal), gl_FragCoord.xy); }
