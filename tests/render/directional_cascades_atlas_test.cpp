// The debug views of the directional shadows: `--aov cascades` picks cascades by culling sphere, nearer
// pixels using lower indices (Catlike Coding "Directional Shadows", Sampling Cascades), and the atlas dump
// shows the tile layout of its Rendering Cascades (split 1 / 2 / 4, tiles = lights x cascades, untouched
// texels at the clear depth).
#include <array>
#include <cstdio>

#include "directional_shadow_scenes.h"

#include "shadows/shadow_fade.h"
#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 128;

// A long ground, seen from low above so that view depth grows up the image; it casts on itself, which
// is enough for the light to get shadow tiles.
Scene longGround(uint32_t lightCount = 1) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 200.0f, material);
    addBox(builder, {{-1.0f, 0.0f, -6.0f}, {1.0f, 2.0f, -4.0f}}, material);
    const glm::vec3 directions[4] = {{0.5f, -1.0f, 0.2f}, {-0.6f, -1.0f, 0.1f}, {0.1f, -1.0f, 0.7f}, {0.3f, -1.0f, -0.6f}};
    for (uint32_t i = 0; i < lightCount; ++i) builder.addLight(makeDirectionalLight(directions[i], 1.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 3.0f, 4.0f}, {0.0f, 0.0f, -20.0f}, glm::radians(60.0f)));
    return builder.build();
}

// The colours of lit.frag.glsl's cascadeColor(), as 8-bit UNORM: none, cascade 0, 1, 2, 3.
int decodeCascade(const Image& image, uint32_t x, uint32_t y) {
    const std::array<glm::vec3, 5> colors = {glm::vec3(0, 0, 0), glm::vec3(255, 64, 64), glm::vec3(64, 255, 64),
                                             glm::vec3(64, 102, 255), glm::vec3(255, 255, 64)};
    const glm::vec3 pixel(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
    int best = 0;
    for (int i = 1; i < 5; ++i) {
        if (glm::distance(pixel, colors[i]) < glm::distance(pixel, colors[best])) best = i;
    }
    return best - 1;
}

// Texels of the tile `tileIndex` (split x split tiles) whose depth is below the clear value.
uint32_t writtenTexels(const Image& atlas, uint32_t split, uint32_t tileIndex) {
    const uint32_t tileSize = atlas.width / split;
    const uint32_t x0 = (tileIndex % split) * tileSize, y0 = (tileIndex / split) * tileSize;
    uint32_t written = 0;
    for (uint32_t y = y0; y < y0 + tileSize; ++y)
        for (uint32_t x = x0; x < x0 + tileSize; ++x) written += atlas.at(x, y) < 255;
    return written;
}

}  // namespace

TEST_F(DirectionalShadowTest, CascadesAovShowsTheCascadeEachPixelSamples) {
    const Scene scene = longGround();
    const Settings settings = shadowSettings(40.0f, 4, 512);
    const Image aov = renderScene(scene, RenderRequest{kSize, kSize, OutputMode::CascadesAov, 0, false}, settings).image;
    ASSERT_EQ(aov.channels, 3u);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t ground = 0, agree = 0;
    std::array<double, 4> depthSum{};
    std::array<uint32_t, 4> count{};
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const auto wsPosition = visibleGroundPoint(view, x, y, 100.0f, {{{-1.0f, 0.0f, -6.0f}, {1.0f, 2.0f, -4.0f}}});
            if (!wsPosition) continue;
            const float viewDepth = -(view.viewFromWorld * glm::vec4(*wsPosition, 1.0f)).z;
            const CascadeSelection expected = selectCascade(plan.directional.gpu, *wsPosition, viewDepth);
            const int expectedIndex = expected.cascadeIndex < 4 ? int(expected.cascadeIndex) : -1;
            const int actual = decodeCascade(aov, x, y);
            ++ground;
            agree += actual == expectedIndex;
            if (actual >= 0) {
                depthSum[actual] += viewDepth;
                ++count[actual];
            }
        }
    }
    ASSERT_GT(ground, kSize * kSize / 3);
    // Disagreements only where a sphere's rim crosses a pixel.
    EXPECT_GT(double(agree) / ground, 0.99) << agree << " of " << ground;
    for (int i = 0; i < 4; ++i) ASSERT_GT(count[i], 20u) << "cascade " << i << " is never used";
    for (int i = 1; i < 4; ++i)
        EXPECT_GT(depthSum[i] / count[i], depthSum[i - 1] / count[i - 1]) << "cascade " << i << " is not farther";
}

TEST_F(DirectionalShadowTest, AtlasDumpHasOneTilePerCascadeInTheSplitLayout) {
    struct Case {
        uint32_t lights, cascades, split;
    };
    for (const Case c : {Case{1, 1, 1}, Case{1, 2, 2}, Case{1, 4, 2}, Case{2, 3, 4}, Case{4, 4, 4}}) {
        const Scene scene = longGround(c.lights);
        RenderRequest request{64, 64, OutputMode::Color, 0, true};
        const RenderResult result = renderScene(scene, request, shadowSettings(40.0f, c.cascades, 512));
        ASSERT_EQ(result.atlas.width, 512u);
        ASSERT_EQ(result.atlas.channels, 1u);
        const uint32_t tileTexels = (512 / c.split) * (512 / c.split);
        for (uint32_t tile = 0; tile < c.split * c.split; ++tile) {
            const uint32_t written = writtenTexels(result.atlas, c.split, tile);
            if (tile < c.lights * c.cascades) {
                EXPECT_GT(written, tileTexels / 4) << c.lights << " lights x " << c.cascades << ", tile " << tile;
            } else {
                EXPECT_EQ(written, 0u) << c.lights << " lights x " << c.cascades << ", tile " << tile;
            }
        }
    }
}

TEST_F(DirectionalShadowTest, DitherBlendMixesNeighbouringCascadesInTheBlendBands) {
    // Dithered transition: in cascade i's fade band a pixel samples cascade i + 1 when the interleaved
    // gradient noise exceeds the blend weight, so a fraction 1 - blend of the band's pixels shows i + 1.
    const Scene scene = longGround();
    Settings settings = shadowSettings(40.0f, 4, 512, ShadowFilter::PCF2x2, CascadeBlend::Dither);
    settings.shadows.directional.cascadeFade = 0.5f;
    const Image aov = renderScene(scene, RenderRequest{kSize, kSize, OutputMode::CascadesAov, 0, false}, settings).image;
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t bandPixels = 0, outsideBand = 0, outsideAgree = 0, bandUnexpected = 0;
    double expectedNext = 0.0, actualNext = 0.0;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const auto wsPosition = visibleGroundPoint(view, x, y, 100.0f, {{{-1.0f, 0.0f, -6.0f}, {1.0f, 2.0f, -4.0f}}});
            if (!wsPosition) continue;
            const float viewDepth = -(view.viewFromWorld * glm::vec4(*wsPosition, 1.0f)).z;
            const CascadeSelection expected = selectCascade(plan.directional.gpu, *wsPosition, viewDepth);
            const int actual = decodeCascade(aov, x, y);
            const int index = expected.cascadeIndex < 4 ? int(expected.cascadeIndex) : -1;
            if (expected.cascadeBlend < 1.0f) {
                ++bandPixels;
                expectedNext += 1.0 - expected.cascadeBlend;
                actualNext += actual == index + 1;
                bandUnexpected += actual != index && actual != index + 1;
            } else {
                ++outsideBand;
                outsideAgree += actual == index;
            }
        }
    }
    std::printf("[dither blend] %u band pixels: %.3f show the next cascade, %.3f expected\n", bandPixels,
                actualNext / bandPixels, expectedNext / bandPixels);
    ASSERT_GT(bandPixels, 1000u);
    EXPECT_LT(bandUnexpected, bandPixels / 100);
    EXPECT_NEAR(actualNext / bandPixels, expectedNext / bandPixels, 0.05) << "share of band pixels in the next cascade";
    EXPECT_GT(double(outsideAgree) / outsideBand, 0.99);
}

TEST_F(DirectionalShadowTest, SoftBlendChangesTheShadowOnlyInsideCascadeBlendBands) {
    const Scene scene = boxesInDepthScene();
    Settings settings = shadowSettings(40.0f, 4, 1024, ShadowFilter::PCF2x2, CascadeBlend::Hard);
    settings.shadows.directional.cascadeFade = 0.5f;
    const Image hard = renderShadowAov(scene, settings, kSize);
    settings.shadows.directional.cascadeBlend = CascadeBlend::Soft;
    const Image soft = renderShadowAov(scene, settings, kSize);
    const CameraView view = resolveCameraView(scene, kSize, kSize);
    const ShadowFrame plan = ShadowPlanner::plan(scene, view, settings.shadows);
    uint32_t changedInBand = 0, changedOutside = 0;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const auto wsPosition = visibleGroundPoint(view, x, y, 40.0f, boxesInDepth());
            if (!wsPosition || std::abs(int(hard.at(x, y)) - int(soft.at(x, y))) <= 1) continue;
            const float viewDepth = -(view.viewFromWorld * glm::vec4(*wsPosition, 1.0f)).z;
            const bool inBand = selectCascade(plan.directional.gpu, *wsPosition, viewDepth).cascadeBlend < 1.0f;
            (inBand ? changedInBand : changedOutside) += 1;
        }
    }
    std::printf("[soft blend] pixels changed from hard: %u inside blend bands, %u outside\n", changedInBand,
                changedOutside);
    EXPECT_GT(changedInBand, 20u);
    EXPECT_EQ(changedOutside, 0u);
}
