// The GPU tent filters (penumbra/shadows/tent.glsl) give, pixel by pixel, the attenuation their CPU twin
// (src/shadows/tent_filter.cpp) predicts across a straight shadow edge: the tent's width and shape are
// checked on the GPU, not just that wider filters blur more.
#include <cmath>
#include <cstdio>

#include "directional_shadow_scenes.h"
#include "shadows/shadow_planner.h"
#include "shadows/tent_filter.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 128;

// A plate over x < 0 high above a ground, the sun straight down, the camera between them looking down:
// the shadow edge is the line x = 0, along one axis of the shadow map's texel grid.
Scene edgeUnderAVerticalSun() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 40.0f, material);
    addBox(builder, {{-30.0f, 10.0f, -30.0f}, {0.0f, 10.1f, 30.0f}}, material);
    builder.addLight(makeDirectionalLight({0.0f, -1.0f, 0.0f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.3f, 5.0f, 0.0f}, {0.3f, 0.0f, 0.0f}, glm::radians(20.0f)));
    return builder.build();
}

// The filter's weight of texel column j for a sample at texel coordinate u: the tent integrated over
// each texel (tent_filter.h), or the bilinear hat of the single hardware tap for PCF2x2.
float texelWeight(ShadowFilter filter, float u, int j) {
    if (filter == ShadowFilter::PCF2x2) return std::max(0.0f, 1.0f - std::abs(u - (float(j) + 0.5f)));
    return tentTexelWeights1D(u, tentRadius(filter), j, 1)[0];
}

}  // namespace

TEST_F(DirectionalShadowTest, GpuFiltersMatchTheirCpuTwinAcrossAStraightEdge) {
    const Scene scene = edgeUnderAVerticalSun();
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        SCOPED_TRACE(shadowFilterName(filter));
        const Settings settings = shadowSettings(8.0f, 1, 256, filter);  // one 256-texel tile: ~5 cm texels
        const Image aov = renderShadowAov(scene, settings, kSize);
        const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
        const glm::mat4& atlasFromWorld = plan.directional.tiles.at(0).atlasFromWorld;
        const float atlasSize = float(plan.directional.atlas.atlasSize);
        auto texelU = [&](glm::vec3 p) { return (atlasFromWorld * glm::vec4(p, 1.0f)).x * atlasSize; };
        const float edge = texelU({0, 0, 0});
        const bool litSideIsAbove = texelU({1, 0, 0}) > edge;  // the ground at x > 0 is lit
        uint32_t penumbraPixels = 0;
        int worst = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const auto ground = visibleGroundPoint(view, x, y, 20.0f, {});
                if (!ground) continue;
                const float u = texelU(*ground);
                float expected = 0.0f;
                for (int j = int(std::floor(u)) - 5; j <= int(std::floor(u)) + 5; ++j) {
                    const bool lit = (float(j) + 0.5f > edge) == litSideIsAbove;
                    expected += lit ? texelWeight(filter, u, j) : 0.0f;
                }
                penumbraPixels += expected > 0.05f && expected < 0.95f ? 1 : 0;
                worst = std::max(worst, std::abs(int(aov.at(x, y)) - int(std::lround(255.0f * expected))));
            }
        std::printf("[tent] %s: %u penumbra pixels, worst difference %d levels\n", shadowFilterName(filter),
                    penumbraPixels, worst);
        EXPECT_GT(penumbraPixels, kSize) << "the edge should cross the view with a penumbra of pixels";
        EXPECT_LE(worst, 2) << "8-bit AOV levels between the GPU filter and its CPU twin";
    }
}
