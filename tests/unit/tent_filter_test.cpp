#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "shadows/tent_filter.h"

using namespace penumbra;

namespace {

const ShadowFilter kTentFilters[] = {ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7};

// The continuous normalized tent of radius r, integrated over [a, b] numerically (midpoint rule).
double tentIntegral(double a, double b, double center, double r) {
    const int steps = 2000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double x = a + (b - a) * (i + 0.5) / steps;
        sum += std::max(0.0, r - std::abs(x - center)) / (r * r);
    }
    return sum * (b - a) / steps;
}

// What the taps weigh each texel with once every bilinear fetch is split onto its 2 x 2 texels.
std::map<std::pair<int, int>, double> texelResponse(const std::vector<TentTap>& taps, glm::vec2 u) {
    std::map<std::pair<int, int>, double> response;
    for (const TentTap& tap : taps) {
        const glm::vec2 p = u + tap.texelOffset - 0.5f;  // fetch position relative to texel centres
        const glm::vec2 base = glm::floor(p);
        const glm::vec2 f = p - base;
        for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
                const double w = (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y);
                response[{int(base.x) + dx, int(base.y) + dy}] += tap.weight * w;
            }
        }
    }
    return response;
}

}  // namespace

TEST(TentFilter, UsesOneFourNineOrSixteenFetches) {
    EXPECT_EQ(tentFilterTaps(ShadowFilter::PCF2x2, {3.3f, 7.9f}).size(), 1u);
    EXPECT_EQ(tentFilterTaps(ShadowFilter::PCF3x3, {3.3f, 7.9f}).size(), 4u);
    EXPECT_EQ(tentFilterTaps(ShadowFilter::PCF5x5, {3.3f, 7.9f}).size(), 9u);
    EXPECT_EQ(tentFilterTaps(ShadowFilter::PCF7x7, {3.3f, 7.9f}).size(), 16u);
}

TEST(TentFilter, WeightsSumToOne) {
    for (ShadowFilter filter : kTentFilters) {
        for (glm::vec2 u : {glm::vec2(10.0f, 10.0f), glm::vec2(10.5f, 3.21f), glm::vec2(0.49f, 7.77f)}) {
            float sum = 0.0f;
            for (const TentTap& tap : tentFilterTaps(filter, u)) sum += tap.weight;
            EXPECT_NEAR(sum, 1.0f, 1e-5f) << shadowFilterName(filter);
        }
    }
}

TEST(TentFilter, IsSymmetricAboutATexelCentre) {
    // Mirroring the sample position about a texel centre mirrors the taps.
    for (ShadowFilter filter : kTentFilters) {
        const std::vector<TentTap> left = tentFilterTaps(filter, {5.5f - 0.2f, 5.5f});
        const std::vector<TentTap> right = tentFilterTaps(filter, {5.5f + 0.2f, 5.5f});
        float leftMoment = 0.0f, rightMoment = 0.0f, leftSpread = 0.0f, rightSpread = 0.0f;
        for (const TentTap& tap : left) {
            leftMoment += tap.weight * (tap.texelOffset.x - 0.2f);
            leftSpread += tap.weight * tap.texelOffset.y * tap.texelOffset.y;
        }
        for (const TentTap& tap : right) {
            rightMoment += tap.weight * (tap.texelOffset.x + 0.2f);
            rightSpread += tap.weight * tap.texelOffset.y * tap.texelOffset.y;
        }
        EXPECT_NEAR(leftMoment, -rightMoment, 1e-5f) << shadowFilterName(filter);
        EXPECT_NEAR(leftSpread, rightSpread, 1e-5f);
    }
}

TEST(TentFilter, CenteredOnATexelTheResponseIsSymmetric) {
    const auto response = texelResponse(tentFilterTaps(ShadowFilter::PCF5x5, {8.5f, 8.5f}), {8.5f, 8.5f});
    EXPECT_NEAR(response.at({6, 8}), response.at({10, 8}), 1e-6);
    EXPECT_NEAR(response.at({8, 6}), response.at({8, 10}), 1e-6);
    EXPECT_NEAR(response.at({7, 9}), response.at({9, 7}), 1e-6);
}

TEST(TentFilter, ResponseEqualsTheContinuousTentIntegratedOverEachTexel) {
    for (ShadowFilter filter : kTentFilters) {
        const double r = tentRadius(filter);
        for (glm::vec2 u : {glm::vec2(20.0f, 20.0f), glm::vec2(20.3f, 19.6f), glm::vec2(20.74f, 20.01f)}) {
            const auto response = texelResponse(tentFilterTaps(filter, u), u);
            double total = 0.0;
            for (int y = 10; y < 30; ++y) {
                for (int x = 10; x < 30; ++x) {
                    const double expected = tentIntegral(x, x + 1, u.x, r) * tentIntegral(y, y + 1, u.y, r);
                    const auto it = response.find({x, y});
                    const double actual = it == response.end() ? 0.0 : it->second;
                    EXPECT_NEAR(actual, expected, 2e-5) << shadowFilterName(filter) << " texel " << x << "," << y;
                    total += actual;
                }
            }
            EXPECT_NEAR(total, 1.0, 1e-5);
        }
    }
}

TEST(TentFilter, PcfTwoByTwoIsOneCentredTap) {
    const std::vector<TentTap> taps = tentFilterTaps(ShadowFilter::PCF2x2, {4.2f, 1.1f});
    EXPECT_EQ(taps[0].texelOffset, glm::vec2(0.0f));
    EXPECT_EQ(taps[0].weight, 1.0f);
}

TEST(TentFilter, TexelWeightsOfTheThreeByThreeTentAtATexelCentre) {
    // Radius 1.5 centred on texel 0's centre: each neighbour holds a triangle of height 1/1.5 and base 1,
    // area (1/2)(1)(2/3) = 1/3 of the unnormalized tent area 1.5, i.e. 2/9; the centre texel the rest.
    const std::vector<float> w = tentTexelWeights1D(0.5f, 1.5f, -1, 3);
    EXPECT_NEAR(w[0], 2.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(w[1], 5.0f / 9.0f, 1e-6f);
    EXPECT_NEAR(w[2], 2.0f / 9.0f, 1e-6f);
}
