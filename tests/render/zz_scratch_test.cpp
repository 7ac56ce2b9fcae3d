#include "directional_shadow_scenes.h"
using namespace penumbra;
using namespace penumbra::test;
TEST_F(DirectionalShadowTest, Scratch) {
    for (float nb : {0.0f, 1.0f}) for (float sb : {0.0f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f}) {
        SceneBuilder builder;
        const uint32_t material = builder.addMaterial(matteMaterial());
        addGround(builder, 60.0f, material);
        const float angle = glm::radians(60.0f);
        Light l = makeDirectionalLight({std::sin(angle), -std::cos(angle), 0.3f * std::sin(angle)}, 3.0f);
        l.shadowNormalBias = nb; l.shadowBias = sb;
        builder.addLight(l);
        builder.setCamera(makeLookAtCamera({0.0f, 4.0f, 10.0f}, {0.0f, 0.0f, -6.0f}, glm::radians(60.0f)));
        const Scene scene = builder.build();
        const Image aov = renderShadowAov(scene, shadowSettings(30.0f, 4, 1024, ShadowFilter::PCF2x2), 128);
        const auto shadowed = std::count_if(aov.pixels.begin(), aov.pixels.end(), [](uint8_t v) { return v < 250; });
        std::cout << "nb " << nb << " sb " << sb << " acne pixels " << shadowed << "\n";
    }
}
