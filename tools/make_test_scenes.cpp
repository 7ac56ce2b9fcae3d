// Writes the canonical shadow test scenes (src/scene/canonical_scenes.h) as OUTDIR/NAME.gltf (or .glb).
// Regenerate the committed copies with: ./build/tests/make_test_scenes tests/scenes
#include <cstdio>
#include <string>

#include "core/error.h"
#include "scene/canonical_scenes.h"
#include "penumbra/gltf_writer.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_test_scenes OUTDIR\n");
        return 2;
    }
    try {
        for (const penumbra::CanonicalSceneInfo& info : penumbra::canonicalScenes()) {
            const std::string path = std::string(argv[1]) + "/" + info.fileName();
            penumbra::writeGltfScene(penumbra::makeCanonicalScene(info.name), path);
            std::printf("%s: %s\n", path.c_str(), info.description.c_str());
        }
    } catch (const penumbra::Error& e) {
        std::fprintf(stderr, "make_test_scenes: %s\n", e.what());
        return 1;
    }
    return 0;
}
