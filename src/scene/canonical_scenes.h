#pragma once
// The canonical shadow test scenes (issue 3): small scenes, each stressing one way shadow maps fail,
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
};

// In a fixed order: directional-light scenes first, then spot_lights and point_light.
const std::vector<CanonicalSceneInfo>& canonicalScenes();

// Builds the scene named `name`; throws penumbra::Error for an unknown name.
Scene makeCanonicalScene(const std::string& name);

}  // namespace penumbra
