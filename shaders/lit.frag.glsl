#version 460
// Forward lit pass: opaque, alpha-tested (MASK) and alpha-blended (BLEND) materials, lit or unlit,
// with up to 4 directional and 64 spot / point lights. Also writes the debug AOVs.
#include "bindings.glsl"
#include "lighting.glsl"
#include "shadows.glsl"
#include "surface_normals.glsl"

layout(constant_id = 1) const bool kBlendPass = false;
// The main directional light's shadow term from the screen-space resolve (seed 004), when enabled.
layout(set = 0, binding = 9) uniform sampler2D screenSpaceShadows;

layout(location = 0) in vec3 inWsPosition;
layout(location = 1) in vec3 inWsNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) flat in uint inInstance;
layout(location = 0) out vec4 outColor;

vec3 cascadeColor(int cascade) {
    const vec3 colors[5] = vec3[](vec3(0.0), vec3(1, 0.25, 0.25), vec3(0.25, 1, 0.25), vec3(0.25, 0.4, 1), vec3(1, 1, 0.25));
    return colors[clamp(cascade + 1, 0, 4)];
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
    Surface surface = Surface(inWsPosition, wsNormal, wsToCamera, baseColor.rgb, material.params.x, material.params.y);
    bool receives = (material.flags.y & kMaterialReceiveShadows) != 0u;
    uint outputMode = frame.counts.z;
    uint aovLight = frame.counts.w;

    vec3 radiance = frame.params.y * baseColor.rgb;
    float aovShadow = 1.0;
    int aovCascade = -1;
    for (uint i = 0u; i < frame.counts.x + frame.counts.y; ++i) {
        LightData light = lights[i];
        vec3 wsToLight = light.wsToLight.xyz;
        float attenuation = 1.0;
        ShadowSample shadow = ShadowSample(1.0, -1);
        if (uint(light.colorIntensity.a) == kLightDirectional) {
            // Transparent surfaces are not in the depth prepass: they sample the atlas directly, as in URP.
            bool resolved = frame.params.z > 0.5 && light.shadow.y == 0u && !kBlendPass && outputMode != kOutputCascadesAov;
            if (receives && resolved)
                shadow = ShadowSample(texelFetch(screenSpaceShadows, ivec2(gl_FragCoord.xy), 0).r, -1);
            else if (receives)
                shadow = directionalShadow(light.shadow.y, receiver, gl_FragCoord.xy);
        } else {
            vec3 wsOffset = light.wsPosition.xyz - inWsPosition;
            float distanceSquared = dot(wsOffset, wsOffset);
            wsToLight = wsOffset * inversesqrt(max(distanceSquared, 1e-8));
            attenuation = rangeAttenuation(distanceSquared, light.wsPosition.w);
            if (uint(light.colorIntensity.a) == kLightSpot)
                attenuation *= spotAttenuation(-wsToLight, -light.wsToLight.xyz, light.spotAngles);
            if (receives) shadow = otherShadow(light.shadow.y, receiver, wsToLight);
        }
        if (light.shadow.x == aovLight) { aovShadow = shadow.attenuation; aovCascade = shadow.cascade; }
        float nDotL = max(dot(wsNormal, wsToLight), 0.0);
        radiance += brdf(surface, wsToLight) * light.colorIntensity.rgb * (nDotL * attenuation * shadow.attenuation);
    }
    if ((material.flags.y & kMaterialUnlit) != 0u) radiance = baseColor.rgb;

    if (outputMode == kOutputShadowAov) {
        outColor = vec4(vec3(aovShadow), 1.0);
    } else if (outputMode == kOutputCascadesAov) {
        outColor = vec4(cascadeColor(aovCascade), 1.0);
    } else {
        outColor = vec4(radiance * frame.params.x, kBlendPass ? baseColor.a : 1.0);
    }
}
