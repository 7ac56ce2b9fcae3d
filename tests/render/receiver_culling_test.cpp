// Receiver culling of cascade casters (shadows.directional.receiverCulling, shadows/caster_culling.h):
// the GPU culling pass leaves out casters whose shadow cannot reach a receiver that samples the cascade,
// and the image is the same as with every caster drawn.
#include <cstdio>

#include "directional_shadow_scenes.h"
#include "scene/canonical_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

class ReceiverCullingTest : public RenderTest {
protected:
    struct Frame {
        Image aov;
        uint32_t casters = 0;  // caster draws over the cascades, as the GPU counted them
    };
    Frame render(const Scene& scene, Settings settings, bool receiverCulling, uint32_t width, uint32_t height) {
        settings.shadows.directional.receiverCulling = receiverCulling;
        Renderer renderer(device(), scene);  // a renderer each: the tight fit follows its own first frame
        const RenderResult result = renderer.render({width, height, OutputMode::ShadowAov, 0, false}, settings);
        Frame frame{result.image};
        for (const DirectionalTileStats& tile : result.stats.shadows.directional.tileStats) frame.casters += tile.drawn.casters;
        return frame;
    }
};

size_t differingBytes(const Image& a, const Image& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    size_t differ = 0;
    for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i) differ += a.pixels[i] != b.pixels[i];
    return differ;
}

}  // namespace

// Tolerance: none. A caster culled is one whose every lookup lands outside the receivers that sample the
// cascade, so not one byte of the shadow term may change; across the scenes some casters must be culled.
TEST_F(ReceiverCullingTest, ShadowTermOfEveryCanonicalSceneIsTheSameWithoutTheCulledCasters) {
    uint32_t culledDraws = 0, allDraws = 0;
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        for (CascadeFit fit : {CascadeFit::Tight, CascadeFit::Sphere}) {
            Settings settings;
            settings.shadows.maxDistance = 150.0f;
            settings.shadows.directional.fit = fit;
            settings.shadows.directional.atlasSize = 512;  // lavapipe rasterizes on the CPU: keep it small
            settings.shadows.directional.cascadeBlend = CascadeBlend::Soft;
            const Frame culled = render(scene, settings, true, 128, 72);
            const Frame all = render(scene, settings, false, 128, 72);
            EXPECT_EQ(differingBytes(culled.aov, all.aov), 0u) << info.name << (fit == CascadeFit::Tight ? ", tight" : ", sphere");
            EXPECT_LE(culled.casters, all.casters) << info.name;
            culledDraws += culled.casters;
            allDraws += all.casters;
        }
    }
    std::printf("cascade caster draws: %u with receiver culling, %u without\n", culledDraws, allDraws);
    EXPECT_LT(culledDraws, allDraws * 9 / 10) << "receiver culling left out under 10 % of the draws";
}

// A wall just beyond the left edge of a downward view under an overhead sun: its shadow ends 1 cm outside
// the view, and the 5x5 tent of the pixels at the edge (their centres 7 cm inside, 18 cm texels) reaches it. Culled without the lookups' reach, the
// wall would leave those pixels lit.
TEST_F(ReceiverCullingTest, AShadowEndingJustOutsideTheViewStillDarkensTheEdgePixels) {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 60.0f, material);
    const float yfov = glm::radians(60.0f), aspect = 16.0f / 9.0f, height = 10.0f;
    const float halfWidth = height * std::tan(0.5f * yfov) * aspect;  // of the ground the view shows
    addBox(builder, {{-halfWidth - 2.0f, 0.0f, -5.0f}, {-halfWidth - 0.01f, 2.0f, 5.0f}}, material);
    builder.addLight(makeDirectionalLight(glm::normalize(glm::vec3(0.0f, -1.0f, 1e-3f)), 3.0f));
    Camera camera = makeLookAtCamera({0.0f, height, 0.0f}, {0.0f, 0.0f, 0.0f}, yfov);  // image right = +x
    builder.setCamera(camera);
    const Scene scene = builder.build();
    Settings settings;
    settings.shadows.maxDistance = 40.0f;
    settings.shadows.directional.filter = ShadowFilter::PCF5x5;
    settings.shadows.directional.cascadeCount = 1;
    // The ground lies 10 m deep everywhere: a tight cascade would end there and fade it out.
    settings.shadows.directional.fit = CascadeFit::Sphere;
    settings.shadows.directional.atlasSize = 512;
    constexpr uint32_t kWidth = 160, kHeight = 90;
    const Frame culled = render(scene, settings, true, kWidth, kHeight);
    const Frame all = render(scene, settings, false, kWidth, kHeight);
    uint32_t darkened = 0;
    for (uint32_t y = 0; y < kHeight; ++y) darkened += culled.aov.at(0, y) < 250;
    EXPECT_GT(darkened, kHeight / 2) << "the wall's shadow must reach the first column through the filter";
    EXPECT_EQ(differingBytes(culled.aov, all.aov), 0u);
}
