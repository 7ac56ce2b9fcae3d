// Which bias removes spot-shadow acne with less peter-panning: the normal bias scaled by the world texel size
// at the fragment's distance (the default), or the constant clip-space depth bias of Catlike Coding
// "Spotlight Shadows", Shadow Bias (settings shadows.spot.depthBias). Measured against the ray-traced
// reference on a grazing-light scene: acne = false shadow on lit ground, peter-panning = false light at
// contacts.
#include "spot_render_scenes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A spot skimming the ground at about 20°, a box standing on the ground and a thin plate just above it.
Scene grazingSpot(float normalBias, LightShadows shadows) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    white.roughness = 1.0f;
    const uint32_t material = builder.addMaterial(white);
    builder.addInstance(builder.addMesh(makePlaneMesh({12.0f, 12.0f}, material)), glm::mat4(1.0f), true, "ground");
    glm::mat4 box(1.0f);
    box[3] = glm::vec4(0.0f, 0.3f, -1.0f, 1.0f);
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.3f), material)), box, true, "box");
    // A thin plate 6 cm above the ground: its shadow shrinks or vanishes as soon as a bias exceeds the gap.
    glm::mat4 plate(1.0f);
    plate[3] = glm::vec4(1.2f, 0.07f, -0.5f, 1.0f);
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.4f, 0.01f, 0.4f), material)), plate, true, "plate");
    Light spot = makeSpotLight({0.0f, 2.0f, 4.5f}, glm::vec3(0.0f, -2.0f, -6.0f), 80.0f, 14.0f, 0.6f, 0.5f);
    spot.shadows = shadows;
    spot.shadowNormalBias = normalBias;
    builder.addLight(spot);
    builder.setCamera(makeLookAtCamera({3.0f, 4.0f, 3.0f}, {0.0f, 0.0f, -1.5f}, 0.9f));
    return builder.build();
}

struct BiasResult {
    double acnePercent = 0.0;        // reference lit, ours shadowed
    double peterPanningPercent = 0.0;  // reference shadowed, ours lit
};

BiasResult measure(float normalBias, float depthBias, LightShadows shadows,
                   ShadowBiasMode mode = ShadowBiasMode::Normal) {
    const Scene scene = grazingSpot(normalBias, shadows);
    Settings settings = smallSpotAtlas(1024);
    settings.shadows.bias = mode;
    settings.shadows.spot.depthBias = depthBias;
    Renderer renderer(sharedDevice(), scene);
    const RenderResult ours = renderer.render(shadowAov(0, 128), settings);
    const ReferenceImages reference = traceReferenceShadow(scene, resolveCameraView(scene, 128, 128), 0, false);
    const CompareMetrics m = compareShadowImages(ours.image, reference.shadow, reference.validMask);
    return {m.falseShadowPercent, m.falseLitPercent};
}

}  // namespace

// Sweep (hard / soft, 128 x 128, atlas 1024, lavapipe), acne % / peter-panning % of valid pixels:
//   normal bias 0          48.3 / 0.03    49.3 / 0.02
//   normal bias 0.5         0.01 / 0.10    0.01 / 0.25
//   normal bias 1 (default) 0.01 / 0.19    0.00 / 0.44
//   depth bias 0.0005       0.02 / 0.03    0.03 / 0.02
//   depth bias 0.002        0.02 / 0.03    0.02 / 0.03
//   depth bias 0.005        0.02 / 0.27    0.02 / 0.25
// (all in the constant normal-offset bias mode, shadows.bias = normal; measure() defaults to it).
// Both remove the acne; here the constant clip-space bias keeps contact shadows slightly better, but the
// point light of tests/scenes/point_light.gltf keeps faint acne up to depth bias 0.003 (MAE 0.031 vs
// 0.0067 with normal bias 1), and at 0.005 this scene peter-pans more than with the normal bias. So the
// normal bias stays the default (numbers and reasons: SpotShadowSettings::depthBias).

// The default receiver-plane bias (penumbra/shadows/bias.glsl) removes the acne with no tuning, even at
// shadowNormalBias 0, and peter-pans less than the normal bias.
TEST_F(RenderTest, ReceiverPlaneBiasRemovesSpotAcneWithLessPeterPanningThanTheNormalBias) {
    const BiasResult normal = measure(1.0f, 0.0f, LightShadows::Hard);
    for (LightShadows shadows : {LightShadows::Hard, LightShadows::Soft})
        for (float normalBias : {0.0f, 1.0f}) {
            const BiasResult plane = measure(normalBias, 0.0f, shadows, ShadowBiasMode::ReceiverPlane);
            EXPECT_LT(plane.acnePercent, 0.1) << "normal bias " << normalBias;
            EXPECT_LT(plane.peterPanningPercent, normal.peterPanningPercent) << "normal bias " << normalBias;
        }
}

TEST_F(RenderTest, SpotShadowsWithoutBiasShowAcneOnGrazingGround) {
    EXPECT_GT(measure(0.0f, 0.0f, LightShadows::Hard).acnePercent, 10.0);
}

TEST_F(RenderTest, DefaultNormalBiasRemovesSpotShadowAcne) {
    const BiasResult r = measure(1.0f, 0.0f, LightShadows::Hard);
    EXPECT_LT(r.acnePercent, 0.1);
    EXPECT_LT(r.peterPanningPercent, 0.5);
}

TEST_F(RenderTest, ConstantClipSpaceDepthBiasRemovesSpotShadowAcneWithoutMorePeterPanning) {
    const BiasResult normal = measure(1.0f, 0.0f, LightShadows::Hard);
    const BiasResult depth = measure(0.0f, 0.001f, LightShadows::Hard);
    EXPECT_LT(depth.acnePercent, 0.1);
    EXPECT_LE(depth.peterPanningPercent, normal.peterPanningPercent);
}
