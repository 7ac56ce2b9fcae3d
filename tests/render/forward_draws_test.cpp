// The forward main pass's draws: the opaque and alpha-tested objects go to the GPU as two indirect
// multi-draws (single-sided, double-sided), whatever their number, and a variant builds only the
// pipelines of the (blended, double-sided) combinations the scene's materials use.
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"

namespace penumbra::test {
namespace {

class ForwardDrawsTest : public RenderTest {
protected:
    static Settings forward() {
        Settings settings;
        settings.render.mainView = MainView::Forward;
        settings.shadows.directional.atlasSize = 512;  // lavapipe: keep the shadow passes small
        settings.shadows.spot.atlasSize = 512;
        return settings;
    }
    static RenderRequest small() {
        RenderRequest request;
        request.width = 128;
        request.height = 72;
        return request;
    }
    // A device that can issue one draw per indirect call: the main pass draws object by object.
    static Device oneDrawPerCallDevice() {
        gpu::DeviceFaultInjection faults;
        faults.maxDrawIndirectCount = 1;
        return DeviceAccess::makeDevice({testDeviceOptions(), faults});
    }
};

// A quad facing away from the camera (culled while single-sided) in front of a ground, under a sun.
Scene quadSeenFromBehind(bool doubleSided) {
    SceneBuilder builder;
    Material ground, quad;
    quad.baseColorFactor = glm::vec4(0.9f, 0.2f, 0.1f, 1.0f);
    ground.metallic = quad.metallic = 0.0f;
    quad.doubleSided = doubleSided;
    const uint32_t groundMaterial = builder.addMaterial(ground), quadMaterial = builder.addMaterial(quad);
    builder.addInstance(builder.addMesh(makePlaneMesh(glm::vec2(10.0f), groundMaterial)), glm::mat4(1.0f));
    // Facing +Z, turned to face -Z: away from the camera on +Z.
    const glm::mat4 turned = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}), glm::pi<float>(), {0, 1, 0});
    builder.addInstance(builder.addMesh(makeQuadMesh(glm::vec2(2.0f), quadMaterial)), turned);
    builder.addLight(makeDirectionalLight({0.3f, -1.0f, -0.4f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 2.0f, 6.0f}, {0.0f, 0.8f, 0.0f}, 0.9f));
    return builder.build();
}

TEST_F(ForwardDrawsTest, MultiDrawEqualsOneDrawPerObjectOnEveryCanonicalScene) {
    Device oneDraw = oneDrawPerCallDevice();
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        Renderer multi(device(), scene), single(oneDraw, scene);
        const RenderResult a = multi.render(small(), forward());
        const RenderResult b = single.render(small(), forward());
        EXPECT_EQ(shareOfPixelsOver(a.image, b.image, 0), 0.0) << info.name;
    }
    EXPECT_EQ(oneDraw.validationMessageCount(), 0u);
}

TEST_F(ForwardDrawsTest, AMaterialTurnedDoubleSidedDrawsAsAFreshRendererDoes) {
    Renderer edited(device(), quadSeenFromBehind(false));
    const RenderResult before = edited.render(small(), forward());
    Material material = edited.scene().materials[1];
    material.doubleSided = true;
    edited.setMaterial(1, material);
    const RenderResult after = edited.render(small(), forward());
    Renderer fresh(device(), quadSeenFromBehind(true));
    const RenderResult expected = fresh.render(small(), forward());
    EXPECT_GT(shareOfPixelsOver(before.image, expected.image, 8), 0.02) << "the quad's back must show once double-sided";
    EXPECT_EQ(shareOfPixelsOver(after.image, expected.image, 0), 0.0);
}

TEST_F(ForwardDrawsTest, EachSidednessTheMaterialsUseAddsItsLitAndPrepassPipelines) {
    // Opaque only (no blended material): per sidedness in use one lit pipeline and one of the depth
    // prepass (normal_prepass.frag, which the frame draws for the cascades' tight fit); nothing else
    // differs. With every combination built, both scenes would make as many pipelines.
    auto pipelinesFor = [&](bool secondDoubleSided) {
        Device own(testDeviceOptions());
        Scene scene = quadSeenFromBehind(secondDoubleSided);
        Renderer renderer(own, scene);
        renderer.render(small(), forward());
        return own.liveObjects().pipelines;
    };
    EXPECT_EQ(pipelinesFor(true), pipelinesFor(false) + 2);
}

}  // namespace
}  // namespace penumbra::test
