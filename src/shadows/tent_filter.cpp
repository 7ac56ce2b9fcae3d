#include "shadows/tent_filter.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// Integral of the unit-area tent of radius r (max(0, r - |s|) / r^2) from -infinity to s.
float tentCdf(float s, float r) {
    if (s <= -r) return 0.0f;
    if (s >= r) return 1.0f;
    const float inv2r2 = 0.5f / (r * r);
    return s <= 0.0f ? (s + r) * (s + r) * inv2r2 : 1.0f - (r - s) * (r - s) * inv2r2;
}

struct Fetch1D {
    float offset;  // fetch position minus sample position, texels
    float weight;
};

// Pairs up the texels under the tent: pair k covers texels first + 2k and first + 2k + 1; a bilinear
// fetch at (first + 2k + 0.5) + w1 / (w0 + w1) weights them (w0, w1) / (w0 + w1).
std::vector<Fetch1D> tentFetches1D(float u, float radius) {
    const int pairs = int(radius + 0.5f);     // 1.5 -> 2, 2.5 -> 3, 3.5 -> 4
    const float corner = std::floor(u + 0.5f);  // texel corner nearest u: the tent stays within +-pairs
    const int first = int(corner) - pairs;
    const std::vector<float> w = tentTexelWeights1D(u, radius, first, 2 * pairs);
    std::vector<Fetch1D> fetches(pairs);
    for (int k = 0; k < pairs; ++k) {
        const float w0 = w[2 * k], w1 = w[2 * k + 1];
        const float sum = w0 + w1;
        const float frac = sum > 0.0f ? w1 / sum : 0.5f;
        fetches[k] = {float(first + 2 * k) + 0.5f + frac - u, sum};
    }
    return fetches;
}

}  // namespace

float tentRadius(ShadowFilter filter) { return filterSize(filter) + 0.5f; }

std::vector<float> tentTexelWeights1D(float u, float radius, int first, int count) {
    std::vector<float> weights(std::max(count, 0));
    for (int i = 0; i < count; ++i) {
        const float j = float(first + i);
        weights[i] = tentCdf(j + 1.0f - u, radius) - tentCdf(j - u, radius);
    }
    return weights;
}

std::vector<TentTap> tentFilterTaps(ShadowFilter filter, glm::vec2 texelPosition) {
    if (filter == ShadowFilter::PCF2x2) return {TentTap{glm::vec2(0.0f), 1.0f}};
    const float radius = tentRadius(filter);
    const std::vector<Fetch1D> xs = tentFetches1D(texelPosition.x, radius);
    const std::vector<Fetch1D> ys = tentFetches1D(texelPosition.y, radius);
    std::vector<TentTap> taps;
    taps.reserve(xs.size() * ys.size());
    for (const Fetch1D& y : ys) {
        for (const Fetch1D& x : xs) taps.push_back({glm::vec2(x.offset, y.offset), x.weight * y.weight});
    }
    return taps;
}

}  // namespace penumbra
