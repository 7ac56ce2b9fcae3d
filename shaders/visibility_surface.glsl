// The visibility buffer's surfaces (visibility_structs.h): what mesh.vert and the hardware's
// interpolation give lit.frag, rebuilt from a pixel's (instance, triangle): perspective-correct
// position, normal and uv, the uv change to the next pixel in x and y as texture gradients, the facing
// and the triangle's plane. Shared by the compute resolve (visibility_resolve.comp) and its fragment
// twin for CPU devices (visibility_resolve.frag, render/visibility_pass.h says why).
#ifndef PENUMBRA_VISIBILITY_SURFACE_GLSL
#define PENUMBRA_VISIBILITY_SURFACE_GLSL
#extension GL_KHR_shader_subgroup_ballot : require
#include "pass_bindings.h"
#include "cull_structs.h"
#include "shade_surface.glsl"
#include "visibility_structs.h"

layout(set = kPassSet, binding = kResolveBindingVisibility, std430) readonly buffer VisibilityBlock { uvec2 visibility[]; };  // (payload, depth bits): the 64-bit words
layout(set = kPassSet, binding = kResolveBindingIndices, std430) readonly buffer IndexBlock { uint indices[]; };
layout(set = kPassSet, binding = kResolveBindingMeshes, std430) readonly buffer CullMeshBlock { CullMesh cullMeshes[]; };
layout(set = kPassSet, binding = kResolveBindingInstances, std430) readonly buffer CullInstanceBlock { CullInstance cullInstances[]; };
layout(push_constant) uniform Constants { VisibilityConstants constants; };

// Perspective-correct barycentrics at NDC point `ndc` of the triangle with clip-space (x, y, w) rows:
// homogeneous edge functions (Olano and Greer 1997), valid for vertices behind the camera too. A
// covered pixel's weights lie in [0, 1] but for rounding, which a sliver seen edge-on magnifies without
// bound: they are clamped there (the vertices' mean where nothing is left), so no surface point leaves
// its triangle. unclampedBarycentricsAt extends the triangle's plane beyond it (for gradients).
vec3 unclampedBarycentricsAt(mat3 edges, vec2 ndc) {
    vec3 b = edges * vec3(ndc, 1.0);
    return b / (b.x + b.y + b.z);
}
vec3 barycentricsAt(mat3 edges, vec2 ndc) {
    vec3 b = clamp(unclampedBarycentricsAt(edges, ndc), 0.0, 1.0);
    float sum = b.x + b.y + b.z;
    return sum > 1e-6 ? b / sum : vec3(1.0 / 3.0);
}

// The base colour at uv with gradients dx, dy (the level by bindings.glsl's textureLevel, the rule the
// compute rasterizers use too); the texture index made uniform per subgroup pass, since the pixels
// of a workgroup may show different materials.
vec4 baseColorGrad(MaterialData material, vec2 uv, vec2 dx, vec2 dy) {
    vec4 color = material.baseColorFactor;
    if (material.baseColorTexture == 0u) return color;
    uint wanted = material.baseColorTexture - 1u;
    vec4 texel = vec4(1.0);
    for (;;) {
        uint texture = subgroupBroadcastFirst(wanted);
        if (texture == wanted) {
            texel = textureLod(baseColorTextures[texture], uv, textureLevel(texture, dx, dy));
            break;
        }
    }
    return color * texel;
}

// The surface of `triangle` of `instance` at pixel centre `pixel`.
SurfaceInput surfaceAt(uint instance, uint triangle, vec2 pixel) {
    CullMesh mesh = cullMeshes[cullInstances[instance].meshSlot];
    InstanceData data = instances[instance];
    mat4 worldFromObject = instanceWorldFromObject(data);
    VertexData v[3];
    vec3 wsPositions[3];
    mat3 clipRows;
    for (int i = 0; i < 3; ++i) {
        v[i] = vertices[uint(int(indices[mesh.firstIndex + triangle * 3u + uint(i)]) + mesh.vertexOffset)];
        wsPositions[i] = (worldFromObject * vec4(v[i].osPosition, 1.0)).xyz;
        vec4 clip = frame.clipFromWorld * vec4(wsPositions[i], 1.0);
        clipRows[i] = clip.xyw;
    }
    // Row i of `edges` is the edge function opposite vertex i: cross of the other two (x, y, w).
    mat3 edges = transpose(mat3(cross(clipRows[1], clipRows[2]), cross(clipRows[2], clipRows[0]),
                                cross(clipRows[0], clipRows[1])));
    vec2 ndcPerPixel = 2.0 * frame.viewport.zw;
    vec2 ndc = pixel * ndcPerPixel - 1.0;
    vec3 b = barycentricsAt(edges, ndc);
    // Texture gradients over the pixel's 2 x 2 quad, as the hardware's coarse derivatives in lit.frag.
    vec2 ndcQuad = (floor(pixel * 0.5) * 2.0 + 0.5) * ndcPerPixel - 1.0;
    vec3 bq = unclampedBarycentricsAt(edges, ndcQuad);
    vec3 bx = unclampedBarycentricsAt(edges, ndcQuad + vec2(ndcPerPixel.x, 0.0));
    vec3 by = unclampedBarycentricsAt(edges, ndcQuad + vec2(0.0, ndcPerPixel.y));
    mat3x2 uvs = mat3x2(vec2(v[0].u, v[0].v), vec2(v[1].u, v[1].v),
                        vec2(v[2].u, v[2].v));
    vec2 uv = uvs * b;
    vec3 wsPosition = mat3(wsPositions[0], wsPositions[1], wsPositions[2]) * b;
    vec3 osNormal = mat3(v[0].osNormal, v[1].osNormal, v[2].osNormal) * b;
    vec3 wsNormal = normalize(instanceNormalFromObject(data) * osNormal);
    bool frontFacing = determinant(clipRows) < 0.0;  // visibility_raster.glsl facesShown
    if (!frontFacing) wsNormal = -wsNormal;
    vec3 wsGeometric = cross(wsPositions[1] - wsPositions[0], wsPositions[2] - wsPositions[0]);
    float length2 = dot(wsGeometric, wsGeometric);
    wsGeometric = length2 > 1e-30 ? wsGeometric * inversesqrt(length2) : wsNormal;
    if (dot(wsGeometric, wsNormal) < 0.0) wsGeometric = -wsGeometric;
    MaterialData material = materials[data.materialIndex];
    vec4 baseColor = baseColorGrad(material, uv, uvs * (bx - bq), uvs * (by - bq));
    return SurfaceInput(wsPosition, wsNormal, wsGeometric, pixel, material, baseColor, false);
}

// The colour of a pixel no surface covers: the clear colour, or the colour output's gradient background
// (background.frag's: the pixel's view ray's radiance, exposed and tone mapped).
vec4 backgroundPixel(uvec2 pixel) {
    if (constants.backgroundGradient == 0u) return unpackUnorm4x8(constants.background);
    vec2 ndc = (vec2(pixel) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    vec4 wsNear = frame.worldFromClip * vec4(ndc, 1.0, 1.0);  // reversed Z: the near plane at depth 1
    vec3 wsDirection = wsNear.xyz / wsNear.w - frame.wsCameraPosition.xyz;
    return vec4(toneMap(backgroundRadiance(wsDirection) * frame.exposure, frame.toneMapping), 1.0);
}

// The shaded colour of pixel `pixel` (its payload != 0), or magenta for an id no instance has (a
// visible error, never a read out of bounds).
vec4 shadeVisiblePixel(uint payload, uvec2 pixel) {
    uint id = payload - 1u, triangleBits = constants.triangleBits;
    uint instance = id >> triangleBits, triangle = triangleBits == 0u ? 0u : id & ((1u << triangleBits) - 1u);
    if (instance >= uint(cullInstances.length())) return vec4(1.0, 0.0, 1.0, 1.0);
    return shadeSurface(surfaceAt(instance, triangle, vec2(pixel) + 0.5));
}

#endif
