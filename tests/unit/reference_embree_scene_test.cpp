// Which surfaces camera rays and shadow rays see in the reference's Embree scene (embree_scene.h).
#include <gtest/gtest.h>

#include "core/error.h"
#include "reference/embree_scene.h"
#include "reference/material_alpha.h"
#include "reference_test_scenes.h"

namespace penumbra {
namespace {

using namespace penumbra::test;

constexpr glm::vec3 kDown{0.0f, -1.0f, 0.0f};
constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};
constexpr float kInf = std::numeric_limits<float>::infinity();

// A ground quad (instance 0) under a 2x2 quad at height 1 (instance 1) made of `material`.
Scene groundUnderQuad(const Material& material, bool quadCastsShadows = true) {
    Scene scene = emptyScene();
    const uint32_t quadMaterial = addMaterial(scene, material);
    addObject(scene, horizontalQuad(0.0f, -4.0f, 4.0f, -4.0f, 4.0f));
    addObject(scene, horizontalQuad(1.0f, -1.0f, 1.0f, -1.0f, 1.0f, quadMaterial), quadCastsShadows);
    return scene;
}

Material namedMaterial(const char* name) {
    Material m;
    m.name = name;
    return m;
}

TEST(ReferenceEmbreeScene, CameraRayReportsTheNearestInstanceAndItsSurface) {
    const EmbreeScene scene(groundUnderQuad(namedMaterial("plain")));
    const auto hit = scene.intersectCamera({0.25f, 5.0f, 0.5f}, kDown, 0.0f, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->instanceIndex, 1u);
    EXPECT_NEAR(hit->t, 4.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(hit->wsPosition, glm::vec3(0.25f, 1.0f, 0.5f)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(hit->wsGeometricNormal, kUp), 0.0f, 1e-5f);
    EXPECT_TRUE(hit->frontFacing);
    EXPECT_EQ(scene.triangleCount(), 4u);
}

TEST(ReferenceEmbreeScene, CameraRaysSkipTheBackOfSingleSidedSurfaces) {
    const EmbreeScene scene(groundUnderQuad(namedMaterial("single-sided")));
    EXPECT_FALSE(scene.intersectCamera({0.0f, 0.5f, 0.0f}, kUp, 0.0f, kInf));
}

TEST(ReferenceEmbreeScene, CameraRaysSeeTheBackOfDoubleSidedSurfaces) {
    Material m = namedMaterial("double-sided");
    m.doubleSided = true;
    const EmbreeScene scene(groundUnderQuad(m));
    const auto hit = scene.intersectCamera({0.0f, 0.5f, 0.0f}, kUp, 0.0f, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->instanceIndex, 1u);
    EXPECT_FALSE(hit->frontFacing);
}

TEST(ReferenceEmbreeScene, ShadowRaysAreBlockedByBothFaces) {
    const EmbreeScene scene(groundUnderQuad(namedMaterial("single-sided")));
    EXPECT_TRUE(scene.occluded({0.0f, 0.5f, 0.0f}, kUp, 0.0f, kInf));
    EXPECT_TRUE(scene.occluded({0.0f, 1.5f, 0.0f}, kDown, 0.0f, 1.0f));
}

TEST(ReferenceEmbreeScene, ShadowRayStopsAtItsFarDistance) {
    const EmbreeScene scene(groundUnderQuad(namedMaterial("plain")));
    EXPECT_FALSE(scene.occluded({0.0f, 0.5f, 0.0f}, kUp, 0.0f, 0.4f));
}

TEST(ReferenceEmbreeScene, InstanceThatCastsNoShadowsIsSeenButDoesNotBlock) {
    const EmbreeScene scene(groundUnderQuad(namedMaterial("plain"), false));
    EXPECT_FALSE(scene.occluded({0.0f, 0.5f, 0.0f}, kUp, 0.0f, kInf));
    const auto hit = scene.intersectCamera({0.0f, 5.0f, 0.0f}, kDown, 0.0f, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->instanceIndex, 1u);
}

TEST(ReferenceEmbreeScene, MaterialWithShadowsOffIsSeenButDoesNotBlock) {
    Material m = namedMaterial("no shadows");
    m.shadows = MaterialShadowMode::Off;
    const EmbreeScene scene(groundUnderQuad(m));
    EXPECT_FALSE(scene.occluded({0.0f, 0.5f, 0.0f}, kUp, 0.0f, kInf));
    EXPECT_TRUE(scene.intersectCamera({0.0f, 5.0f, 0.0f}, kDown, 0.0f, kInf));
}

// A 4x4 texture, opaque but for its central 2x2 texels: over the quad, a hole at |x|, |z| < 0.5.
Scene groundUnderHoledQuad(AlphaMode alphaMode, MaterialShadowMode shadows) {
    Material m = namedMaterial("holed");
    m.alphaMode = alphaMode;
    m.shadows = shadows;
    m.baseColorTexture = 0;
    Scene scene = groundUnderQuad(m);
    Texture texture;
    texture.rgba = Image(4, 4, 4, 255);
    for (uint32_t y = 1; y <= 2; ++y)
        for (uint32_t x = 1; x <= 2; ++x) texture.rgba.at(x, y, 3) = 0;
    scene.textures.push_back(texture);
    return scene;
}

TEST(ReferenceEmbreeScene, ClipShadowsPassThroughTransparentTexelsOnly) {
    const EmbreeScene scene(groundUnderHoledQuad(AlphaMode::Mask, MaterialShadowMode::Clip));
    EXPECT_FALSE(scene.occluded({0.1f, 0.5f, -0.2f}, kUp, 0.0f, kInf));
    EXPECT_TRUE(scene.occluded({-0.8f, 0.5f, -0.8f}, kUp, 0.0f, kInf));
}

TEST(ReferenceEmbreeScene, CameraRaysSeeThroughTransparentTexelsOfMaskMaterials) {
    const EmbreeScene scene(groundUnderHoledQuad(AlphaMode::Mask, MaterialShadowMode::Clip));
    const auto throughHole = scene.intersectCamera({0.1f, 5.0f, -0.2f}, kDown, 0.0f, kInf);
    const auto onTexels = scene.intersectCamera({-0.8f, 5.0f, -0.8f}, kDown, 0.0f, kInf);
    ASSERT_TRUE(throughHole && onTexels);
    EXPECT_EQ(throughHole->instanceIndex, 0u);
    EXPECT_EQ(onTexels->instanceIndex, 1u);
}

TEST(ReferenceEmbreeScene, ShadowModeOnBlocksEvenWhereTheTextureIsTransparent) {
    const EmbreeScene scene(groundUnderHoledQuad(AlphaMode::Mask, MaterialShadowMode::On));
    EXPECT_TRUE(scene.occluded({0.1f, 0.5f, -0.2f}, kUp, 0.0f, kInf));
}

TEST(ReferenceEmbreeScene, BlendSurfacesAreInvisibleToCameraRays) {
    Material m = namedMaterial("glass");
    m.alphaMode = AlphaMode::Blend;
    m.shadows = MaterialShadowMode::Dither;
    const EmbreeScene scene(groundUnderQuad(m));
    const auto hit = scene.intersectCamera({0.0f, 5.0f, 0.0f}, kDown, 0.0f, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->instanceIndex, 0u);
}

TEST(ReferenceEmbreeScene, DitheredShadowsBlockAboutAlphaOfTheRaysDeterministically) {
    Material m = namedMaterial("glass");
    m.alphaMode = AlphaMode::Blend;
    m.shadows = MaterialShadowMode::Dither;
    m.baseColorFactor.a = 0.3f;
    const EmbreeScene scene(groundUnderQuad(m));
    int blocked = 0;
    constexpr int kRays = 4000;
    for (int i = 0; i < kRays; ++i) {
        const glm::vec3 origin(-0.9f + 1.8f * float(i % 63) / 63.0f, 0.5f, -0.9f + 1.8f * float(i / 63) / 64.0f);
        const bool first = scene.occluded(origin, kUp, 0.0f, kInf);
        EXPECT_EQ(first, scene.occluded(origin, kUp, 0.0f, kInf));
        blocked += first ? 1 : 0;
    }
    EXPECT_NEAR(double(blocked) / kRays, 0.3, 0.04);
}

TEST(ReferenceEmbreeScene, MirroringTransformKeepsTheFrontSide) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(1.0f, -1.0f, 1.0f, -1.0f, 1.0f));
    scene.instances[0].worldFromObject = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
    const EmbreeScene embree(scene);
    const auto fromAbove = embree.intersectCamera({0.2f, 5.0f, 0.3f}, kDown, 0.0f, kInf);
    ASSERT_TRUE(fromAbove);
    EXPECT_GT(fromAbove->wsGeometricNormal.y, 0.99f);
    EXPECT_FALSE(embree.intersectCamera({0.2f, -5.0f, 0.3f}, kUp, 0.0f, kInf));
}

TEST(ReferenceEmbreeScene, InstanceOfAMissingMeshIsAnError) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(1.0f, -1.0f, 1.0f, -1.0f, 1.0f));
    scene.instances[0].meshIndex = 7;
    EXPECT_THROW(EmbreeScene embree(scene), Error);
}

TEST(ReferenceMaterialAlpha, BilinearAlphaWrapsAroundTheTextureEdges) {
    Material m;
    m.baseColorFactor.a = 0.5f;
    Texture texture;
    texture.rgba = Image(2, 1, 4, 255);
    texture.rgba.at(1, 0, 3) = 0;
    // Texel centres at u = 0.25 (alpha 1) and 0.75 (alpha 0); u = 0 lies halfway across the seam.
    EXPECT_NEAR(baseColorAlpha(m, &texture, {0.25f, 0.5f}), 0.5f, 1e-6f);
    EXPECT_NEAR(baseColorAlpha(m, &texture, {0.75f, 0.5f}), 0.0f, 1e-6f);
    EXPECT_NEAR(baseColorAlpha(m, &texture, {0.0f, 0.5f}), 0.25f, 1e-6f);
    EXPECT_NEAR(baseColorAlpha(m, &texture, {-1.75f, 3.5f}), 0.5f, 1e-6f);
    EXPECT_NEAR(baseColorAlpha(m, nullptr, {0.75f, 0.5f}), 0.5f, 1e-6f);
}

TEST(ReferenceMaterialAlpha, NearestClampedSamplerGivesTheTexelUnderTheSample) {
    Material m;
    Texture texture;
    texture.rgba = Image(2, 1, 4, 255);
    texture.rgba.at(1, 0, 3) = 0;
    texture.sampler.magFilter = TextureFilter::Nearest;
    texture.sampler.wrapS = TextureWrap::ClampToEdge;
    EXPECT_EQ(baseColorAlpha(m, &texture, {0.49f, 0.5f}), 1.0f);  // bilinear would give 0.52
    EXPECT_EQ(baseColorAlpha(m, &texture, {0.51f, 0.5f}), 0.0f);
    EXPECT_EQ(baseColorAlpha(m, &texture, {-0.2f, 0.5f}), 1.0f);  // clamped to texel 0, not wrapped to 1
    EXPECT_EQ(baseColorAlpha(m, &texture, {1.2f, 0.5f}), 0.0f);
}

}  // namespace
}  // namespace penumbra
