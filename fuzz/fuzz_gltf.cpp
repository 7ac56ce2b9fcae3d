// Fuzz target: a .gltf (JSON) or .glb (by its magic) held in memory, through the whole CPU side of a
// frame: loading (tinygltf, accessors, materials, lights, extras, embedded images), the scene checks
// the renderer makes, the camera and the shadow plan. External files are never read.
#include <cstddef>
#include <cstdint>

#include "penumbra/camera.h"
#include "penumbra/error.h"
#include "scene/gltf_loader.h"
#include "scene/scene_validation.h"
#include "shadows/shadow_planner.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    penumbra::Scene scene;
    try {
        scene = penumbra::loadGltfSceneFromMemory(data, size, "fuzz.gltf");
    } catch (const penumbra::Error&) {
        return 0;  // a clean one-line error is a correct answer to a bad file
    }
    // What the loader accepts, the renderer must accept too: validateScene must not throw here.
    penumbra::validateScene(scene);
    try {
        const penumbra::CameraView view = penumbra::resolveCameraView(scene, 64, 48);
        penumbra::ShadowSettings settings;
        (void)penumbra::ShadowPlanner::plan(scene, view, settings);
    } catch (const penumbra::Error&) {
        // The camera or the plan may still refuse a scene (e.g. a camera inside degenerate bounds).
    }
    return 0;
}
