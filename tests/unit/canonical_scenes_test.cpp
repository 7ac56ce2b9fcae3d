// The canonical shadow test scenes: the committed tests/scenes/*.gltf are what the generator writes,
// and each is a usable comparison scene (a camera, geometry, shadowed lights).
#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/canonical_scenes.h"
#include "penumbra/camera.h"
#include "scene/gltf_loader.h"
#include "penumbra/gltf_writer.h"

using namespace penumbra;
using penumbra::testing::TempDir;

namespace {

std::string committedPath(const std::string& name) {
    return std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/" + canonicalSceneFileName(name);
}

}  // namespace

TEST(CanonicalScenes, CommittedFilesAreWhatTheGeneratorWrites) {
    TempDir dir;
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        SCOPED_TRACE(info.name);
        ASSERT_TRUE(std::filesystem::exists(committedPath(info.name)));
        const std::string fresh = dir.file(info.fileName());
        writeGltfScene(makeCanonicalScene(info.name), fresh);
        EXPECT_TRUE(penumbra::testing::readFile(fresh) == penumbra::testing::readFile(committedPath(info.name)))
            << "tests/scenes/" << info.fileName() << " is stale: run ./build/tests/make_test_scenes tests/scenes";
    }
}

TEST(CanonicalScenes, EachHasACameraGeometryAndOnlyShadowedLights) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        SCOPED_TRACE(info.name);
        const Scene scene = loadGltfScene(committedPath(info.name));
        ASSERT_TRUE(scene.camera.has_value());
        EXPECT_EQ(scene.camera->name, "camera");
        EXPECT_GE(scene.instances.size(), 2u);
        ASSERT_FALSE(scene.lights.empty());
        for (const Light& light : scene.lights) {
            EXPECT_NE(light.shadows, LightShadows::None);
            EXPECT_GT(light.shadowStrength, 0.0f);
        }
    }
}

TEST(CanonicalScenes, LightTypesCoverSunSpotAndPoint) {
    EXPECT_EQ(makeCanonicalScene("low_sun").lights.at(0).type, LightType::Directional);
    EXPECT_EQ(makeCanonicalScene("spot_lights").lights.at(0).type, LightType::Spot);
    EXPECT_EQ(makeCanonicalScene("spot_lights").lights.at(1).type, LightType::Spot);
    EXPECT_EQ(makeCanonicalScene("point_light").lights.at(0).type, LightType::Point);
}

TEST(CanonicalScenes, LowSunIsEightDegreesAboveTheHorizon) {
    const Light sun = makeCanonicalScene("low_sun").lights.at(0);
    EXPECT_NEAR(glm::degrees(std::asin(-sun.wsDirection.y)), 8.0f, 1e-3f);
}

TEST(CanonicalScenes, UnknownNameIsAnError) { EXPECT_THROW(makeCanonicalScene("nope"), Error); }
