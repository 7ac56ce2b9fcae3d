// The lit surface of a pixel: materials, every light's shadow and the outputs (colour and the debug
// AOVs), shared by the forward lit pass (lit.frag) and the visibility buffer's resolve
// (visibility_resolve.comp), so both paths evaluate the same functions. The caller supplies what its
// rasterizer knows: the interpolated position and normal, the triangle's plane and the base colour.
#ifndef PENUMBRA_SHADE_SURFACE_GLSL
#define PENUMBRA_SHADE_SURFACE_GLSL
#include "pass_bindings.h"
#include "bindings.glsl"
#include "lighting.glsl"
#include "light_clusters.glsl"
#include "lit_shadows.glsl"
#include "sky_light.glsl"

// The main directional light's shadow term from the screen-space resolve (shadows.screenSpace), when enabled.
layout(set = kPassSet, binding = kLitBindingScreenSpaceShadows) uniform sampler2D screenSpaceShadows;
layout(set = kPassSet, binding = kLitBindingClusterMasks, std430) readonly buffer ClusterMaskBlock { uint clusterMasks[]; };

// What the rasterizer knows of the visible surface at a pixel.
struct SurfaceInput {
    vec3 wsPosition;
    vec3 wsNormal;           // unit shading normal, turned to the viewer for double-sided back faces
    vec3 wsGeometricNormal;  // the triangle's unit normal on the side of wsNormal
    vec2 pixel;              // window position of the pixel centre (gl_FragCoord.xy)
    MaterialData material;
    vec4 baseColor;          // factor x texture at the pixel's uv
    bool blendPass;          // an alpha-blended draw (not in the depth prepass)
};

// What a lit pixel knows while it sums its lights.
struct PixelLighting {
    Surface surface;
    ShadowReceiver receiver;
    vec2 pixel;
    bool receives;
    bool blendPass;
    uint outputMode;
};

// Light i's radiance at the pixel; the AOV light's shadow term is recorded on the way.
vec3 shadeLight(uint i, PixelLighting pixel, inout float aovShadow, inout int aovCascade) {
    LightData light = lights[i];
    vec3 wsToLight = light.wsToLight.xyz;
    float attenuation = 1.0;
    ShadowSample shadow = ShadowSample(1.0, -1);
    bool aovLight = light.sceneLightIndex == frame.aovLightIndex;
    if (light.type == kLightDirectional) {
        // Transparent surfaces are not in the depth prepass: they sample the atlas directly, as in URP.
        bool resolved = frame.screenSpaceShadows != 0u && light.shadowSlot == 0u && !pixel.blendPass &&
                        pixel.outputMode != kOutputCascadesAov;
        if (pixel.receives && resolved)
            shadow = ShadowSample(texelFetch(screenSpaceShadows, ivec2(pixel.pixel), 0).r, -1);
        else if (pixel.receives)
            shadow = directionalShadow(light.shadowSlot, pixel.receiver, pixel.pixel);
    } else {
        vec3 wsOffset = light.wsPosition.xyz - pixel.surface.wsPosition;
        float distanceSquared = dot(wsOffset, wsOffset);
        wsToLight = wsOffset * inversesqrt(max(distanceSquared, 1e-8));
        attenuation = rangeAttenuation(distanceSquared, light.invRangeSquared);
        if (light.type == kLightSpot)
            attenuation *= spotAttenuation(-wsToLight, -light.wsToLight, light.spotScale, light.spotOffset);
        // A light that adds nothing here (outside its cone or range, or behind the surface) needs no shadow
        // lookup, unless its shadow term is the AOV's: a cluster holds every light whose range sphere
        // reaches it, and most of those pixels lie outside a spot's cone.
        bool adds = attenuation > 0.0 && dot(pixel.surface.wsNormal, wsToLight) > 0.0;
        if (pixel.receives && (adds || aovLight)) shadow = otherShadow(light.shadowSlot, pixel.receiver, wsToLight);
    }
    if (aovLight) { aovShadow = shadow.attenuation; aovCascade = shadow.cascade; }
    float nDotL = max(dot(pixel.surface.wsNormal, wsToLight), 0.0);
    return brdf(pixel.surface, wsToLight) * light.color * (nDotL * attenuation * shadow.attenuation);
}

// The pixel's output: colour x exposure, tone mapped (render.toneMapping; alpha for blended draws), or
// the AOV of frame.outputMode.
vec4 shadeSurface(SurfaceInput s) {
    MaterialData material = s.material;
    vec3 wsToCamera = normalize(frame.wsCameraPosition.xyz - s.wsPosition);
    PixelLighting pixel = PixelLighting(Surface(s.wsPosition, s.wsNormal, wsToCamera, s.baseColor.rgb, material.metallic,
                                                material.roughness),
                                        ShadowReceiver(s.wsPosition, s.wsNormal, s.wsGeometricNormal), s.pixel,
                                        (material.flags & kMaterialReceiveShadows) != 0u, s.blendPass, frame.outputMode);
    uint outputMode = pixel.outputMode;

    // The ambient sky light (render.ambient, sky_light.glsl), unshadowed; then every light.
    vec3 radiance = ambientRadiance(s.wsNormal, s.baseColor.rgb, frame.ambient);
    float aovShadow = 1.0;
    int aovCascade = -1;
    for (uint i = 0u; i < frame.directionalLightCount; ++i) radiance += shadeLight(i, pixel, aovShadow, aovCascade);
    // Spot and point lights: the cluster's (a culled light adds exactly nothing here), or all of them
    // for the AOVs (the AOV light's shadow term is wanted where it does not light) and beyond the slices.
    float vsDepth = -dot(vec4(frame.viewFromWorld[0].z, frame.viewFromWorld[1].z, frame.viewFromWorld[2].z,
                              frame.viewFromWorld[3].z), vec4(s.wsPosition, 1.0));
    int cluster = clusters.clustered != 0u && outputMode == kOutputColor ? clusterOfFragment(s.pixel, vsDepth) : -1;
    if (cluster < 0) {
        for (uint i = frame.directionalLightCount; i < frame.directionalLightCount + frame.otherLightCount; ++i)
            radiance += shadeLight(i, pixel, aovShadow, aovCascade);
    } else {
        uint words = clusters.wordsPerCluster;
        for (uint word = 0u; word < words; ++word) {
            uint bits = clusterMasks[uint(cluster) * words + word];
            while (bits != 0u) {
                uint bit = uint(findLSB(bits));
                bits &= bits - 1u;
                radiance += shadeLight(clusters.firstLight + word * 32u + bit, pixel, aovShadow, aovCascade);
            }
        }
    }
    if ((material.flags & kMaterialUnlit) != 0u) radiance = s.baseColor.rgb;

    if (outputMode == kOutputShadowAov) return vec4(vec3(aovShadow), 1.0);
    if (outputMode == kOutputCascadesAov) return vec4(aovCascadeColor(aovCascade), 1.0);
    return vec4(toneMap(radiance * frame.exposure, frame.toneMapping), s.blendPass ? s.baseColor.a : 1.0);
}

#endif
