// Material and node shadow modes (Catlike Coding "Directional Shadows", Transparency): `on`, `clip`,
// `dither`, `off`, unlit casters, `receiveShadows: false` and node `castShadows: false`, seen in the
// directional shadow AOV.
//
// The scene: a ground plane, a small control box whose shadow must always be there, and a 3 x 3 m quad
// held 2 m above the ground facing down (the camera above sees only its culled back), textured with
// one alpha on its -X half and another on its +X half.
#include <cstdio>

#include "directional_shadow_scenes.h"

#include "shadows/shadow_planner.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr float kGroundHalf = 8.0f;
constexpr float kQuadHalf = 1.5f;
constexpr float kQuadHeight = 2.0f;
constexpr uint32_t kSize = 128;
const Box kControlBox{{-5.0f, 0.0f, -5.0f}, {-4.0f, 4.0f, -4.0f}};
const glm::vec3 kSun = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));

struct QuadSetup {
    MaterialShadowMode shadows = MaterialShadowMode::On;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float leftAlpha = 1.0f, rightAlpha = 1.0f;  // texture alpha on the quad's -X and +X halves
    bool unlit = false;
    bool quadCastsShadows = true;      // the node's castShadows
    bool groundReceivesShadows = true;
};

Texture halvesTexture(float leftAlpha, float rightAlpha) {
    Texture texture;
    texture.rgba = Image(8, 8, 4, 255);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) texture.rgba.at(x, y, 3) = uint8_t(std::lround(255.0f * (x < 4 ? leftAlpha : rightAlpha)));
    return texture;
}

Scene quadOverGround(const QuadSetup& setup) {
    SceneBuilder builder;
    Material groundMaterial = matteMaterial();
    groundMaterial.receiveShadows = setup.groundReceivesShadows;
    addGround(builder, 2.0f * kGroundHalf, builder.addMaterial(groundMaterial));
    addBox(builder, kControlBox, builder.addMaterial(matteMaterial()));

    Material quadMaterial = matteMaterial(glm::vec4(1.0f));
    quadMaterial.baseColorTexture = int(builder.addTexture(halvesTexture(setup.leftAlpha, setup.rightAlpha)));
    quadMaterial.shadows = setup.shadows;
    quadMaterial.alphaMode = setup.alphaMode;
    quadMaterial.unlit = setup.unlit;
    const uint32_t quad = builder.addMesh(makeQuadMesh({2.0f * kQuadHalf, 2.0f * kQuadHalf}, builder.addMaterial(quadMaterial)));
    // +90 degrees about X turns the quad's +Z front to -Y and its +Y (texture top) to +Z; u still runs along +X.
    const glm::mat4 worldFromQuad = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, kQuadHeight, 0.0f}),
                                                glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    builder.addInstance(quad, worldFromQuad, setup.quadCastsShadows);
    builder.addLight(makeDirectionalLight(kSun, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 12.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, glm::radians(55.0f)));
    return builder.build();
}

// The AOV values of the ground under the quad's -X and +X halves (projected along the sun), under the
// control box, and elsewhere; each keeps 0.3 m away from the borders of these regions.
struct Regions {
    std::vector<uint8_t> left, right, control, elsewhere;
};

double mean(const std::vector<uint8_t>& values) {
    double sum = 0.0;
    for (uint8_t v : values) sum += v;
    return values.empty() ? 0.0 : sum / double(values.size());
}

Box grown(const Box& box, float margin) { return {box.min - glm::vec3(margin), box.max + glm::vec3(margin)}; }

Regions measureRegions(const Scene& scene, const Image& aov) {
    const CameraView view = resolveCameraView(scene, aov.width, aov.height);
    constexpr float kMargin = 0.3f;
    Regions regions;
    for (uint32_t y = 0; y < aov.height; ++y) {
        for (uint32_t x = 0; x < aov.width; ++x) {
            const auto ground = visibleGroundPoint(view, x, y, kGroundHalf, {kControlBox});
            if (!ground) continue;
            const glm::vec3 onQuadPlane = *ground - kSun * (kQuadHeight / -kSun.y);
            const float ax = std::abs(onQuadPlane.x), az = std::abs(onQuadPlane.z);
            const glm::vec3 start = *ground - 1e-4f * kSun;
            if (rayBoxHit(start, -kSun, grown(kControlBox, -kMargin))) {
                regions.control.push_back(aov.at(x, y));
            } else if (rayBoxHit(start, -kSun, grown(kControlBox, kMargin))) {
                continue;
            } else if (ax < kQuadHalf - kMargin && az < kQuadHalf - kMargin && ax > kMargin) {
                (onQuadPlane.x < 0.0f ? regions.left : regions.right).push_back(aov.at(x, y));
            } else if (ax > kQuadHalf + kMargin || az > kQuadHalf + kMargin) {
                regions.elsewhere.push_back(aov.at(x, y));
            }
        }
    }
    return regions;
}

class MaterialShadowTest : public DirectionalShadowTest {
protected:
    Regions render(const QuadSetup& setup) {
        const Scene scene = quadOverGround(setup);
        const Regions regions = measureRegions(scene, renderShadowAov(scene, shadowSettings(30.0f, 2, 1024), kSize));
        EXPECT_GT(regions.left.size(), 100u);
        EXPECT_GT(regions.right.size(), 100u);
        EXPECT_GT(regions.control.size(), 20u);
        return regions;
    }
};

bool all(const std::vector<uint8_t>& values, uint8_t expected) {
    return std::all_of(values.begin(), values.end(), [&](uint8_t v) { return v == expected; });
}

}  // namespace

TEST_F(MaterialShadowTest, OpaqueMaterialCastsAFullShadow) {
    const Regions r = render({});
    EXPECT_TRUE(all(r.left, 0) && all(r.right, 0)) << mean(r.left) << " " << mean(r.right);
    EXPECT_TRUE(all(r.control, 0));
    EXPECT_TRUE(all(r.elsewhere, 255));
}

TEST_F(MaterialShadowTest, ClipMaterialLeavesHolesWhereAlphaIsBelowTheCutoff) {
    QuadSetup setup;
    setup.shadows = MaterialShadowMode::Clip;
    setup.alphaMode = AlphaMode::Mask;
    setup.leftAlpha = 0.2f;  // below the default cutoff 0.5
    const Regions r = render(setup);
    EXPECT_TRUE(all(r.left, 255)) << mean(r.left);
    EXPECT_TRUE(all(r.right, 0)) << mean(r.right);
    EXPECT_TRUE(all(r.control, 0));
}

TEST_F(MaterialShadowTest, DitherMaterialShadowDensityFollowsAlpha) {
    QuadSetup setup;
    setup.shadows = MaterialShadowMode::Dither;
    setup.alphaMode = AlphaMode::Blend;
    setup.leftAlpha = 0.25f;
    setup.rightAlpha = 0.75f;
    const Regions r = render(setup);
    std::printf("[dither] mean AOV / 255: alpha 0.25 -> %.3f, alpha 0.75 -> %.3f\n", mean(r.left) / 255.0,
                mean(r.right) / 255.0);
    // Shadowed fraction = alpha, so the mean AOV is 255 (1 - alpha), up to the noise's unevenness.
    EXPECT_NEAR(mean(r.left) / 255.0, 0.75, 0.08);
    EXPECT_NEAR(mean(r.right) / 255.0, 0.25, 0.08);
    EXPECT_TRUE(all(r.control, 0));
}

TEST_F(MaterialShadowTest, OffMaterialCastsNoShadow) {
    QuadSetup setup;
    setup.shadows = MaterialShadowMode::Off;
    const Regions r = render(setup);
    EXPECT_TRUE(all(r.left, 255) && all(r.right, 255));
    EXPECT_TRUE(all(r.control, 0));
}

TEST_F(MaterialShadowTest, UnlitMaterialStillCastsShadows) {
    QuadSetup setup;
    setup.unlit = true;
    const Regions r = render(setup);
    EXPECT_TRUE(all(r.left, 0) && all(r.right, 0));
}

TEST_F(MaterialShadowTest, NodeWithCastShadowsFalseCastsNoShadow) {
    QuadSetup setup;
    setup.quadCastsShadows = false;
    const Regions r = render(setup);
    EXPECT_TRUE(all(r.left, 255) && all(r.right, 255));
    EXPECT_TRUE(all(r.control, 0));
}

TEST_F(MaterialShadowTest, SurfaceWithReceiveShadowsFalseShowsNoShadow) {
    QuadSetup setup;
    setup.groundReceivesShadows = false;
    const Scene scene = quadOverGround(setup);
    const Settings settings = shadowSettings(30.0f, 2, 1024);
    ASSERT_EQ(ShadowPlanner::plan(scene, resolveCameraView(scene, kSize, kSize), settings.shadows).directional.lights.size(), 1u);
    const Image aov = renderShadowAov(scene, settings, kSize);
    // The light is reserved and its atlas drawn, but the ground doesn't receive: no shadow anywhere on it.
    const Regions r = measureRegions(scene, aov);
    EXPECT_TRUE(all(r.left, 255) && all(r.right, 255) && all(r.control, 255) && all(r.elsewhere, 255));
}
