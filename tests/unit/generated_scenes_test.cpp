// The built-in scale scenes (gen:field, gen:boxes) that benchmarks and tests name as SCENE.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/error.h"

#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "scene/generated_scenes.h"

namespace penumbra {
namespace {

Scene twoBoxModel() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    const uint32_t box = builder.addMesh(makeBoxMesh(glm::vec3(100.0f, 50.0f, 20.0f), material));  // millimetres
    builder.addInstance(box, glm::mat4(1.0f));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), glm::vec3(0, 100, 0)));
    builder.addLight(makeDirectionalLight(glm::vec3(0, -1, 0), 1.0f));
    return builder.build();
}

uint64_t triangles(const Scene& scene) {
    uint64_t total = 0;
    for (const Instance& instance : scene.instances) total += scene.meshes[instance.meshIndex].indices.size() / 3;
    return total;
}

bool insideView(const CameraView& view, const glm::vec3& wsPoint) {
    const glm::vec4 clip = view.clipFromWorld * glm::vec4(wsPoint, 1.0f);
    return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
}

TEST(GeneratedSceneSpec, ParsesFieldWithAndWithoutSpots) {
    const auto a = parseGeneratedSceneSpec("gen:field:25");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->kind, GeneratedSceneSpec::Kind::Field);
    EXPECT_EQ(a->count, 25u);
    EXPECT_EQ(a->spotLights, 0u);
    const auto b = parseGeneratedSceneSpec("gen:field:100:16");
    ASSERT_TRUE(b);
    EXPECT_EQ(b->spotLights, 16u);
}

TEST(GeneratedSceneSpec, ParsesBoxes) {
    const auto spec = parseGeneratedSceneSpec("gen:boxes:100000");
    ASSERT_TRUE(spec);
    EXPECT_EQ(spec->kind, GeneratedSceneSpec::Kind::Boxes);
    EXPECT_EQ(spec->count, 100000u);
}

TEST(GeneratedSceneSpec, APathIsNotAGeneratedScene) { EXPECT_FALSE(parseGeneratedSceneSpec("scene.gltf")); }

TEST(GeneratedSceneSpec, MalformedSpecsAreErrorsNamingTheSpec) {
    for (const char* bad : {"gen:field", "gen:field:", "gen:field:0", "gen:field:x", "gen:field:4:-1", "gen:field:4:1:2:3",
                            "gen:field:4:1:1025", "gen:boxes:4:x", "gen:boxes:4:1:1",
                            "gen:boxes:0", "gen:boxes:99999999999", "gen:cubes:4", "gen:"}) {
        try {
            parseGeneratedSceneSpec(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
}

TEST(FieldScene, HasEveryCopyOfTheModelPlusTheGround) {
    const Scene model = twoBoxModel();
    const Scene field = makeFieldScene(model, 9, 0);
    EXPECT_EQ(field.instances.size(), 9u * 2u + 1u);
    EXPECT_EQ(triangles(field), 9u * triangles(model) + 2u);
}

TEST(FieldScene, CopiesAreScaledToTwoMetresAndStandOnTheGround) {
    const Scene field = makeFieldScene(twoBoxModel(), 4, 0);
    for (uint32_t copy = 0; copy < 4; ++copy) {
        Aabb bounds;
        for (uint32_t i = 0; i < 2; ++i) bounds.extend(field.instances[copy * 2 + i].wsBounds);
        EXPECT_NEAR(bounds.min.y, 0.0f, 1e-4f);
        EXPECT_NEAR(bounds.extent().y, 2.0f * 200.0f / 200.0f, 1e-3f);  // 200 mm tall = the largest extent
    }
}

TEST(FieldScene, HasASunAndTheRequestedShadowedSpots) {
    const Scene field = makeFieldScene(twoBoxModel(), 16, 5);
    ASSERT_EQ(field.lights.size(), 6u);
    EXPECT_EQ(field.lights[0].type, LightType::Directional);
    for (uint32_t i = 1; i < 6; ++i) {
        EXPECT_EQ(field.lights[i].type, LightType::Spot);
        EXPECT_NE(field.lights[i].shadows, LightShadows::None);
        EXPECT_LT(field.lights[i].wsDirection.y, -0.9f);  // aimed down at the field
    }
}

TEST(FieldScene, CameraSeesEveryCopyAndSpot) {
    const Scene field = makeFieldScene(twoBoxModel(), 100, 16);
    const CameraView view = resolveCameraView(field, 1920, 1080);
    for (const Instance& instance : field.instances) {
        if (instance.nodeName == "ground") continue;
        EXPECT_TRUE(insideView(view, instance.wsBounds.center())) << instance.nodeName;
    }
    for (const Light& light : field.lights)
        if (light.type == LightType::Spot) EXPECT_TRUE(insideView(view, light.wsPosition - glm::vec3(0, 6, 0)));
}

TEST(BoxesScene, HasOneInstancePerBoxPlusTheGround) {
    const Scene boxes = makeBoxesScene(1000);
    EXPECT_EQ(boxes.instances.size(), 1001u);
    EXPECT_EQ(triangles(boxes), 1000u * 12u + 2u);
    EXPECT_EQ(boxes.lights.size(), 1u);
}

TEST(GeneratedSceneSpec, ParsesPointLightCounts) {
    EXPECT_EQ(parseGeneratedSceneSpec("gen:field:100:16:1008")->pointLights, 1008u);
    EXPECT_EQ(parseGeneratedSceneSpec("gen:field:100:16")->pointLights, 0u);
    EXPECT_EQ(parseGeneratedSceneSpec("gen:boxes:100:400")->pointLights, 400u);
}

TEST(BoxesScene, PointLightsAreUnshadowedRangedAndOverTheBoxes) {
    const Scene boxes = makeBoxesScene(100, 400);
    ASSERT_EQ(boxes.lights.size(), 401u);  // the sun first
    Aabb spread;
    for (size_t i = 1; i < boxes.lights.size(); ++i) {
        const Light& light = boxes.lights[i];
        EXPECT_EQ(light.type, LightType::Point);
        EXPECT_EQ(light.shadows, LightShadows::None);
        EXPECT_GT(light.range, 0.0f);
        EXPECT_GE(light.wsPosition.y, 0.5f);
        EXPECT_LE(light.wsPosition.y, 1.5f);
        spread.extend(light.wsPosition);
    }
    EXPECT_GT(spread.extent().x, 0.8f * boxes.wsBounds.extent().x - 4.0f) << "spread over the whole ground";
}

TEST(BoxesScene, CameraSeesEveryBox) {
    const Scene boxes = makeBoxesScene(2500);
    const CameraView view = resolveCameraView(boxes, 1920, 1080);
    for (const Instance& instance : boxes.instances) EXPECT_TRUE(insideView(view, instance.wsBounds.center()));
}

TEST(BoxesScene, IsTheSameOnEveryRun) {
    const Scene a = makeBoxesScene(50), b = makeBoxesScene(50);
    for (size_t i = 0; i < a.instances.size(); ++i) EXPECT_EQ(a.instances[i].worldFromObject, b.instances[i].worldFromObject);
}

TEST(LoadScene, GenFieldCopiesTheDefaultEngineModel) {
    const Scene field = loadScene("gen:field:2:1");
    const Scene engine = loadGltfScene(kDefaultFieldModel);
    EXPECT_EQ(field.instances.size(), 2 * engine.instances.size() + 1);
    EXPECT_EQ(field.lights.size(), 2u);
    EXPECT_EQ(field.sourcePath, "gen:field:2:1");
}

TEST(LoadScene, GenFieldWithAMissingModelIsAnError) {
    SceneSourceOptions options;
    options.model = "/nonexistent/model.glb";
    EXPECT_THROW(loadScene("gen:field:2", options), Error);
}

TEST(LoadScene, EmptySourceIsTheDemoScene) { EXPECT_EQ(loadScene("").instances.size(), makeDemoScene().instances.size()); }

}  // namespace
}  // namespace penumbra
