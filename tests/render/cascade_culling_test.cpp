// Cascade blend culling (Unity's shadowCascadeBlendCullingFactor) never removes a shadow: a caster inside a
// smaller cascade whose long shadow reaches ground sampled by the next cascade is drawn there too.
#include "directional_shadow_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 256, kHeight = 144;

// A 1 m post 2.5 m in front of the camera under an 8° sun shining away from it, shadows out to 30 m:
// the post lies inside 0.7 x cascade 0's sphere (centre 3 m ahead, radius 3.5 m) while its 7 m shadow
// runs on through cascades 1 and 2.
Scene postUnderALowSun() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 120.0f, material);
    addBox(builder, {{0.45f, 0.0f, -2.55f}, {0.55f, 1.0f, -2.45f}}, material);
    const float elevation = glm::radians(8.0f), azimuth = glm::radians(20.0f);
    const glm::vec3 horizontal(std::sin(azimuth), 0.0f, -std::cos(azimuth));
    builder.addLight(makeDirectionalLight(std::cos(elevation) * horizontal - glm::vec3(0, std::sin(elevation), 0), 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 1.6f, 0.0f}, {0.0f, 0.6f, -8.0f}, glm::radians(60.0f)));
    return builder.build();
}

}  // namespace

TEST_F(DirectionalShadowTest, PostsShadowIsWholeAcrossTheCascadeBoundary) {
    const Scene scene = postUnderALowSun();
    Settings settings;  // 4 cascades, cascade fade 0.1: blend culling factor 0.7
    settings.shadows.maxDistance = 30.0f;
    Renderer renderer(device(), scene);
    const Image aov = renderer.render({kWidth, kHeight, OutputMode::ShadowAov, 0, false}, settings).image;
    const Image cascades = renderer.render({kWidth, kHeight, OutputMode::CascadesAov, 0, false}, settings).image;
    const CompareMetrics m = compareWithReference(scene, aov, settings);
    // The shadow lies in the pixels of cascade 0 (red in the cascades AOV) and of cascade 1 (green).
    uint32_t shadowedInCascade[2] = {0, 0};
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            if (aov.at(x, y) >= 128) continue;
            const bool red = cascades.at(x, y, 0) > 200 && cascades.at(x, y, 1) < 100;
            const bool green = cascades.at(x, y, 1) > 200 && cascades.at(x, y, 0) < 100;
            shadowedInCascade[0] += red ? 1 : 0;
            shadowedInCascade[1] += green ? 1 : 0;
        }
    EXPECT_GT(shadowedInCascade[0], 10u);
    EXPECT_GT(shadowedInCascade[1], 10u) << "the part of the shadow in cascade 1 is missing";
    EXPECT_GT(m.edgePixels, 20u);
    EXPECT_EQ(m.interiorFalseLit, 0u) << toText(m);
}
