// The viewer's scene document (src/viewer/scene_document.h), what File > Open, a dropped file, R,
// File > Reload, a change on disk and File > Save scene do, without a window: real files of
// tests/scenes/ copied into a temporary directory, the renderer replaced by a function that keeps the
// installed scene (or refuses it, as a GPU that cannot take it would).
#include <filesystem>
#include <string>

#include <glm/gtc/matrix_access.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_test_files.h"
#include "penumbra/error.h"
#include "penumbra/image.h"
#include "penumbra/scene_loading.h"
#include "viewer/scene_document.h"

using namespace penumbra;
using namespace penumbra::viewer;
using penumbra::testing::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kScenes = std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/";

// The renderer's side: the scene last installed, and how many were.
struct FakeRenderer {
    Scene scene;
    int installs = 0;
    bool refuse = false;
    SceneDocument::InstallScene install() {
        return [this](Scene&& next) {
            if (refuse) throw Error("the GPU cannot take this scene");
            scene = std::move(next);
            ++installs;
        };
    }
};

// A document on a copy of tests/scenes/NAME, its first scene installed.
struct OpenDocument {
    TempDir dir;
    std::string path;
    SceneDocument document;
    FakeRenderer renderer;
    explicit OpenDocument(const std::string& name)
        : path(copyScene(dir, name)), document(path, 0) {
        renderer.scene = document.loadFirst();
    }
    static std::string copyScene(const TempDir& dir, const std::string& name) {
        const std::string path = dir.file(name);
        fs::copy_file(kScenes + name, path);
        return path;
    }
    std::optional<SceneEvent> update() { return document.update(FileWatcher::Clock::now(), renderer.scene, renderer.install()); }
};

glm::vec3 wsPositionOf(const Camera& camera) { return glm::vec3(glm::column(camera.worldFromView, 3)); }

}  // namespace

TEST(SceneDocument, OpenAnotherSceneInstallsItAtItsOwnCamera) {
    OpenDocument open("cube.gltf");
    const std::string other = OpenDocument::copyScene(open.dir, "spot_lights.gltf");
    open.document.requestOpen(other);  // File > Open and a dropped file
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_TRUE(event->opened);
    EXPECT_EQ(event->message, "opened " + other);
    EXPECT_EQ(open.renderer.installs, 1);
    EXPECT_EQ(open.renderer.scene.lights.size(), 2u) << "spot_lights.gltf has two spot lights";
    EXPECT_EQ(open.document.source(), other);
    ASSERT_TRUE(event->camera.has_value()) << "another scene starts at its own camera";
    const Scene expected = loadScene(other);
    ASSERT_TRUE(expected.camera.has_value());
    EXPECT_EQ(wsPositionOf(*event->camera), wsPositionOf(*expected.camera));
    EXPECT_NE(wsPositionOf(*event->camera), wsPositionOf(*loadScene(open.path).camera)) << "the two cameras must differ";
    EXPECT_EQ(open.document.defaultSavePath(), fs::path(other).replace_extension(".edited.gltf").string());
    EXPECT_FALSE(open.update().has_value()) << "a request is acted on once";
}

TEST(SceneDocument, ReloadKeepsTheCamera) {
    OpenDocument open("cube.gltf");
    open.document.requestReload();  // R and File > Reload
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_TRUE(event->opened);
    EXPECT_EQ(event->message, "reloaded " + open.path);
    EXPECT_FALSE(event->camera.has_value()) << "a reload keeps the user's camera";
    EXPECT_EQ(open.renderer.installs, 1);
    // Opening the open file by name is a reload too.
    open.document.requestOpen(open.path);
    EXPECT_FALSE(open.update()->camera.has_value());
}

TEST(SceneDocument, ChangeOnDiskReloadsOnceTheFileHeld) {
    OpenDocument open("cube.gltf");
    EXPECT_FALSE(open.update().has_value());
    nlohmann::json gltf = nlohmann::json::parse(penumbra::testing::readFile(open.path));
    gltf["extensions"]["KHR_lights_punctual"]["lights"][0]["extras"]["shadowStrength"] = 0.25;
    penumbra::testing::writeFile(open.path, gltf.dump());
    EXPECT_FALSE(open.update().has_value()) << "the new stamp must hold for two polls";
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_EQ(event->message, "reloaded " + open.path);
    EXPECT_FLOAT_EQ(open.renderer.scene.lights[0].shadowStrength, 0.25f);
}

TEST(SceneDocument, BadFileKeepsTheOldSceneAndSetsTheError) {
    OpenDocument open("cube.gltf");
    const std::string bad = open.dir.file("bad.gltf");
    nlohmann::json gltf = nlohmann::json::parse(penumbra::testing::readFile(open.path));
    gltf["materials"][0]["extras"]["shadows"] = "sometimes";
    penumbra::testing::writeFile(bad, gltf.dump());
    open.document.requestOpen(bad);
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_FALSE(event->opened);
    EXPECT_FALSE(event->camera.has_value());
    EXPECT_EQ(open.renderer.installs, 0) << "nothing installed";
    EXPECT_EQ(open.document.source(), open.path) << "the old scene stays open";
    EXPECT_NE(open.document.error().find("sometimes"), std::string::npos) << open.document.error();
    EXPECT_EQ(event->message, open.document.error());
    // The next load that succeeds clears the error.
    open.document.requestReload();
    EXPECT_TRUE(open.update()->opened);
    EXPECT_EQ(open.document.error(), "");
}

TEST(SceneDocument, SceneTheRendererRefusesKeepsTheOldSource) {
    OpenDocument open("cube.gltf");
    const std::string other = OpenDocument::copyScene(open.dir, "spot_lights.gltf");
    open.renderer.refuse = true;
    const SceneEvent event = open.document.open(other, open.renderer.install());
    EXPECT_FALSE(event.opened);
    EXPECT_EQ(open.document.source(), open.path);
    EXPECT_EQ(open.document.error(), "the GPU cannot take this scene");
}

TEST(SceneDocument, OpenWinsOverReloadInTheSameFrame) {
    OpenDocument open("cube.gltf");
    const std::string other = OpenDocument::copyScene(open.dir, "spot_lights.gltf");
    open.document.requestReload();
    open.document.requestOpen(other);
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_EQ(event->message, "opened " + other);
    EXPECT_EQ(open.renderer.installs, 1);
}

TEST(SceneDocument, SaveWritesTheEditedShadowExtras) {
    OpenDocument open("cube.gltf");
    Scene& scene = open.renderer.scene;  // edited as the inspector does through the renderer
    scene.lights[0].shadows = LightShadows::Pcss;
    scene.lights[0].shadowStrength = 0.4f;
    scene.lights[0].shadowNormalBias = 2.5f;
    scene.materials[0].receiveShadows = false;
    scene.instances[0].castShadows = false;
    const std::string saved = open.dir.file("saved.glb");
    open.document.requestSave(saved);
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event.has_value());
    EXPECT_FALSE(event->opened) << "saving opens nothing";
    EXPECT_EQ(event->message, "saved the scene to " + saved);
    const Scene back = loadScene(saved);
    ASSERT_EQ(back.lights.size(), 1u);
    EXPECT_EQ(back.lights[0].shadows, LightShadows::Pcss);
    EXPECT_FLOAT_EQ(back.lights[0].shadowStrength, 0.4f);
    EXPECT_FLOAT_EQ(back.lights[0].shadowNormalBias, 2.5f);
    EXPECT_FALSE(back.materials[0].receiveShadows);
    EXPECT_FALSE(back.instances[0].castShadows);
    EXPECT_EQ(open.document.source(), open.path) << "the open file stays the document";
}

TEST(SceneDocument, SaveOverTheOpenFileIsNoReload) {
    OpenDocument open("cube.gltf");
    open.renderer.scene.lights[0].shadowStrength = 0.5f;
    EXPECT_EQ(open.document.save(open.renderer.scene, open.path).message, "saved the scene to " + open.path);
    EXPECT_FALSE(open.update().has_value());
    EXPECT_FALSE(open.update().has_value()) << "the viewer's own write is what is loaded";
    EXPECT_EQ(open.renderer.installs, 0);
}

TEST(SceneDocument, SaveToABadPathIsAnErrorLine) {
    OpenDocument open("cube.gltf");
    const SceneEvent event = open.document.save(open.renderer.scene, open.dir.file("no_such_dir/scene.gltf"));
    EXPECT_FALSE(event.opened);
    EXPECT_NE(event.message.find("no_such_dir"), std::string::npos) << event.message;
    EXPECT_EQ(open.document.error(), "") << "a failed save leaves the scene as it is";
    const SceneEvent wrongType = open.document.save(open.renderer.scene, open.dir.file("scene.obj"));
    EXPECT_NE(wrongType.message.find("scene.obj"), std::string::npos) << wrongType.message;
}

TEST(SceneDocument, DemoAndGeneratedScenesHaveNoFile) {
    SceneDocument demo("", 0);
    EXPECT_EQ(demo.label(), "the demo scene");
    EXPECT_EQ(demo.defaultSavePath(), "penumbra-scene.gltf");
    FakeRenderer renderer;
    renderer.scene = demo.loadFirst();
    EXPECT_FALSE(demo.update(FileWatcher::Clock::now(), renderer.scene, renderer.install()).has_value());
    SceneDocument generated("gen:boxes:3", 0);
    EXPECT_EQ(generated.defaultSavePath(), "penumbra-scene.gltf");
}

TEST(SceneDocument, LoadingOptionsApplyToEverySceneOpened) {
    // The viewer's --ground: the first scene, another opened and a reload all get the plane.
    TempDir dir;
    const std::string cube = OpenDocument::copyScene(dir, "cube.gltf");
    const std::string spots = OpenDocument::copyScene(dir, "spot_lights.gltf");
    SceneSourceOptions grounded;
    grounded.addGround = true;
    SceneDocument document(cube, 0, grounded);
    FakeRenderer renderer;
    renderer.scene = document.loadFirst();
    EXPECT_EQ(renderer.scene.instances.size(), loadScene(cube).instances.size() + 1);
    EXPECT_EQ(renderer.scene.instances.back().nodeName, "ground");
    for (const std::string& source : {spots, spots}) {  // open, then reload
        document.requestOpen(source);
        ASSERT_TRUE(document.update(FileWatcher::Clock::now(), renderer.scene, renderer.install()).has_value());
        EXPECT_EQ(renderer.scene.instances.size(), loadScene(spots).instances.size() + 1) << source;
        EXPECT_EQ(renderer.scene.instances.back().nodeName, "ground");
    }
    EXPECT_EQ(renderer.installs, 2);
}

// A copy of cube.gltf in DIR/scene/ with one image, "../outside.png", which lies in DIR.
std::string sceneReachingOut(const TempDir& dir) {
    fs::create_directories(dir.file("scene"));
    nlohmann::json doc = nlohmann::json::parse(penumbra::testing::readFile(kScenes + "cube.gltf"));
    doc["images"] = {{{"uri", "../outside.png"}}};
    Image outside(2, 2, 4);
    outside.pixels.assign(16, 255);
    writePng(outside, dir.file("outside.png"));
    const std::string path = dir.file("scene/cube.gltf");
    penumbra::testing::writeFile(path, doc.dump());
    return path;
}

TEST(SceneDocument, OpeningASceneThatReachesOutsideItsFolderKeepsTheOldOne) {
    OpenDocument open("cube.gltf");
    const std::string outside = sceneReachingOut(open.dir);
    open.document.requestOpen(outside);  // File > Open and a dropped file
    const std::optional<SceneEvent> event = open.update();
    ASSERT_TRUE(event);
    EXPECT_FALSE(event->opened);
    EXPECT_NE(open.document.error().find("outside the asset root"), std::string::npos) << open.document.error();
    EXPECT_EQ(open.document.source(), open.path);
}

TEST(SceneDocument, AssetRootOfTheLoadingOptionsAppliesToEverySceneOpened) {
    TempDir dir;
    const std::string outside = sceneReachingOut(dir);
    SceneSourceOptions widened;
    widened.assetRoot = dir.file("");
    SceneDocument document("", 0, widened);
    FakeRenderer renderer;
    renderer.scene = document.loadFirst();
    EXPECT_TRUE(document.open(outside, renderer.install()).opened) << document.error();
    EXPECT_TRUE(document.open(outside, renderer.install()).opened) << document.error();  // R: a reload
}

TEST(SceneDocument, LimitsOfTheLoadingOptionsApplyToEverySceneOpened) {
    OpenDocument open("cube.gltf");
    SceneSourceOptions tight;
    tight.limits.maxVertices = 3;
    SceneDocument document("", 0, tight);
    FakeRenderer renderer;
    const SceneEvent event = document.open(open.path, renderer.install());
    EXPECT_FALSE(event.opened);
    EXPECT_NE(event.message.find("over the vertices budget of 3"), std::string::npos) << event.message;
}
