// Bad input for `penumbra reference` and `penumbra compare`: a one-line error and exit code 1, or an
// explicit empty result; never a crash.
#include <cstdlib>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "scene/canonical_scenes.h"
#include "scene/gltf_loader.h"
#include "penumbra/gltf_writer.h"
#include "penumbra/scene_builder.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

std::string sceneArg(const std::string& name) {
    return std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/" + canonicalSceneFileName(name);
}

std::string deviceArgs() {
    const char* device = std::getenv("PENUMBRA_DEVICE");
    return std::string(" --device ") + (device ? device : "cpu") + " --validation --width 64 --height 36";
}

// A scene file written for one test into the temporary directory, removed afterwards.
class TempScene {
public:
    TempScene(const Scene& scene, const std::string& stem)
        : path_((std::filesystem::temp_directory_path() /
                 ("penumbra_cli_" + stem + "_" + std::to_string(::getpid()) + ".gltf"))
                    .string()) {
        writeGltfScene(scene, path_);
    }
    ~TempScene() { std::filesystem::remove(path_); }
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

// A box on a floor under a shadowed sun; the camera looks at it, or straight up into the empty sky.
Scene boxUnderSun(bool lookAtTheSky, LightShadows shadows = LightShadows::Soft) {
    SceneBuilder builder;
    builder.addInstance(builder.addMesh(makePlaneMesh({20.0f, 20.0f}, 0)), glm::mat4(1.0f));
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), 0)),
                        glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}));
    Light sun = makeDirectionalLight({0.3f, -1.0f, -0.2f}, 3.0f);
    sun.name = "sun";
    sun.shadows = shadows;
    builder.addLight(sun);
    const glm::vec3 eye(0.0f, 4.0f, 6.0f);
    builder.setCamera(makeLookAtCamera(eye, lookAtTheSky ? eye + glm::vec3(0.0f, 1.0f, 0.01f) : glm::vec3(0.0f),
                                       glm::radians(50.0f)));
    return builder.build();
}

}  // namespace

TEST(CliReference, LightIndexPastTheEndIsAOneLineError) {
    for (const char* command : {"reference -o /dev/null", "compare"}) {
        SCOPED_TRACE(command);
        const CliRun run = runPenumbra(std::string(command) + " " + sceneArg("low_sun") + " --light 7" + deviceArgs());
        EXPECT_EQ(run.exitCode, 1);
        EXPECT_TRUE(isOneLineError(run.err)) << run.err;
        EXPECT_NE(run.err.find("light 7 does not exist"), std::string::npos) << run.err;
    }
}

TEST(CliReference, LightWithoutShadowsIsAOneLineError) {
    const TempScene scene(boxUnderSun(false, LightShadows::None), "no_shadows");
    for (const char* command : {"reference -o /dev/null", "compare"}) {
        SCOPED_TRACE(command);
        const CliRun run = runPenumbra(std::string(command) + " " + scene.path() + deviceArgs());
        EXPECT_EQ(run.exitCode, 1);
        EXPECT_TRUE(isOneLineError(run.err)) << run.err;
        EXPECT_NE(run.err.find("casts no shadows"), std::string::npos) << run.err;
    }
}

TEST(CliReference, SceneWithNothingInViewGivesAnExplicitEmptyComparison) {
    const TempScene scene(boxUnderSun(true), "sky");
    const CliRun run = runPenumbra("compare " + scene.path() + " --json" + deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json metrics = nlohmann::json::parse(run.out);
    EXPECT_EQ(metrics.at("validPixels").get<uint64_t>(), 0u);
    EXPECT_NE(run.err.find("no pixel is valid for comparison"), std::string::npos) << run.err;
}

TEST(CliReference, ReferenceOfASceneWithNothingInViewIsAllLit) {
    const TempScene scene(boxUnderSun(true), "sky_reference");
    const std::string png = scene.path() + ".png";
    const CliRun run = runPenumbra("reference " + scene.path() + " -o " + png + deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find(" 0 of 2304 pixels valid"), std::string::npos) << run.out;
    const Image image = readPng(png);
    std::filesystem::remove(png);
    for (uint8_t value : image.pixels) ASSERT_EQ(value, 255);
}

TEST(CliReference, MissingSceneFileIsAOneLineError) {
    const CliRun run = runPenumbra("compare /nonexistent/scene.gltf" + deviceArgs());
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_TRUE(isOneLineError(run.err)) << run.err;
}
