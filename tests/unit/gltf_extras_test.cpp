// Shadow properties in glTF extras (the table of docs/scene-format.md): parsing, defaults and validation
// errors.
#include <gtest/gtest.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using penumbra::testing::TempDir;
using penumbra::testing::TestGltf;
using nlohmann::json;

namespace {

// The Error message of loading `gltf`, or "" when it loads.
std::string loadError(TestGltf& gltf) {
    TempDir dir;
    try {
        loadGltfScene(gltf.write(dir, "extras"));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TestGltf withLightExtras(const json& extras) {
    TestGltf gltf;
    gltf.addLight({{"type", "directional"}, {"name", "Sun"}});
    gltf.addLight({{"type", "spot"}, {"name", "Lamp"}, {"spot", json::object()}, {"extras", extras}});
    return gltf;
}

TestGltf withMaterialExtras(const json& material) {
    TestGltf gltf;
    gltf.doc["materials"] = json::array({material});  // not {material}: compilers differ on one-element braces
    return gltf;
}

Scene load(TestGltf& gltf) {
    TempDir dir;
    return loadGltfScene(gltf.write(dir, "extras"));
}

}  // namespace

TEST(GltfExtras, LightShadowPropertiesHaveDesignDefaults) {
    TestGltf gltf = withLightExtras(json::object());
    const Scene scene = load(gltf);
    ASSERT_EQ(scene.lights.size(), 2u);
    for (const Light& light : scene.lights) {
        EXPECT_EQ(light.shadows, LightShadows::Soft);
        EXPECT_FLOAT_EQ(light.shadowStrength, 1.0f);
        EXPECT_FLOAT_EQ(light.shadowBias, 0.0f);
        EXPECT_FLOAT_EQ(light.shadowNormalBias, 1.0f);
    }
    EXPECT_FLOAT_EQ(scene.lights[0].shadowNearPlane, 0.0f);  // directional
    EXPECT_FLOAT_EQ(scene.lights[1].shadowNearPlane, 0.1f);  // spot
}

TEST(GltfExtras, ReadsLightShadowProperties) {
    TestGltf gltf = withLightExtras({{"shadows", "hard"}, {"shadowStrength", 0.25}, {"shadowBias", 0.5},
                                     {"shadowNormalBias", 2}, {"shadowNearPlane", 0.3}});
    const Light light = load(gltf).lights[1];
    EXPECT_EQ(light.shadows, LightShadows::Hard);
    EXPECT_FLOAT_EQ(light.shadowStrength, 0.25f);
    EXPECT_FLOAT_EQ(light.shadowBias, 0.5f);
    EXPECT_FLOAT_EQ(light.shadowNormalBias, 2.0f);
    EXPECT_FLOAT_EQ(light.shadowNearPlane, 0.3f);
}

// Shadows "pcss" with the light's size: angular diameter in degrees for the sun (default
// 0.53), emitter radius in metres for spot and point lights (default 0.05).
TEST(GltfExtras, PcssLightsReadTheirSizeWithTypeDefaults) {
    TestGltf gltf = withLightExtras({{"shadows", "pcss"}, {"shadowLightSize", 0.2}});
    const Scene scene = load(gltf);
    EXPECT_EQ(scene.lights[1].shadows, LightShadows::Pcss);
    EXPECT_FLOAT_EQ(scene.lights[1].shadowLightSize, 0.2f);
    EXPECT_FLOAT_EQ(scene.lights[0].shadowLightSize, 0.53f);
    TestGltf defaults = withLightExtras(json::object());
    EXPECT_FLOAT_EQ(load(defaults).lights[1].shadowLightSize, 0.05f);
}

TEST(GltfExtras, NegativeLightSizeIsAnError) {
    TestGltf gltf = withLightExtras({{"shadowLightSize", -0.1}});
    EXPECT_NE(loadError(gltf).find("shadowLightSize"), std::string::npos);
}

TEST(GltfExtras, LightShadowsNoneIsRead) {
    TestGltf gltf = withLightExtras({{"shadows", "none"}});
    EXPECT_EQ(load(gltf).lights[1].shadows, LightShadows::None);
}

TEST(GltfExtras, OutOfRangeShadowStrengthNamesLightKeyAndRange) {
    TestGltf gltf = withLightExtras({{"shadowStrength", 1.5}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("extras.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("light 1 'Lamp'"), std::string::npos) << message;
    EXPECT_NE(message.find("shadowStrength"), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 1]"), std::string::npos) << message;
}

TEST(GltfExtras, NegativeShadowBiasIsAnError) {
    TestGltf gltf = withLightExtras({{"shadowBias", -0.1}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("shadowBias"), std::string::npos) << message;
    EXPECT_NE(message.find(">= 0"), std::string::npos) << message;
}

TEST(GltfExtras, NegativeNormalBiasAndNearPlaneAreErrors) {
    TestGltf normalBias = withLightExtras({{"shadowNormalBias", -1}});
    EXPECT_NE(loadError(normalBias).find("shadowNormalBias"), std::string::npos);
    TestGltf nearPlane = withLightExtras({{"shadowNearPlane", -1}});
    EXPECT_NE(loadError(nearPlane).find("shadowNearPlane"), std::string::npos);
}

TEST(GltfExtras, UnknownLightShadowModeListsAllowedValues) {
    TestGltf gltf = withLightExtras({{"shadows", "fuzzy"}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("extras.shadows"), std::string::npos) << message;
    EXPECT_NE(message.find("\"none\", \"hard\", \"soft\""), std::string::npos) << message;
    EXPECT_NE(message.find("fuzzy"), std::string::npos) << message;
}

TEST(GltfExtras, WrongTypeForNumberIsAnError) {
    TestGltf gltf = withLightExtras({{"shadowStrength", "strong"}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("shadowStrength must be a number"), std::string::npos) << message;
}

TEST(GltfExtras, MaterialShadowModeOverridesAlphaModeDefault) {
    TestGltf gltf = withMaterialExtras({{"alphaMode", "BLEND"}, {"extras", {{"shadows", "off"}, {"receiveShadows", false}}}});
    const Material material = load(gltf).materials[0];
    EXPECT_EQ(material.shadows, MaterialShadowMode::Off);
    EXPECT_FALSE(material.receiveShadows);
}

TEST(GltfExtras, MaterialReceivesShadowsByDefault) {
    TestGltf gltf = withMaterialExtras({{"name", "plain"}});
    EXPECT_TRUE(load(gltf).materials[0].receiveShadows);
}

TEST(GltfExtras, UnknownMaterialShadowModeNamesMaterialAndKey) {
    TestGltf gltf = withMaterialExtras({{"name", "Leaves"}, {"extras", {{"shadows", "maybe"}}}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("material 0 'Leaves'"), std::string::npos) << message;
    EXPECT_NE(message.find("\"on\", \"clip\", \"dither\", \"off\""), std::string::npos) << message;
}

TEST(GltfExtras, NonBooleanReceiveShadowsIsAnError) {
    TestGltf gltf = withMaterialExtras({{"extras", {{"receiveShadows", 1}}}});
    EXPECT_NE(loadError(gltf).find("receiveShadows must be true or false"), std::string::npos);
}

TEST(GltfExtras, NodeCastShadowsAppliesToItsOwnMeshesOnly) {
    TestGltf gltf;
    const int mesh = gltf.addTriangleMesh();
    const int child = gltf.addNode({{"name", "child"}, {"mesh", mesh}}, false);
    gltf.addNode({{"name", "parent"}, {"mesh", mesh}, {"extras", {{"castShadows", false}}}, {"children", {child}}});
    const Scene scene = load(gltf);
    ASSERT_EQ(scene.instances.size(), 2u);
    EXPECT_EQ(scene.instances[0].nodeName, "parent");
    EXPECT_FALSE(scene.instances[0].castShadows);
    EXPECT_TRUE(scene.instances[1].castShadows);
}

TEST(GltfExtras, NonBooleanCastShadowsNamesNodeAndKey) {
    TestGltf gltf;
    gltf.addNode({{"name", "Tree"}, {"extras", {{"castShadows", "yes"}}}});
    const std::string message = loadError(gltf);
    EXPECT_NE(message.find("node 0 'Tree'"), std::string::npos) << message;
    EXPECT_NE(message.find("castShadows"), std::string::npos) << message;
}
