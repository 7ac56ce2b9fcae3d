// The viewer's scene inspector without a window (src/viewer/scene_edit.h): an edit goes through the
// scene-edit API the Renderer's setters use (scene/scene_edits.h: Renderer::setLight is replaceLight
// on its scene); a value it refuses is a message and leaves the light as it was, and every value the
// light widgets offer is one it accepts.
#include <gtest/gtest.h>

#include "penumbra/scene_builder.h"
#include "scene/scene_edits.h"
#include "viewer/scene_edit.h"

using namespace penumbra;
using namespace penumbra::viewer;

namespace {

Scene sceneWithLights() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), material)), glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight(glm::vec3(0.3f, -1.0f, 0.2f), 1.0f));
    builder.addLight(makeSpotLight(glm::vec3(0, 4, 0), glm::vec3(0, -1, 0), 50.0f, 10.0f, 0.5f, 0.4f));
    builder.addLight(makePointLight(glm::vec3(2, 3, 0), 50.0f, 10.0f));
    return builder.build();
}

bool sameShadowValues(const Light& a, const Light& b) {
    return a.shadows == b.shadows && a.shadowStrength == b.shadowStrength && a.shadowBias == b.shadowBias &&
           a.shadowNormalBias == b.shadowNormalBias && a.shadowNearPlane == b.shadowNearPlane &&
           a.shadowLightSize == b.shadowLightSize && a.wsPosition == b.wsPosition && a.wsDirection == b.wsDirection;
}

}  // namespace

TEST(SceneInspectorEdit, OutOfRangeValueIsRefusedWithAMessageAndTheLightKept) {
    Scene scene = sceneWithLights();
    const Light before = scene.lights[0];
    Light typed = before;
    typed.shadowStrength = 1.5f;  // what a Ctrl+click typed past a slider that does not clamp
    const std::string message = applySceneEdit([&] { replaceLight(scene, 0, typed); });
    EXPECT_NE(message.find("shadowStrength"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_TRUE(sameShadowValues(scene.lights[0], before)) << "a refused edit changed the light";
}

TEST(SceneInspectorEdit, AcceptedEditIsAppliedWithNoMessage) {
    Scene scene = sceneWithLights();
    Light edited = scene.lights[1];
    edited.shadowStrength = 0.25f;
    EXPECT_EQ(applySceneEdit([&] { replaceLight(scene, 1, edited); }), "");
    EXPECT_EQ(scene.lights[1].shadowStrength, 0.25f);
}

TEST(SceneInspectorEdit, EveryValueTheLightWidgetsOfferIsAccepted) {
    Scene scene = sceneWithLights();
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light original = scene.lights[i];
        for (const LightWidget& widget : lightWidgets(original.type))
            for (float value : {widget.min, widget.max}) {
                Light light = original;
                light.*widget.field = value;
                EXPECT_EQ(applySceneEdit([&] { replaceLight(scene, i, light); }), "")
                    << "light " << i << " " << widget.label << " = " << value;
            }
        for (float limit : {-kLightPositionLimit, kLightPositionLimit}) {
            Light light = original;
            light.wsPosition = glm::vec3(limit);
            EXPECT_EQ(applySceneEdit([&] { replaceLight(scene, i, light); }), "") << "light " << i << " position " << limit;
        }
    }
}
