// Alpha-tested (MASK) and alpha-blended (BLEND) materials in the main view.
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "penumbra/scene_builder.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// 8x8 texels: alpha 0 in the left half, 1 in the right half; colour white.
Texture halfTransparentTexture() {
    Texture texture;
    texture.rgba = Image(8, 8, 4, 255);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 4; ++x) texture.rgba.at(x, y, 3) = 0;
    return texture;
}

// A red unlit backdrop at z = -1 behind a 2 x 2 m unlit quad at z = 0 that fills the view; `texture`,
// when given, is texture 0 (added before the materials, so SceneBuilder's checks hold).
Scene quadInFrontOfBackdrop(const Material& quadMaterial, const Texture* texture = nullptr) {
    SceneBuilder builder;
    if (texture) builder.addTexture(*texture);
    Material red;
    red.unlit = true;
    red.baseColorFactor = glm::vec4(1, 0, 0, 1);
    const uint32_t backdrop = builder.addMaterial(red);
    const uint32_t quad = builder.addMaterial(quadMaterial);
    builder.addInstance(builder.addMesh(makeQuadMesh({10, 10}, backdrop)), glm::translate(glm::mat4(1), {0, 0, -1}));
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, quad)), glm::mat4(1));
    builder.setCamera(makeLookAtCamera({0, 0, 2}, {0, 0, 0}, 2.0f * std::atan(0.45f)));
    return builder.build();
}

// The expected values below are the base colours and their linear blends: no tone mapping.
Settings linearOutput() {
    Settings settings;
    settings.render.toneMapping = ToneMapping::None;
    return settings;
}

}  // namespace

TEST_F(RenderTest, MaskMaterialShowsHolesWhereTextureAlphaIsBelowCutoff) {
    Material mask;
    mask.unlit = true;
    mask.alphaMode = AlphaMode::Mask;
    mask.alphaCutoff = 0.5f;
    mask.baseColorTexture = 0;
    const Texture texture = halfTransparentTexture();
    const Scene scene = quadInFrontOfBackdrop(mask, &texture);
    const RenderResult result = renderScene(scene, {64, 64}, linearOutput());
    // Left half of the quad: the red backdrop shows through; right half: the white quad.
    EXPECT_EQ(result.image.at(12, 32, 0), 255);
    EXPECT_EQ(result.image.at(12, 32, 1), 0);
    EXPECT_EQ(result.image.at(52, 32, 1), 255);
}

TEST_F(RenderTest, OpaqueMaterialIgnoresTextureAlpha) {
    Material opaque;
    opaque.unlit = true;
    opaque.baseColorTexture = 0;
    const Texture texture = halfTransparentTexture();
    const Scene scene = quadInFrontOfBackdrop(opaque, &texture);
    const RenderResult result = renderScene(scene, {64, 64}, linearOutput());
    EXPECT_EQ(result.image.at(12, 32, 1), 255);
}

TEST_F(RenderTest, BlendMaterialMixesWithWhatIsBehindIt) {
    Material glass;
    glass.unlit = true;
    glass.alphaMode = AlphaMode::Blend;
    glass.baseColorFactor = glm::vec4(0, 0, 1, 0.5f);
    const RenderResult result = renderScene(quadInFrontOfBackdrop(glass), {64, 64}, linearOutput());
    // Linear 0.5 red + 0.5 blue, sRGB-encoded: 188.
    EXPECT_NEAR(result.image.at(32, 32, 0), 188, 2);
    EXPECT_NEAR(result.image.at(32, 32, 2), 188, 2);
}

TEST_F(RenderTest, BlendedSurfacesAreDrawnBackToFront) {
    // Two half-transparent quads: blue at z = 0.5 (nearer), green at z = 0. Back to front gives
    // blue over (green over red): the nearer colour weighs most.
    SceneBuilder builder;
    Material red, green, blue;
    red.unlit = green.unlit = blue.unlit = true;
    red.baseColorFactor = {1, 0, 0, 1};
    green.alphaMode = blue.alphaMode = AlphaMode::Blend;
    green.baseColorFactor = {0, 1, 0, 0.5f};
    blue.baseColorFactor = {0, 0, 1, 0.5f};
    const uint32_t r = builder.addMaterial(red), g = builder.addMaterial(green), b = builder.addMaterial(blue);
    builder.addInstance(builder.addMesh(makeQuadMesh({10, 10}, r)), glm::translate(glm::mat4(1), {0, 0, -1}));
    // Added nearest first, so scene order is the wrong order for blending.
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, b)), glm::translate(glm::mat4(1), {0, 0, 0.5f}));
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, g)), glm::mat4(1));
    builder.setCamera(makeLookAtCamera({0, 0, 3}, {0, 0, 0}, 0.5f));
    const RenderResult result = renderScene(builder.build(), {32, 32}, linearOutput());
    const float redLinear = srgbToLinear(result.image.at(16, 16, 0));
    const float greenLinear = srgbToLinear(result.image.at(16, 16, 1));
    const float blueLinear = srgbToLinear(result.image.at(16, 16, 2));
    EXPECT_NEAR(redLinear, 0.25f, 0.02f);
    EXPECT_NEAR(greenLinear, 0.25f, 0.02f);
    EXPECT_NEAR(blueLinear, 0.5f, 0.02f);
}
