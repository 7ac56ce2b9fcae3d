// Tent-filtered shadow-map sampling (seed 000 §4.6, seed 004): the GPU twin of
// src/shadows/tent_filter.cpp, whose unit tests check the math. A tent of radius 1.5 / 2.5 / 3.5 texels
// around the sample point is integrated over each texel, and each 2 x 2 block of texels becomes one
// hardware-PCF fetch (bilinear compare) placed so that the bilinear weights reproduce the block's
// texel weights: 4 / 9 / 16 fetches for PCF3x3 / PCF5x5 / PCF7x7.
//
// Inputs: a sampler2DShadow with compare op LESS_OR_EQUAL and linear filtering; uvDepth = (atlas u,
// atlas v, fragment depth) as DirectionalShadowData.atlasFromWorld gives them; texelSize =
// (1 / width, 1 / height, width, height) of the atlas, i.e. DirectionalShadowData.atlasSize.yyxx.
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

float penumbraSampleShadowTent(sampler2DShadow atlas, vec3 uvDepth, vec4 texelSize, int pairs) {
    vec2 u = uvDepth.xy * texelSize.zw;
    vec4 px, wx, py, wy;
    penumbraTentFetches1D(u.x, pairs, px, wx);
    penumbraTentFetches1D(u.y, pairs, py, wy);
    float shadow = 0.0;
    for (int y = 0; y < 4; ++y) {
        if (y >= pairs) break;
        for (int x = 0; x < 4; ++x) {
            if (x >= pairs) break;
            vec2 uv = vec2(px[x], py[y]) * texelSize.xy;
            // textureLod: no implicit derivatives, so safe in non-uniform control flow.
            shadow += wx[x] * wy[y] * textureLod(atlas, vec3(uv, uvDepth.z), 0.0);
        }
    }
    return shadow;
}

float sampleShadowPcf2x2(sampler2DShadow atlas, vec3 uvDepth) { return textureLod(atlas, uvDepth, 0.0); }
float sampleShadowTent3x3(sampler2DShadow atlas, vec3 uvDepth, vec4 texelSize) {
    return penumbraSampleShadowTent(atlas, uvDepth, texelSize, 2);
}
float sampleShadowTent5x5(sampler2DShadow atlas, vec3 uvDepth, vec4 texelSize) {
    return penumbraSampleShadowTent(atlas, uvDepth, texelSize, 3);
}
float sampleShadowTent7x7(sampler2DShadow atlas, vec3 uvDepth, vec4 texelSize) {
    return penumbraSampleShadowTent(atlas, uvDepth, texelSize, 4);
}

// filterMode: DirectionalShadowData.config.y (kShadowFilterPcf2x2 .. kShadowFilterPcf7x7 = 0..3).
// Pass a constant (specialization constant) to let the compiler drop the other branches.
float sampleShadowFiltered(sampler2DShadow atlas, vec3 uvDepth, vec4 texelSize, uint filterMode) {
    if (filterMode == 0u) return sampleShadowPcf2x2(atlas, uvDepth);
    return penumbraSampleShadowTent(atlas, uvDepth, texelSize, int(filterMode) + 1);
}

#endif
