// The main view's depth pyramid layout (shadows/cull_packing.h, cull_structs.h CullCamera): level 0
// is half the view rounded up, every next level half the one below rounded up, down to 1 x 1, the
// levels one after the other; the culling shader's level walk (pyramidTexel) assumes exactly this.
#include <gtest/gtest.h>

#include "shadows/cull_packing.h"

namespace penumbra {
namespace {

TEST(DepthPyramidLayout, HalvesRoundingUpDownToOneTexel) {
    const DepthPyramidLayout layout = depthPyramidLayout(5, 3);
    ASSERT_EQ(layout.sizes.size(), 3u);
    EXPECT_EQ(layout.sizes[0], glm::uvec2(3, 2));
    EXPECT_EQ(layout.sizes[1], glm::uvec2(2, 1));
    EXPECT_EQ(layout.sizes[2], glm::uvec2(1, 1));
    EXPECT_EQ(layout.offsets, (std::vector<uint32_t>{0, 6, 8}));
    EXPECT_EQ(layout.texels, 9u);
}

TEST(DepthPyramidLayout, ATexelOfLevelLCoversTwoToTheLPlusOnePixelsPerAxis) {
    // 1920 x 1080: level L has ceil(1920 / 2^(L+1)) x ceil(1080 / 2^(L+1)) texels.
    const DepthPyramidLayout layout = depthPyramidLayout(1920, 1080);
    ASSERT_EQ(layout.sizes.size(), 11u);
    for (uint32_t level = 0; level < layout.sizes.size(); ++level) {
        const uint32_t span = 2u << level;
        EXPECT_EQ(layout.sizes[level], glm::uvec2((1920 + span - 1) / span, (1080 + span - 1) / span)) << level;
    }
}

TEST(DepthPyramidLayout, AOnePixelViewHasOneLevel) {
    EXPECT_EQ(depthPyramidLayout(1, 1).sizes, (std::vector<glm::uvec2>{glm::uvec2(1, 1)}));
}

TEST(DepthPyramidLayout, TheLevelCountAloneMatchesTheLayout) {
    for (uint32_t width : {1u, 2u, 3u, 7u, 64u, 96u, 1000u, 1920u, 4097u})
        for (uint32_t height : {1u, 2u, 5u, 54u, 1080u, 2161u})
            EXPECT_EQ(depthPyramidLevelCount(width, height), depthPyramidLayout(width, height).sizes.size())
                << width << "x" << height;
}

TEST(CullCamera, CarriesTheViewThePyramidAndTheCullingMode) {
    const gpu_data::CullCamera camera = packCullCamera(glm::mat4(2.0f), 1920, 1080, ViewCulling::Frustum);
    EXPECT_EQ(camera.clipFromWorld, glm::mat4(2.0f));
    EXPECT_EQ(glm::uvec4(camera.width, camera.height, camera.pyramidLevels, camera.culling),
              glm::uvec4(1920, 1080, 11, gpu_data::kViewCullingFrustum));
    EXPECT_EQ(glm::uvec2(camera.pyramidWidth, camera.pyramidHeight), glm::uvec2(960, 540));
    EXPECT_EQ(packCullCamera(glm::mat4(1.0f), 8, 8, ViewCulling::Occlusion).culling, gpu_data::kViewCullingOcclusion);
    EXPECT_EQ(packCullCamera(glm::mat4(1.0f), 8, 8, ViewCulling::None).culling, gpu_data::kViewCullingNone);
}

}  // namespace
}  // namespace penumbra
