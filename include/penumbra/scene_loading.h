#pragma once
// Where scenes come from: a glTF 2.0 file, the built-in demo scene, or a built-in scale scene.
#include <cstdint>
#include <string>

#include <penumbra/scene.h>

namespace penumbra {

// The model gen:field copies unless SceneSourceOptions::model names another glTF (Debian's
// assimp-testmodels, which scripts/setup.sh installs; 121k triangles, in millimetres).
inline constexpr const char* kDefaultFieldModel =
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

struct SceneSourceOptions {
    std::string model = kDefaultFieldModel;  // the glTF that gen:field copies
    bool addDefaultSun = true;               // a scene without lights gets a sun (and a warning)
};

// `source`: "" = the built-in demo scene; "gen:field:N[:S]" = N copies of the model on a square grid
// on a ground, a sun and S shadowed spot lights over the field, a camera that sees it all;
// "gen:boxes:N" = N separate small boxes on a ground under a sun; anything else = a .gltf / .glb
// path. Warnings (skipped primitives, the default sun) go to Scene::warnings. Bad input throws
// penumbra::Error with one line.
Scene loadScene(const std::string& source, const SceneSourceOptions& options = {});

Scene loadGltfScene(const std::string& path);
Scene makeDemoScene();

}  // namespace penumbra
