// Every cascade count, filter and cascade blend mode renders shadows that agree with the ray-traced
// reference, and softer filters widen the penumbra.
#include <cstdio>

#include "directional_shadow_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 160;
constexpr float kMaxDistance = 40.0f;

void report(const char* what, const CompareMetrics& m) {
    std::printf("[metrics] %-22s misclassified %.3f %%  interior %.3f %%  (false shadow %llu, false lit %llu, "
                "valid %llu)\n",
                what, m.misclassifiedPercent, m.interiorMisclassifiedPercent,
                static_cast<unsigned long long>(m.falseShadow), static_cast<unsigned long long>(m.falseLit),
                static_cast<unsigned long long>(m.validPixels));
}

// Thresholds set from measurement on lavapipe (see the report printed by each test), with headroom.
// Measured misclassified / interior: 1-4 cascades 0.28 / 0.73 / 0.15 / 0.13 % and 0 / 0.07 / 0 / 0 %;
// PCF2x2-7x7 0.13 / 0.18 / 0.28 / 0.34 % and 0 %; blends hard / soft / dither 0.18 / 0.19 / 0.21 % and 0 %
// (with the tutorial's (filter + 1) normal-bias unit PCF7x7 was 0.57 / 0.03 %). The errors stay on the
// shadow edges, wider where a far cascade's texels are large.
constexpr double kMaxMisclassifiedPercent = 1.5;
constexpr double kMaxInteriorMisclassifiedPercent = 0.2;

}  // namespace

TEST_F(DirectionalShadowTest, EachCascadeCountMatchesTheReference) {
    const Scene scene = boxesInDepthScene();
    for (uint32_t count = 1; count <= 4; ++count) {
        const Settings settings = shadowSettings(kMaxDistance, count);
        const CompareMetrics metrics = compareWithReference(scene, renderShadowAov(scene, settings, kSize), settings);
        report(("cascades " + std::to_string(count)).c_str(), metrics);
        ASSERT_GT(metrics.validPixels, kSize * kSize / 3);
        EXPECT_LT(metrics.misclassifiedPercent, kMaxMisclassifiedPercent) << count << " cascades";
        EXPECT_LT(metrics.interiorMisclassifiedPercent, kMaxInteriorMisclassifiedPercent) << count << " cascades";
    }
}

TEST_F(DirectionalShadowTest, EachFilterMatchesTheReference) {
    const Scene scene = boxesInDepthScene();
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        const Settings settings = shadowSettings(kMaxDistance, 4, 1024, filter);
        const CompareMetrics metrics = compareWithReference(scene, renderShadowAov(scene, settings, kSize), settings);
        report(shadowFilterName(filter), metrics);
        EXPECT_LT(metrics.misclassifiedPercent, kMaxMisclassifiedPercent) << shadowFilterName(filter);
        EXPECT_LT(metrics.interiorMisclassifiedPercent, kMaxInteriorMisclassifiedPercent) << shadowFilterName(filter);
    }
}

TEST_F(DirectionalShadowTest, EachCascadeBlendModeMatchesTheReference) {
    const Scene scene = boxesInDepthScene();
    for (CascadeBlend blend : {CascadeBlend::Hard, CascadeBlend::Soft, CascadeBlend::Dither}) {
        Settings settings = shadowSettings(kMaxDistance, 4, 1024, ShadowFilter::PCF3x3, blend);
        settings.shadows.directional.cascadeFade = 0.3f;  // wide blend bands, so blending shows
        const CompareMetrics metrics = compareWithReference(scene, renderShadowAov(scene, settings, kSize), settings);
        report((std::string("blend ") + cascadeBlendName(blend)).c_str(), metrics);
        EXPECT_LT(metrics.misclassifiedPercent, kMaxMisclassifiedPercent) << cascadeBlendName(blend);
        EXPECT_LT(metrics.interiorMisclassifiedPercent, kMaxInteriorMisclassifiedPercent) << cascadeBlendName(blend);
    }
}

TEST_F(DirectionalShadowTest, SofterFiltersGiveWiderPenumbrae) {
    const Scene scene = boxesInDepthScene();
    uint32_t previous = 0;
    for (ShadowFilter filter : {ShadowFilter::PCF2x2, ShadowFilter::PCF3x3, ShadowFilter::PCF5x5, ShadowFilter::PCF7x7}) {
        const Image aov = renderShadowAov(scene, shadowSettings(kMaxDistance, 4, 1024, filter), kSize);
        const uint32_t penumbra = countBetween(aov, 12, 243);
        std::printf("[penumbra] %s: %u pixels strictly between 12 and 243\n", shadowFilterName(filter), penumbra);
        EXPECT_GT(penumbra, previous) << shadowFilterName(filter);
        previous = penumbra;
    }
}
