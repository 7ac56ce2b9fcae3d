// The ray-traced shadow reference: shadows land where geometry puts them, errors for unusable
// lights, and the validity mask's rules (reference_tracer.h).
#include <gtest/gtest.h>

#include "core/error.h"
#include "penumbra/reference.h"
#include "reference_test_scenes.h"

namespace penumbra {
namespace {

using namespace penumbra::test;

constexpr glm::vec3 kBoxLo{-1.3f, 0.0f, -0.9f};
constexpr glm::vec3 kBoxHi{0.7f, 1.7f, 1.1f};
constexpr float kGroundHalfSize = 8.0f;

// A box standing on a ground quad, lit by a sun from an oblique direction, seen from 20 units up.
Scene boxOnGround(glm::vec3 sunDirection, bool boxCastsShadows = true) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(0.0f, -kGroundHalfSize, kGroundHalfSize, -kGroundHalfSize, kGroundHalfSize));
    addObject(scene, boxMesh(kBoxLo, kBoxHi), boxCastsShadows);
    scene.lights.push_back(sunLight(sunDirection));
    scene.camera = topDownCamera({0.1f, 20.0f, 0.05f}, glm::radians(30.0f));
    return scene;
}

// The shadow value at the surface that the ray sees, computed in closed form for boxOnGround.
uint8_t expectedBoxShadow(glm::vec3 origin, glm::vec3 dir, glm::vec3 wsToLight) {
    const float tGround = -origin.y / dir.y;
    const auto box = rayBox(origin, dir, kBoxLo, kBoxHi);
    if (box && box->first < tGround) return glm::dot(box->second, wsToLight) > 0.0f ? 255 : 0;  // convex
    const glm::vec3 p = origin + tGround * dir;
    if (std::abs(p.x) > kGroundHalfSize || std::abs(p.z) > kGroundHalfSize) return 255;
    return rayBox(p, wsToLight, kBoxLo, kBoxHi) ? 0 : 255;
}

int countBelow(const Image& image, uint8_t value) {
    int n = 0;
    for (uint8_t v : image.pixels) n += v < value ? 1 : 0;
    return n;
}

TEST(ReferenceTracer, BoxShadowMatchesTheAnalyticShadowToThePixel) {
    const Scene scene = boxOnGround({0.8f, -1.5f, 0.35f});
    const CameraView view = makeCameraView(*scene.camera, 96, 96);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const glm::vec3 wsToLight = -scene.lights[0].wsDirection;
    int mismatches = 0;
    for (uint32_t y = 0; y < view.height; ++y) {
        for (uint32_t x = 0; x < view.width; ++x) {
            const glm::vec3 dir = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            const uint8_t expected = expectedBoxShadow(view.wsPosition, dir, wsToLight);
            if (result.shadow.at(x, y) != expected) {
                ++mismatches;
                ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << int(result.shadow.at(x, y)) << " != "
                              << int(expected);
            }
            if (mismatches > 10) return;
        }
    }
    EXPECT_GT(countBelow(result.shadow, 128), 150);  // the shadow is there to be checked (179 pixels)
}

// The shadow ray's start just off the surface must not depend on the size of the scene: with a ground 600 m
// wide (the canonical near_far_casters), an offset of 1e-4 of the scene (6 cm) lifted every shadow test point
// and shrank the reference's shadows by several centimetres (found measuring docs/fidelity.md).
TEST(ReferenceTracer, ShadowEdgesStayPutInAVeryLargeScene) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(0.0f, -300.0f, 300.0f, -300.0f, 300.0f));
    addObject(scene, boxMesh(kBoxLo, kBoxHi));
    scene.lights.push_back(sunLight({0.8f, -1.5f, 0.35f}));
    scene.camera = topDownCamera({1.2f, 5.0f, 0.3f}, glm::radians(30.0f));  // ~3 cm per pixel
    const CameraView view = makeCameraView(*scene.camera, 96, 96);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const glm::vec3 wsToLight = -scene.lights[0].wsDirection;
    int mismatches = 0, shadowed = 0;
    for (uint32_t y = 0; y < view.height; ++y)
        for (uint32_t x = 0; x < view.width; ++x) {
            const glm::vec3 dir = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            const uint8_t expected = expectedBoxShadow(view.wsPosition, dir, wsToLight);
            mismatches += result.shadow.at(x, y) != expected ? 1 : 0;
            shadowed += expected == 0 ? 1 : 0;
        }
    EXPECT_GT(shadowed, 500);
    EXPECT_LE(mismatches, 2);
}

TEST(ReferenceTracer, ShadowStrengthScalesTheShadowedValue) {
    Scene scene = boxOnGround({0.8f, -1.5f, 0.35f});
    scene.lights[0].shadowStrength = 0.6f;
    const CameraView view = makeCameraView(*scene.camera, 64, 64);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    for (uint8_t v : result.shadow.pixels) EXPECT_TRUE(v == 255 || v == 102) << int(v);  // 255 × (1 - 0.6)
    EXPECT_GT(countBelow(result.shadow, 255), 0);
}

TEST(ReferenceTracer, PixelsNextToAnObjectOutlineAreNotValid) {
    const Scene scene = boxOnGround({0.8f, -1.5f, 0.35f});
    const CameraView view = makeCameraView(*scene.camera, 64, 64);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    int outlinePixels = 0;
    for (uint32_t y = 1; y + 1 < view.height; ++y) {
        for (uint32_t x = 1; x + 1 < view.width; ++x) {
            bool sawBox = false, sawGround = false;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::vec3 dir = wsRayDirection(view, float(int(x) + dx) + 0.5f, float(int(y) + dy) + 0.5f);
                    const auto box = rayBox(view.wsPosition, dir, kBoxLo, kBoxHi);
                    (box ? sawBox : sawGround) = true;
                }
            }
            if (sawBox && sawGround) {
                ++outlinePixels;
                EXPECT_EQ(result.validMask.at(x, y), 0) << "pixel (" << x << ", " << y << ")";
            }
        }
    }
    EXPECT_GT(outlinePixels, 20);
    EXPECT_GT(result.validPixels, 64u * 64u / 2);  // the open ground stays valid
}

TEST(ReferenceTracer, LightIndexPastTheEndIsAnError) {
    const Scene scene = boxOnGround({0.0f, -1.0f, 0.0f});
    const CameraView view = makeCameraView(*scene.camera, 16, 16);
    try {
        traceReferenceShadow(scene, view, 3, false);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "light 3 does not exist (the scene has 1 lights)");
    }
}

TEST(ReferenceTracer, LightWithShadowsNoneIsAnError) {
    Scene scene = boxOnGround({0.0f, -1.0f, 0.0f});
    scene.lights[0].shadows = LightShadows::None;
    const CameraView view = makeCameraView(*scene.camera, 16, 16);
    try {
        traceReferenceShadow(scene, view, 0, false);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "light 0 'sun' casts no shadows");
    }
}

TEST(ReferenceTracer, LightWithZeroShadowStrengthIsAnError) {
    Scene scene = boxOnGround({0.0f, -1.0f, 0.0f});
    scene.lights[0].shadowStrength = 0.0f;
    const CameraView view = makeCameraView(*scene.camera, 16, 16);
    EXPECT_THROW(traceReferenceShadow(scene, view, 0, false), Error);
}

TEST(ReferenceTracer, SceneWithNothingInViewIsAllLitWithNoValidPixels) {
    Scene scene = emptyScene();
    scene.lights.push_back(sunLight({0.0f, -1.0f, 0.0f}));
    scene.camera = topDownCamera({0.0f, 5.0f, 0.0f}, 0.8f);
    const ReferenceImages result = traceReferenceShadow(scene, makeCameraView(*scene.camera, 32, 24), 0, false);
    ASSERT_EQ(result.shadow.width, 32u);
    ASSERT_EQ(result.shadow.height, 24u);
    EXPECT_EQ(countBelow(result.shadow, 255), 0);
    EXPECT_EQ(result.validPixels, 0u);
    EXPECT_EQ(result.geometryPixels, 0u);
    EXPECT_EQ(countBelow(result.validMask, 1), 32 * 24);
}

TEST(ReferenceTracer, InstanceThatCastsNoShadowsLeavesTheGroundLit) {
    const Scene scene = boxOnGround({0.8f, -1.5f, 0.35f}, false);
    const CameraView view = makeCameraView(*scene.camera, 64, 64);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    EXPECT_EQ(countBelow(result.shadow, 255), 0);
    EXPECT_EQ(result.geometryPixels, 64u * 64u);  // the box is still seen
}

TEST(ReferenceTracer, SurfaceThatReceivesNoShadowsIsLit) {
    Scene scene = boxOnGround({0.8f, -1.5f, 0.35f});
    scene.materials[0].receiveShadows = false;
    const ReferenceImages result = traceReferenceShadow(scene, makeCameraView(*scene.camera, 48, 48), 0, false);
    EXPECT_EQ(countBelow(result.shadow, 255), 0);
}

// A mask-material quad at height 1 whose texture is transparent in its central 2x2 of 4x4 texels
// (world x, z in (-0.5, 0.5)); a sun along (2, -1, 0) throws its shadow 2 units to +x, clear of the
// camera's view of the ground there.
Scene maskedQuadScene(AlphaMode alphaMode) {
    Scene scene = emptyScene();
    Texture texture;
    texture.name = "holed";
    texture.rgba = Image(4, 4, 4, 255);
    for (uint32_t y = 1; y <= 2; ++y)
        for (uint32_t x = 1; x <= 2; ++x) texture.rgba.at(x, y, 3) = 0;
    scene.textures.push_back(texture);
    Material mask;
    mask.name = "mask";
    mask.alphaMode = alphaMode;
    mask.baseColorTexture = 0;
    mask.shadows = alphaMode == AlphaMode::Mask ? MaterialShadowMode::Clip : MaterialShadowMode::On;
    mask.doubleSided = true;
    const uint32_t maskMaterial = addMaterial(scene, mask);
    addObject(scene, horizontalQuad(0.0f, -8.0f, 8.0f, -8.0f, 8.0f));
    addObject(scene, horizontalQuad(1.0f, -1.0f, 1.0f, -1.0f, 1.0f, maskMaterial));
    scene.lights.push_back(sunLight({2.0f, -1.0f, 0.0f}));
    scene.camera = topDownCamera({0.0f, 20.0f, 0.0f}, glm::radians(30.0f));
    return scene;
}

TEST(ReferenceTracer, MaskMaterialLetsLightThroughTheTransparentTexels) {
    const Scene scene = maskedQuadScene(AlphaMode::Mask);
    const CameraView view = makeCameraView(*scene.camera, 96, 96);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const glm::ivec2 throughHole = pixelOf(view, {2.0f, 0.0f, 0.0f});
    const glm::ivec2 behindTexels = pixelOf(view, {1.2f, 0.0f, 0.0f});
    const glm::ivec2 behindRim = pixelOf(view, {2.0f, 0.0f, 0.8f});
    EXPECT_EQ(result.shadow.at(throughHole.x, throughHole.y), 255);
    EXPECT_EQ(result.shadow.at(behindTexels.x, behindTexels.y), 0);
    EXPECT_EQ(result.shadow.at(behindRim.x, behindRim.y), 0);
}

TEST(ReferenceTracer, OpaqueMaterialIgnoresTheTextureAlpha) {
    const Scene scene = maskedQuadScene(AlphaMode::Opaque);
    const CameraView view = makeCameraView(*scene.camera, 96, 96);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const glm::ivec2 throughHole = pixelOf(view, {2.0f, 0.0f, 0.0f});
    EXPECT_EQ(result.shadow.at(throughHole.x, throughHole.y), 0);
}

TEST(ReferenceTracer, SpotLightConeBoundsTheValidPixels) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(0.0f, -8.0f, 8.0f, -8.0f, 8.0f));
    const float outerCone = glm::radians(25.0f);
    scene.lights.push_back(spotLight({0.0f, 4.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, outerCone));
    scene.camera = topDownCamera({0.0f, 10.0f, 0.0f}, glm::radians(40.0f));
    const CameraView view = makeCameraView(*scene.camera, 64, 64);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const float coneRadius = 4.0f * std::tan(outerCone);
    for (uint32_t y = 0; y < view.height; ++y) {
        for (uint32_t x = 0; x < view.width; ++x) {
            const glm::vec3 dir = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            const glm::vec3 p = view.wsPosition + (-view.wsPosition.y / dir.y) * dir;
            const float r = glm::length(glm::vec2(p.x, p.z));
            if (r > coneRadius * 1.001f) {
                EXPECT_EQ(result.validMask.at(x, y), 0) << x << ", " << y;
            } else if (r < coneRadius * 0.999f) {
                EXPECT_EQ(result.validMask.at(x, y), 255) << x << ", " << y;
            }
        }
    }
    EXPECT_GT(result.validPixels, 100u);
    EXPECT_LT(result.validPixels, 64u * 64u / 2);
}

TEST(ReferenceTracer, PointLightRangeBoundsTheValidPixels) {
    Scene scene = emptyScene();
    addObject(scene, horizontalQuad(0.0f, -8.0f, 8.0f, -8.0f, 8.0f));
    Light point = spotLight({0.0f, 1.5f, 0.0f}, {0.0f, -1.0f, 0.0f}, 0.5f);
    point.type = LightType::Point;
    point.range = 2.5f;
    scene.lights.push_back(point);
    scene.camera = topDownCamera({0.0f, 10.0f, 0.0f}, glm::radians(40.0f));
    const CameraView view = makeCameraView(*scene.camera, 64, 64);
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false);
    const glm::ivec2 inRange = pixelOf(view, {1.5f, 0.0f, 0.0f});   // distance 2.12
    const glm::ivec2 outOfRange = pixelOf(view, {2.5f, 0.0f, 0.0f});  // distance 2.92
    EXPECT_EQ(result.validMask.at(inRange.x, inRange.y), 255);
    EXPECT_EQ(result.validMask.at(outOfRange.x, outOfRange.y), 0);
}

TEST(ReferenceTracer, SurfacesBeyondTheMaxShadowDistanceAreLitAndNotValid) {
    const Scene scene = boxOnGround({0.8f, -1.5f, 0.35f});
    const CameraView view = makeCameraView(*scene.camera, 48, 48);
    ReferenceOptions options;
    options.maxShadowDistance = 10.0f;  // the ground is 20 away
    const ReferenceImages result = traceReferenceShadow(scene, view, 0, false, options);
    EXPECT_EQ(countBelow(result.shadow, 255), 0);
    EXPECT_EQ(result.validPixels, 0u);
}

}  // namespace
}  // namespace penumbra
