// The spot/point atlas under load: 16 lights at once, the 17th dropped, hard vs soft, tile borders.
#include <cstdlib>

#include "spot_render_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Scene 16/17-light grid seen from above at 96 x 96 with a 1024 atlas (tiles of 256 texels).
Settings gridSettings() { return smallSpotAtlas(1024); }

uint32_t countDifferent(const Image& a, const Image& b, int tolerance) {
    uint32_t count = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) count += std::abs(int(a.pixels[i]) - int(b.pixels[i])) > tolerance;
    return count;
}

// Whether the class (lit >= 128) of `image` changes within `radius` pixels of (x, y).
bool nearEdge(const Image& image, int x, int y, int radius) {
    const bool lit = image.at(x, y) >= 128;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int px = x + dx, py = y + dy;
            if (px < 0 || py < 0 || px >= int(image.width) || py >= int(image.height)) continue;
            if ((image.at(px, py) >= 128) != lit) return true;
        }
    return false;
}

}  // namespace

TEST_F(RenderTest, SixteenSpotLightsEachCastTheirBoxShadowAtOnce) {
    // Each light 1.5 m to the side of its box, so the box's shadow lies beside it, in the camera's view.
    Scene scene = spotGridScene(16, LightShadows::Soft, {1.5f, 0.0f, 0.0f});
    for (uint32_t i = 0; i < 16; i += 2) scene.lights[i].shadows = LightShadows::Hard;  // both variants in one pass
    Renderer renderer(sharedDevice(), scene);
    for (uint32_t light : {0u, 5u, 10u, 15u}) {
        const RenderResult ours = renderer.render(shadowAov(light, 128), gridSettings());
        const ReferenceImages reference = traceReferenceShadow(scene, resolveCameraView(scene, 128, 128), light, false);
        const CompareMetrics m = compareShadowImages(ours.image, reference.shadow, reference.validMask);
        // Each light's box shadow is in view, and ours covers it: an all-lit AOV (no shadow drawn in
        // this light's tile) misses every truly shadowed pixel and fails here.
        const CompareMetrics allLit = compareShadowImages(Image(128, 128, 1, 255), reference.shadow, reference.validMask);
        const uint64_t trulyShadowed = allLit.falseLit;
        EXPECT_GT(trulyShadowed, 20u) << "light " << light;
        EXPECT_LT(double(m.falseLit), 0.4 * double(trulyShadowed)) << "light " << light;  // edges: 20 % measured
        EXPECT_GT(m.validPixels, 30u) << "light " << light;
        EXPECT_LT(m.interiorMisclassifiedPercent, 1.0) << "light " << light;
        EXPECT_LT(m.misclassifiedPercent, 10.0) << "light " << light;
        std::printf("[ metrics  ] 16 spots, light %u: valid %llu, misclassified %.2f %%, interior %.2f %%\n", light,
                    (unsigned long long)m.validPixels, m.misclassifiedPercent, m.interiorMisclassifiedPercent);
    }
    const nlohmann::json stats = nlohmann::json::parse(toJson(renderer.render(shadowAov(0, 32), gridSettings()).stats.shadows));
    EXPECT_EQ(stats["other"]["tiles"], 16);
    EXPECT_EQ(stats["other"]["split"], 4);
    EXPECT_EQ(stats["other"]["lightsDropped"], 0);
}

TEST_F(RenderTest, SeventeenthSpotLightIsDroppedWithAStatsEntryAndAWarning) {
    Scene scene = spotGridScene(17);
    scene.lights[9].range = 3.5f;  // the smallest influence: the one to drop
    Renderer renderer(sharedDevice(), scene);
    const RenderResult result = renderer.render(shadowAov(9, 64), gridSettings());
    const nlohmann::json stats = nlohmann::json::parse(toJson(result.stats.shadows));
    EXPECT_EQ(stats["other"]["lightsReserved"], 16);
    EXPECT_EQ(stats["other"]["lightsDropped"], 1);
    EXPECT_EQ(stats["other"]["droppedLights"], nlohmann::json::array({9}));
    ASSERT_EQ(result.stats.warnings.size(), 1u);
    EXPECT_NE(result.stats.warnings[0].find("light 9 'spot9'"), std::string::npos);
    // The dropped light casts no shadow at all.
    for (uint8_t value : result.image.pixels) ASSERT_EQ(value, 255);
}

TEST_F(RenderTest, HardAndSoftSpotShadowsDifferOnlyNearShadowEdges) {
    const Settings settings = smallSpotAtlas();
    const Scene scene = boxUnderLight(testSpot(LightShadows::Hard));
    const RenderResult hard = renderScene(scene, shadowAov(0), settings);
    const RenderResult soft = renderScene(boxUnderLight(testSpot(LightShadows::Soft)), shadowAov(0), settings);
    // Surfaces facing away from the light (N.L < 0.1) are excluded, as in the reference comparisons:
    // their shadow term is unlit either way and depends on the bias, not the filter.
    const ReferenceImages reference = traceReferenceShadow(scene, resolveCameraView(scene, 128, 128), 0, false);
    uint32_t differing = 0;
    for (uint32_t y = 0; y < hard.image.height; ++y)
        for (uint32_t x = 0; x < hard.image.width; ++x) {
            if (reference.validMask.at(x, y) == 0) continue;
            if (std::abs(int(hard.image.at(x, y)) - int(soft.image.at(x, y))) <= 8) continue;
            ++differing;
            EXPECT_TRUE(nearEdge(hard.image, int(x), int(y), 3)) << "pixel " << x << ", " << y;
        }
    EXPECT_GT(differing, 0u) << "soft shadows should soften the edges";
}

TEST_F(RenderTest, CasterAtATilesEdgeLeavesTheNeighbouringTileUnchanged) {
    // Two spots in tiles 0 and 1 (side by side). A plate with a square hole 0.5 m under light 0 covers
    // the rim of light 0's tile out to and beyond the frustum's edges, right next to tile 1.
    auto makeScene = [](bool plate) {
        Scene scene = spotGridScene(2);
        if (!plate) return scene;
        SceneBuilder builder;
        for (const Material& m : scene.materials) builder.addMaterial(m);
        for (const Mesh& mesh : scene.meshes) builder.addMesh(mesh);
        for (const Instance& i : scene.instances) builder.addInstance(i.meshIndex, i.worldFromObject, i.castShadows, i.nodeName);
        for (const Light& l : scene.lights) builder.addLight(l);
        builder.setCamera(*scene.camera);
        const glm::vec3 centre = scene.lights[0].wsPosition - glm::vec3(0.0f, 0.5f, 0.0f);
        const uint32_t bar = builder.addMesh(makeBoxMesh(glm::vec3(0.5f, 0.02f, 0.15f), 0));
        const uint32_t side = builder.addMesh(makeBoxMesh(glm::vec3(0.15f, 0.02f, 0.5f), 0));
        const float offset = 0.27f + 0.15f;  // hole half-size 0.27 m: inside the 30° cone (0.289 m)
        for (float sign : {-1.0f, 1.0f}) {
            glm::mat4 t(1.0f);
            t[3] = glm::vec4(centre + glm::vec3(0.0f, 0.0f, sign * offset), 1.0f);
            builder.addInstance(bar, t, true, "plate");
            t[3] = glm::vec4(centre + glm::vec3(sign * offset, 0.0f, 0.0f), 1.0f);
            builder.addInstance(side, t, true, "plate");
        }
        return builder.build();
    };
    const Settings settings = smallSpotAtlas(512);
    const Scene without = makeScene(false), with = makeScene(true);
    const nlohmann::json stats = nlohmann::json::parse(toJson(renderScene(with, shadowAov(1, 32), settings).stats.shadows));
    ASSERT_EQ(stats["other"]["split"], 2);
    EXPECT_EQ(countDifferent(renderScene(without, shadowAov(1, 96), settings).image,
                             renderScene(with, shadowAov(1, 96), settings).image, 0),
              0u);
    // The plate does shadow light 0's own cone rim: the scene tests something.
    EXPECT_GT(countDifferent(renderScene(without, shadowAov(0, 96), settings).image,
                             renderScene(with, shadowAov(0, 96), settings).image, 64),
              0u);
}
