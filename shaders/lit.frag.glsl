#version 460
// Forward lit pass: opaque, alpha-tested (MASK) and alpha-blended (BLEND) materials, lit or unlit,
// with up to 4 directional and 1024 spot / point lights (each pixel loops over its cluster's spot and
// point lights only: light_clusters.glsl). Also writes the debug AOVs.
#include "bindings.glsl"
#include "lighting.glsl"
#include "light_clusters.glsl"
#include "shadows.glsl"
#include "surface_normals.glsl"

layout(constant_id = 1) const bool kBlendPass = false;
// The main directional light's shadow term from the screen-space resolve (seed 004), when enabled.
layout(set = 0, binding = 9) uniform sampler2D screenSpaceShadows;

layout(set = 0, binding = kBindingClusterMasks, std430) readonly buffer ClusterMaskBlock { uint clusterMasks[]; };

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inInstance;
layout(location = 0) out vec4 outColor;

vec3 cascadeColor(int cascade) {
    const vec3 colors[5] = vec3[](vec3(0.0), vec3(1, 0.25, 0.25), vec3(0.25, 1, 0.25), vec3(0.25, 0.4, 1), vec3(1, 1, 0.25));
    return colors[clamp(cascade + 1, 0, 4)];
}

// What a lit pixel knows while it sums its lights.
struct PixelLighting {
    Surface surface;
    ShadowReceiver receiver;
    bool receives;
    uint outputMode;
};

// Light i's radiance at the pixel; the AOV light's shadow term is recorded on the way.
vec3 shadeLight(uint i, PixelLighting pixel, inout float aovShadow, inout int aovCascade) {
    LightData light = lights[i];
    vec3 wsToLight = light.wsToLight.xyz;
    float attenuation = 1.0;
    ShadowSample shadow = ShadowSample(1.0, -1);
    if (uint(light.colorIntensity.a) == kLightDirectional) {
        // Transparent surfaces are not in the depth prepass: they sample the atlas directly, as in URP.
        bool resolved = frame.params.z > 0.5 && light.shadow.y == 0u && !kBlendPass && pixel.outputMode != kOutputCascadesAov;
        if (pixel.receives && resolved)
            shadow = ShadowSample(texelFetch(screenSpaceShadows, ivec2(gl_FragCoord.xy), 0).r, -1);
        else if (pixel.receives)
            shadow = directionalShadow(light.shadow.y, pixel.receiver, gl_FragCoord.xy);
    } else {
        vec3 wsOffset = light.wsPosition.xyz - inWsPosition;
        float distanceSquared = dot(wsOffset, wsOffset);
        wsToLight = wsOffset * inversesqrt(max(distanceSquared, 1e-8));
        attenuation = rangeAttenuation(distanceSquared, light.wsPosition.w);
        if (uint(light.colorIntensity.a) == kLightSpot)
            attenuation *= spotAttenuation(-wsToLight, -light.wsToLight.xyz, light.spotAngles);
        if (pixel.receives) shadow = otherShadow(light.shadow.y, pixel.receiver, wsToLight);
    }
    if (light.shadow.x == frame.counts.w) { aovShadow = shadow.attenuation; aovCascade = shadow.cascade; }
    float nDotL = max(dot(pixel.surface.wsNormal, wsToLight), 0.0);
    return brdf(pixel.surface, wsToLight) * light.colorIntensity.rgb * (nDotL * attenuation * shadow.attenuation);
}

void main() {
    vec3 wsNormal = normalize(inWsNormal);
    if (!gl_FrontFacing) wsNormal = -wsNormal;  // double-sided back faces
    // Before any discard or branch: derivatives need the whole quad (the biases use the triangle's plane).
    ShadowReceiver receiver = ShadowReceiver(inWsPosition, wsNormal, geometricNormal(inWsPosition, wsNormal));
    MaterialData material = materials[instances[inInstance].info.x];
    vec4 baseColor = materialBaseColor(material, inUv);
    if (material.flags.z == kAlphaMask && baseColor.a < material.params.z) discard;

    vec3 wsToCamera = normalize(frame.wsCameraPosition.xyz - inWsPosition);
    PixelLighting pixel = PixelLighting(Surface(inWsPosition, wsNormal, wsToCamera, baseColor.rgb, material.params.x,
                                                material.params.y),
                                        receiver, (material.flags.y & kMaterialReceiveShadows) != 0u, frame.counts.z);
    uint outputMode = pixel.outputMode;

    vec3 radiance = frame.params.y * baseColor.rgb;
    float aovShadow = 1.0;
    int aovCascade = -1;
    for (uint i = 0u; i < frame.counts.x; ++i) radiance += shadeLight(i, pixel, aovShadow, aovCascade);
    // Spot and point lights: the cluster's (a culled light adds exactly nothing here), or all of them
    // for the AOVs (the AOV light's shadow term is wanted where it does not light) and beyond the slices.
    float vsDepth = -dot(vec4(frame.viewFromWorld[0].z, frame.viewFromWorld[1].z, frame.viewFromWorld[2].z,
                              frame.viewFromWorld[3].z), vec4(inWsPosition, 1.0));
    int cluster = clusters.config.w != 0u && outputMode == kOutputColor ? clusterOfFragment(gl_FragCoord.xy, vsDepth) : -1;
    if (cluster < 0) {
        for (uint i = frame.counts.x; i < frame.counts.x + frame.counts.y; ++i)
            radiance += shadeLight(i, pixel, aovShadow, aovCascade);
    } else {
        uint words = clusters.config.z;
        for (uint word = 0u; word < words; ++word) {
            uint bits = clusterMasks[uint(cluster) * words + word];
            while (bits != 0u) {
                uint bit = uint(findLSB(bits));
                bits &= bits - 1u;
                radiance += shadeLight(clusters.config.y + word * 32u + bit, pixel, aovShadow, aovCascade);
            }
        }
    }
    if ((material.flags.y & kMaterialUnlit) != 0u) radiance = baseColor.rgb;

    if (outputMode == kOutputShadowAov) {
        outColor = vec4(vec3(aovShadow), 1.0);
    } else if (outputMode == kOutputCascadesAov) {
        outColor = vec4(cascadeColor(aovCascade), 1.0);
    } else {
        outColor = vec4(toneMap(radiance * frame.params.x, uint(frame.params.w)), kBlendPass ? baseColor.a : 1.0);
    }
}
