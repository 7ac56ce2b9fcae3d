#pragma once
// The canonical shadow test scenes: small scenes, each stressing one way shadow maps fail,
// with a camera and shadowed lights. tools/make_test_scenes writes them to tests/scenes/NAME.gltf, the
// files that `penumbra compare` and the regression tests read; a unit test checks that the committed
// files are what this code writes.
#include <string>
#include <vector>

#include "penumbra/scene.h"

namespace penumbra {

struct CanonicalSceneInfo {
    std::string name;         // file stem under tests/scenes/
    std::string description;  // one line: what it stresses
    bool binary = false;      // written as NAME.glb (large meshes) instead of NAME.gltf
    std::string fileName() const { return name + (binary ? ".glb" : ".gltf"); }
};

// The installed glTF sample model that the CAD scene places (Debian package assimp-testmodels).
inline constexpr const char* kCadEngineSamplePath =
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

// In a fixed order: the first eight scenes (directional-light scenes, then spot_lights and point_light),
// then those added for the shadow-fidelity measurements (docs/fidelity.md).
const std::vector<CanonicalSceneInfo>& canonicalScenes();
// The file name under tests/scenes/ of the scene named `name` (NAME.gltf or NAME.glb).
std::string canonicalSceneFileName(const std::string& name);

// Builds the scene named `name`; throws penumbra::Error for an unknown name.
Scene makeCanonicalScene(const std::string& name);

}  // namespace penumbra
