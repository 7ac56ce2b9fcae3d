// glTF samplers on the GPU: the main view and the shadow casters sample each
// texture with its own filters and wrap modes, the rule of scene/texture_sampler.h.
#include <glm/gtc/matrix_transform.hpp>

#include "directional_shadow_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// 4 x 1 texels, alpha 160, 0, 0, 0 (white). NEAREST + CLAMP_TO_EDGE: the left quarter (u < 0.25) is
// opaque at cutoff 0.5. LINEAR + REPEAT (the old fixed sampler) would blend texel 0 with texel 3 across
// the seam and keep only u in [0.075, 0.175] above the cutoff.
Texture quarterStripTexture(const TextureSampler& sampler) {
    Texture texture;
    texture.name = "strip";
    texture.rgba = Image(4, 1, 4, 255);
    for (uint32_t x = 0; x < 4; ++x) texture.rgba.at(x, 0, 3) = x == 0 ? 160 : 0;
    texture.sampler = sampler;
    return texture;
}

TextureSampler nearestClamped() {
    TextureSampler sampler;
    sampler.magFilter = sampler.minFilter = TextureFilter::Nearest;
    sampler.mipmaps = MipmapMode::None;
    sampler.wrapS = sampler.wrapT = TextureWrap::ClampToEdge;
    return sampler;
}

Material maskMaterial(bool unlit) {
    Material mask = matteMaterial(glm::vec4(1.0f));
    mask.unlit = unlit;
    mask.alphaMode = AlphaMode::Mask;
    mask.alphaCutoff = 0.5f;
    mask.doubleSided = true;
    mask.shadows = MaterialShadowMode::Clip;
    mask.baseColorTexture = 0;
    return mask;
}

// Fraction of the pixels in column range [x0, x1) of row y that are white (the quad) rather than red.
float whiteFraction(const Image& image, uint32_t y, uint32_t x0, uint32_t x1) {
    uint32_t white = 0;
    for (uint32_t x = x0; x < x1; ++x) white += image.at(x, y, 1) > 128 ? 1 : 0;
    return float(white) / float(x1 - x0);
}

// An unlit 2 x 2 m quad at z = 0 filling the middle of a 64 x 64 view, a red backdrop behind it.
Scene quadOverBackdrop(const Texture& texture, float distance) {
    SceneBuilder builder;
    Material red;
    red.unlit = true;
    red.baseColorFactor = glm::vec4(1, 0, 0, 1);
    const uint32_t backdrop = builder.addMaterial(red);
    const uint32_t quad = builder.addMaterial(maskMaterial(true));
    builder.addTexture(texture);
    builder.addInstance(builder.addMesh(makeQuadMesh({400, 400}, backdrop)), glm::translate(glm::mat4(1), {0, 0, -1}));
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, quad)), glm::mat4(1));
    builder.setCamera(makeLookAtCamera({0, 0, distance}, {0, 0, 0}, 2.0f * std::atan(2.0f / distance)));
    return builder.build();
}

}  // namespace

TEST_F(RenderTest, MainViewSamplesANearestClampedTextureTexelByTexel) {
    const RenderResult result = renderScene(quadOverBackdrop(quarterStripTexture(nearestClamped()), 2.0f), {64, 64});
    // The quad spans the middle 32 columns (16..47): its left quarter, columns 16..23, is opaque.
    EXPECT_GT(whiteFraction(result.image, 32, 16, 24), 0.99f);
    EXPECT_LT(whiteFraction(result.image, 32, 24, 48), 0.01f);
}

TEST_F(RenderTest, MinFilterWithoutMipmapsSamplesLevelZeroWhenMinified) {
    // Stripes of 2 opaque and 1 clear texel, 256 texels over the quad, seen 8 x minified: the mip levels
    // average alpha to 2/3 (all opaque), level 0 shows the clear stripes at a third of the pixel centres.
    Texture stripes;
    stripes.rgba = Image(256, 256, 4, 255);
    for (uint32_t y = 0; y < 256; ++y)
        for (uint32_t x = 2; x < 256; x += 3) stripes.rgba.at(x, y, 3) = 0;
    stripes.sampler = nearestClamped();
    const RenderResult levelZero = renderScene(quadOverBackdrop(stripes, 2.0f), {64, 64});
    stripes.sampler = TextureSampler{};  // LINEAR_MIPMAP_LINEAR, the default
    const RenderResult mipmapped = renderScene(quadOverBackdrop(stripes, 2.0f), {64, 64});
    uint32_t clearLevelZero = 0, clearMipmapped = 0;
    for (uint32_t y = 17; y < 47; ++y) {
        clearLevelZero += uint32_t(std::lround((1.0f - whiteFraction(levelZero.image, y, 17, 47)) * 30.0f));
        clearMipmapped += uint32_t(std::lround((1.0f - whiteFraction(mipmapped.image, y, 17, 47)) * 30.0f));
    }
    EXPECT_GT(clearLevelZero, 30u * 30u / 10) << "level 0: some pixel centres fall on the clear stripes";
    EXPECT_EQ(clearMipmapped, 0u) << "the generated mip chain averages the stripes to alpha 2/3";
}

TEST_F(DirectionalShadowTest, ShadowOfAMaskTextureFollowsItsSampler) {
    // The strip texture on a horizontal 2 x 2 m quad 1 m above the ground: its shadow is the shadow of
    // the opaque strip x in [-1, -0.5], z in [-1, 1] alone.
    SceneBuilder builder;
    const uint32_t ground = builder.addMaterial(matteMaterial());
    addGround(builder, 20.0f, ground);
    const uint32_t mask = builder.addMaterial(maskMaterial(false));
    builder.addTexture(quarterStripTexture(nearestClamped()));
    const glm::mat4 pose = glm::rotate(glm::translate(glm::mat4(1), {0, 1, 0}), glm::radians(-90.0f), {1, 0, 0});
    builder.addInstance(builder.addMesh(makeQuadMesh({2, 2}, mask)), pose);
    const glm::vec3 sun(0.3f, -1.0f, 0.2f);
    builder.addLight(makeDirectionalLight(sun, 3.0f));
    builder.setCamera(makeLookAtCamera({0, 6, 2}, {-0.3f, 0, 0}, glm::radians(40.0f)));
    const Scene scene = builder.build();

    const Settings settings = shadowSettings(10.0f, 1, 2048);
    const Image aov = renderShadowAov(scene, settings, 128);
    const CameraView view = resolveCameraView(scene, 128, 128);
    const AnalyticShadow truth = analyticGroundShadow(view, 10.0f, {{{-1.0f, 0.999f, -1.0f}, {-0.5f, 1.001f, 1.0f}}}, sun);
    const CompareMetrics m = compareShadowImages(aov, truth.shadow, truth.validMask);
    EXPECT_GT(m.edgePixels, 40u);
    EXPECT_EQ(m.interiorFalseShadow + m.interiorFalseLit, 0u) << toText(m);
    EXPECT_LT(m.edgeErrorPixels, 1.0) << toText(m);
}
