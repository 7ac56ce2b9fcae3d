// The texel rule of glTF samplers (scene/texture_sampler.h) that the reference shares with the GPU.
#include <gtest/gtest.h>

#include "scene/texture_sampler.h"

using namespace penumbra;

namespace {

TextureSampler sampler(TextureFilter filter, TextureWrap wrap) {
    TextureSampler s;
    s.magFilter = s.minFilter = filter;
    s.wrapS = s.wrapT = wrap;
    return s;
}

// 4 x 1 texels with channel 0 = 0, 100, 200, 250.
Image ramp() {
    Image image(4, 1, 1, 0);
    const uint8_t values[4] = {0, 100, 200, 250};
    for (uint32_t x = 0; x < 4; ++x) image.at(x, 0) = values[x];
    return image;
}

}  // namespace

TEST(TextureSampler, NearestTakesTheTexelThatContainsTheSample) {
    const TextureSampler s = sampler(TextureFilter::Nearest, TextureWrap::Repeat);
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {0.26f, 0.5f}, 0), 100.0f / 255.0f);
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {0.74f, 0.5f}, 0), 200.0f / 255.0f);
}

TEST(TextureSampler, LinearBlendsTheTwoNearestTexelCentres) {
    const TextureSampler s = sampler(TextureFilter::Linear, TextureWrap::Repeat);
    // u = 0.5 lies halfway between the centres of texels 1 (0.375) and 2 (0.625).
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {0.5f, 0.5f}, 0), 150.0f / 255.0f);
    EXPECT_NEAR(sampleTextureChannel(ramp(), s, {0.4375f, 0.5f}, 0), 125.0f / 255.0f, 1e-6f);
}

TEST(TextureSampler, RepeatBlendsAcrossTheSeam) {
    const TextureSampler s = sampler(TextureFilter::Linear, TextureWrap::Repeat);
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {0.0f, 0.5f}, 0), 125.0f / 255.0f);  // texels 3 and 0
}

TEST(TextureSampler, ClampToEdgeRepeatsTheBorderTexel) {
    const TextureSampler s = sampler(TextureFilter::Linear, TextureWrap::ClampToEdge);
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {0.0f, 0.5f}, 0), 0.0f);
    EXPECT_FLOAT_EQ(sampleTextureChannel(ramp(), s, {1.3f, 0.5f}, 0), 250.0f / 255.0f);
}

TEST(TextureSampler, MirroredRepeatReflectsAtEachEdge) {
    EXPECT_EQ(wrapTexelIndex(-1, 4, TextureWrap::MirroredRepeat), 0);
    EXPECT_EQ(wrapTexelIndex(4, 4, TextureWrap::MirroredRepeat), 3);
    EXPECT_EQ(wrapTexelIndex(5, 4, TextureWrap::MirroredRepeat), 2);
    EXPECT_EQ(wrapTexelIndex(8, 4, TextureWrap::MirroredRepeat), 0);
    EXPECT_EQ(wrapTexelIndex(-5, 4, TextureWrap::MirroredRepeat), 3);
    EXPECT_EQ(wrapTexelIndex(-1, 4, TextureWrap::Repeat), 3);
    EXPECT_EQ(wrapTexelIndex(-1, 4, TextureWrap::ClampToEdge), 0);
}

TEST(TextureSampler, GltfFilterCodesRoundTrip) {
    for (int code : {9728, 9729, 9984, 9985, 9986, 9987}) {
        TextureSampler s;
        ASSERT_TRUE(setGltfMinFilter(s, code));
        EXPECT_EQ(gltfMinFilterCode(s), code);
    }
    TextureSampler s;
    ASSERT_TRUE(setGltfMinFilter(s, 9728));
    EXPECT_EQ(s.mipmaps, MipmapMode::None);
    EXPECT_FALSE(setGltfMinFilter(s, 1234));
    EXPECT_FALSE(setGltfMagFilter(s, 9987));
    TextureWrap wrap;
    EXPECT_FALSE(gltfWrap(7, wrap));
    ASSERT_TRUE(gltfWrap(33648, wrap));
    EXPECT_EQ(wrap, TextureWrap::MirroredRepeat);
}

TEST(TextureSampler, UndefinedGltfValuesKeepTheDefaults) {
    TextureSampler s;
    EXPECT_TRUE(setGltfMagFilter(s, -1));
    EXPECT_TRUE(setGltfMinFilter(s, -1));
    EXPECT_TRUE(s == TextureSampler{});
}
