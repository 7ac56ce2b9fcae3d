// GPU data of the scene and frame, shared by C++ (render/) and GLSL (shaders/).
#ifndef PENUMBRA_SCENE_STRUCTS_H
#define PENUMBRA_SCENE_STRUCTS_H
#include "gpu_shared.h"
#include "shadow_view_structs.h"

PENUMBRA_GPU_NAMESPACE_BEGIN

PENUMBRA_CONST(uint, kMaxDirectionalLights, 4u)
PENUMBRA_CONST(uint, kMaxOtherLights, 1024u)  // = 32 x kMaxClusterLightWords

// Debug output of the lit pass (--aov).
PENUMBRA_CONST(uint, kOutputColor, 0u)
PENUMBRA_CONST(uint, kOutputShadowAov, 1u)
PENUMBRA_CONST(uint, kOutputCascadesAov, 2u)

// The colour of --aov cascades: black where no cascade (or virtual level) serves, then cascade or
// virtual shadow map level i: red, green, blue, yellow for 0-3, then a hue per further level, full and
// dimmed in turn so that neighbouring levels differ.
PENUMBRA_INLINE vec3 aovCascadeColor(int index) {
    if (index < 0) return vec3(0.0f);
    if (index == 0) return vec3(1.0f, 0.25f, 0.25f);
    if (index == 1) return vec3(0.25f, 1.0f, 0.25f);
    if (index == 2) return vec3(0.25f, 0.4f, 1.0f);
    if (index == 3) return vec3(1.0f, 1.0f, 0.25f);
    const float hue = float(index - 4) * 0.0833333f + 0.04f;
    const vec3 rgb = clamp(abs(fract(vec3(hue) + vec3(0.0f, 0.6666667f, 0.3333333f)) * 6.0f - 3.0f) - 1.0f, 0.0f, 1.0f);
    return (index % 2 == 0 ? 1.0f : 0.55f) * (0.2f + 0.8f * rgb);
}

// Tone mapping of the colour output (FrameData.toneMapping; = penumbra::ToneMapping, tone_mapping.glsl).
PENUMBRA_CONST(uint, kToneMapNone, 0u)
PENUMBRA_CONST(uint, kToneMapNeutral, 1u)
PENUMBRA_CONST(uint, kToneMapAces, 2u)

// Material flags (MaterialData.flags)
PENUMBRA_CONST(uint, kMaterialUnlit, 1u)
PENUMBRA_CONST(uint, kMaterialDoubleSided, 2u)
PENUMBRA_CONST(uint, kMaterialReceiveShadows, 4u)

// Alpha and shadow modes (MaterialData.alphaMode / .shadowMode) mirror scene::AlphaMode and MaterialShadowMode.
PENUMBRA_CONST(uint, kAlphaOpaque, 0u)
PENUMBRA_CONST(uint, kAlphaMask, 1u)
PENUMBRA_CONST(uint, kAlphaBlend, 2u)
PENUMBRA_CONST(uint, kShadowModeOn, 0u)
PENUMBRA_CONST(uint, kShadowModeClip, 1u)
PENUMBRA_CONST(uint, kShadowModeDither, 2u)
PENUMBRA_CONST(uint, kShadowModeOff, 3u)

// kNoShadowSlot (LightData.shadowSlot of a light without shadows) and the kLight* types are
// shadow_view_structs.h's: the installed shadow sampling reads them too.

struct FrameData {
    mat4 clipFromWorld;
    mat4 viewFromWorld;
    mat4 worldFromClip;     // inverse of clipFromWorld: depth-buffer positions back to world space
    vec4 wsCameraPosition;  // xyz, w unused
    vec4 viewport;          // width, height, 1/width, 1/height
    uint directionalLightCount;
    uint otherLightCount;
    uint outputMode;          // kOutput*
    uint aovLightIndex;       // the scene light whose shadow the AOV outputs show
    float exposure;
    float ambient;
    uint screenSpaceShadows;  // 1: the main light's shadows come from the screen-space resolve
    uint toneMapping;         // kToneMap*
};
PENUMBRA_CHECK_SIZE(FrameData, 256)
PENUMBRA_CHECK_LAYOUT(FrameData, viewFromWorld, 64)
PENUMBRA_CHECK_LAYOUT(FrameData, worldFromClip, 128)
PENUMBRA_CHECK_LAYOUT(FrameData, wsCameraPosition, 192)
PENUMBRA_CHECK_LAYOUT(FrameData, directionalLightCount, 224)
PENUMBRA_CHECK_LAYOUT(FrameData, exposure, 240)
PENUMBRA_CHECK_LAYOUT(FrameData, toneMapping, 252)

struct LightData {
    vec3 color;             // colour x intensity
    uint type;              // kLight*
    vec3 wsPosition;        // spot, point
    float invRangeSquared;  // 1 / range^2 (0 = infinite)
    vec3 wsToLight;         // unit vector toward the light (directional) / opposite of the spot axis
    float reserved2;
    float spotScale;        // 1 / (cos inner - cos outer)   (KHR_lights_punctual's spot attenuation)
    float spotOffset;       // -cos outer * spotScale
    float reserved3;
    float reserved4;
    uint sceneLightIndex;
    uint shadowSlot;      // kNoShadowSlot = none
    uint reserved0;
    uint reserved1;
};
PENUMBRA_CHECK_SIZE(LightData, 80)
PENUMBRA_CHECK_LAYOUT(LightData, type, 12)
PENUMBRA_CHECK_LAYOUT(LightData, wsPosition, 16)
PENUMBRA_CHECK_LAYOUT(LightData, invRangeSquared, 28)
PENUMBRA_CHECK_LAYOUT(LightData, wsToLight, 32)
PENUMBRA_CHECK_LAYOUT(LightData, spotScale, 48)
PENUMBRA_CHECK_LAYOUT(LightData, sceneLightIndex, 64)
PENUMBRA_CHECK_LAYOUT(LightData, shadowSlot, 68)

// Per instance, what the shaders read (64 bytes): the affine worldFromObject as its first three rows
// (row i = worldFromObject[0..3][i]: the linear part and the translation; the fourth row of an affine
// transform is (0, 0, 0, 1)) and its mesh's material. The normal matrix is not stored: the shaders derive
// it from the rows (instanceNormalFromObject).
struct InstanceData {
    vec4 worldFromObjectRow0;
    vec4 worldFromObjectRow1;
    vec4 worldFromObjectRow2;
    uint materialIndex;
    uint reserved0;
    uint reserved1;
    uint reserved2;
};
PENUMBRA_CHECK_SIZE(InstanceData, 64)
PENUMBRA_CHECK_LAYOUT(InstanceData, worldFromObjectRow1, 16)
PENUMBRA_CHECK_LAYOUT(InstanceData, worldFromObjectRow2, 32)
PENUMBRA_CHECK_LAYOUT(InstanceData, materialIndex, 48)

// The instance's worldFromObject as a 4x4 matrix (the rows back in their columns, exactly).
PENUMBRA_INLINE mat4 instanceWorldFromObject(InstanceData instance) {
    return transpose(mat4(instance.worldFromObjectRow0, instance.worldFromObjectRow1, instance.worldFromObjectRow2,
                          vec4(0.0f, 0.0f, 0.0f, 1.0f)));
}

// The normals' transform of a worldFromObject with linear part m: its cofactor matrix, which is the
// inverse transpose times the determinant. It gives the inverse transpose's directions (the shaders
// normalize) for every invertible transform, non-uniform scales included, keeps the facing of mirrored
// ones (the sign), and stays finite for a singular one (a zero scale), where the inverse would divide by zero.
PENUMBRA_INLINE mat3 cofactorNormalMatrix(mat3 m) {
    mat3 cofactor = mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1]));
    return determinant(m) < 0.0f ? -cofactor : cofactor;
}
PENUMBRA_INLINE mat3 instanceNormalFromObject(InstanceData instance) {
    return cofactorNormalMatrix(mat3(instanceWorldFromObject(instance)));
}

struct MaterialData {
    vec4 baseColorFactor;
    float metallic;
    float roughness;
    float alphaCutoff;
    float reserved;
    uint baseColorTexture;  // texture index + 1 (0 = none)
    uint flags;             // kMaterial* bits
    uint alphaMode;         // kAlpha*
    uint shadowMode;        // kShadowMode*
};
PENUMBRA_CHECK_SIZE(MaterialData, 48)
PENUMBRA_CHECK_LAYOUT(MaterialData, alphaCutoff, 24)
PENUMBRA_CHECK_LAYOUT(MaterialData, baseColorTexture, 32)
PENUMBRA_CHECK_LAYOUT(MaterialData, shadowMode, 44)

// One vertex as the shaders pull it from the vertex storage buffer.
struct VertexData {
    vec3 osPosition;
    float u;  // texture coordinates
    vec3 osNormal;
    float v;
};
PENUMBRA_CHECK_SIZE(VertexData, 32)
PENUMBRA_CHECK_LAYOUT(VertexData, u, 12)
PENUMBRA_CHECK_LAYOUT(VertexData, osNormal, 16)

PENUMBRA_GPU_NAMESPACE_END
#endif
