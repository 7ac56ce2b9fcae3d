// Tent-filtered shadow-map sampling (Unity's ShadowSamplingTent.hlsl, SampleShadow_ComputeSamples_Tent_*, as
// Catlike Coding "Directional Shadows", PCF Filtering and URP's SampleShadowmapFiltered use it): the GPU twin
// of src/shadows/tent_filter.cpp, whose unit tests check the math. A tent of radius 1.5 / 2.5 / 3.5 texels
// around the sample point is integrated over each texel, and each 2 x 2 block of texels becomes one
// bilinear compare (a textureGather of its 4 depths, each compared, weighted bilinearly: what hardware PCF
// does) placed so that the bilinear weights reproduce the block's texel weights: 4 / 9 / 16 fetches for
// PCF3x3 / PCF5x5 / PCF7x7.
//
// Inputs: a sampler2D of the atlas (R32F depth, nearest: the compare is the shader's, so the atlas is a
// colour image that compute passes write directly); uvDepth = (atlas u,
// atlas v, fragment depth) as DirectionalShadowData.atlasFromWorld gives them; texelSize =
// (1 / width, 1 / height, width, height) of the atlas (shadowTexelSize in shadows.glsl).
#ifndef PENUMBRA_SHADOW_TENT_GLSL
#define PENUMBRA_SHADOW_TENT_GLSL

// Integral from -infinity to s of the unit-area tent max(0, r - |x|) / r^2.
float penumbraTentCdf(float s, float r) {
    float a = clamp(s, -r, r);
    float t = r - abs(a);
    float tail = 0.5 * t * t / (r * r);
    return a <= 0.0 ? tail : 1.0 - tail;
}

// 1D fetches of a tent of radius pairs - 0.5 centred at u (texel units, texel j spans [j, j + 1]):
// pair k covers texels first + 2k and first + 2k + 1, where first = nearest texel corner - pairs.
// position = fetch coordinate in texel units, weight = the pair's summed texel weights.
void penumbraTentFetches1D(float u, int pairs, out vec4 position, out vec4 weight) {
    float r = float(pairs) - 0.5;
    float first = floor(u + 0.5) - float(pairs);
    position = vec4(0.0);
    weight = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        if (k >= pairs) break;
        float j = first + 2.0 * float(k);
        float c0 = penumbraTentCdf(j - u, r);
        float c1 = penumbraTentCdf(j + 1.0 - u, r);
        float c2 = penumbraTentCdf(j + 2.0 - u, r);
        float sum = c2 - c0;
        position[k] = j + 0.5 + (sum > 0.0 ? (c2 - c1) / sum : 0.5);
        weight[k] = sum;
    }
}

// The depth test of one bilinear block of 2 x 2 texels at fetch position q (texel units): a textureGather
// of the 4 raw depths, each compared LESS_OR_EQUAL ("receiver depth <= stored depth -> lit"), weighted
// bilinearly, one of two ways (shadows.bias):
// - hardware-PCF style: the 4 texels against one depth, uvDepth.z;
// - receiver plane (planeGradient = the receiver's depth per texel along u, v): each texel against the
//   depth the receiver's plane has at that texel's centre, so a plane never shadows itself whatever its slope.
// u = the sample position in texels, where the plane's depth is uvDepth.z. textureGather: no implicit
// derivatives, so safe in non-uniform control flow.
float penumbraCompareBilinear(sampler2D atlas, vec2 q, vec3 uvDepth, vec2 u, vec4 texelSize, vec2 planeGradient,
                              bool perTexelPlane) {
    vec2 first = floor(q - 0.5);  // texel (i0, j0); the block is i0..i0+1, j0..j0+1
    vec2 f = q - 0.5 - first;
    vec4 stored = textureGather(atlas, (first + 1.0) * texelSize.xy, 0);  // (i0,j1) (i1,j1) (i1,j0) (i0,j0)
    vec4 receiver = vec4(uvDepth.z);
    if (perTexelPlane) {
        float plane00 = uvDepth.z + dot(planeGradient, first + 0.5 - u);
        receiver = plane00 + vec4(planeGradient.y, planeGradient.x + planeGradient.y, planeGradient.x, 0.0);
    }
    vec4 lit = vec4(lessThanEqual(receiver, stored));
    return mix(mix(lit.w, lit.z, f.x), mix(lit.x, lit.y, f.x), f.y);
}

float penumbraSampleShadowTent(sampler2D atlas, vec3 uvDepth, vec4 texelSize, int pairs,
                               vec2 planeGradient, bool perTexelPlane) {
    vec2 u = uvDepth.xy * texelSize.zw;
    vec4 px, wx, py, wy;
    penumbraTentFetches1D(u.x, pairs, px, wx);
    penumbraTentFetches1D(u.y, pairs, py, wy);
    float shadow = 0.0;
    for (int y = 0; y < 4; ++y) {
        if (y >= pairs) break;
        for (int x = 0; x < 4; ++x) {
            if (x >= pairs) break;
            shadow += wx[x] * wy[y] * penumbraCompareBilinear(atlas, vec2(px[x], py[y]), uvDepth, u, texelSize,
                                                              planeGradient, perTexelPlane);
        }
    }
    return shadow;
}

// One bilinear block at the sample point: the 2 x 2 PCF tap (PCF2x2), against one depth or the
// receiver's plane.
float sampleShadowPcf2x2(sampler2D atlas, vec3 uvDepth, vec4 texelSize, vec2 planeGradient,
                         bool perTexelPlane) {
    vec2 u = uvDepth.xy * texelSize.zw;
    return penumbraCompareBilinear(atlas, u, uvDepth, u, texelSize, planeGradient, perTexelPlane);
}

// filterMode: kShadowFilterPcf2x2 .. kShadowFilterPcf7x7 = 0..3. Pass a constant (specialization
// constant) to let the compiler drop the other branches.
float sampleShadowFiltered(sampler2D atlas, vec3 uvDepth, vec4 texelSize, uint filterMode,
                           vec2 planeGradient, bool perTexelPlane) {
    if (filterMode == 0u) return sampleShadowPcf2x2(atlas, uvDepth, texelSize, planeGradient, perTexelPlane);
    return penumbraSampleShadowTent(atlas, uvDepth, texelSize, int(filterMode) + 1, planeGradient,
                                    perTexelPlane);
}

#endif
