#pragma once
// Where scenes come from: a glTF 2.0 file, the built-in demo scene, or a built-in scale scene, with
// what the loading may add to them (a default sun, a ground plane).
#include <cstdint>
#include <string>

#include <penumbra/scene.h>
#include <penumbra/scene_limits.h>

namespace penumbra {

// The model gen:field copies unless SceneSourceOptions::model names another glTF (Debian's
// assimp-testmodels, which scripts/setup.sh installs; 121k triangles, in millimetres).
inline constexpr const char* kDefaultFieldModel =
    "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

// How a glTF file is read (docs/security.md). Its external buffers and images are named by URIs:
// `data:` URIs, or paths relative to the scene file's folder that must resolve (percent-decoded, the
// symlinks followed) to a regular file inside `assetRoot`. An absolute path, another URI scheme
// (`file:`, `http:`, ...), a path that leaves the root, or a directory, device, FIFO or socket is
// refused with one penumbra::Error line naming the reference and the rule.
struct GltfLoadOptions {
    std::string assetRoot;  // "" = the scene file's folder; a caller who trusts the input may widen it
    SceneLimits limits;     // the budgets of penumbra/scene_limits.h
};

struct SceneSourceOptions {
    std::string model = kDefaultFieldModel;  // the glTF that gen:field copies
    bool addDefaultSun = true;               // a scene without lights gets a sun (and a warning)
    bool addGround = false;                  // addGroundPlane (the CLI's and the viewer's --ground)
    std::string assetRoot;                   // GltfLoadOptions::assetRoot of the scene file (and of `model`)
    SceneLimits limits;                      // GltfLoadOptions::limits of the scene file (and of `model`)
};

// `source`: "" = the built-in demo scene; "gen:field:N[:S]" = N copies of the model on a square grid
// on a ground, a sun and S shadowed spot lights over the field, a camera that sees it all;
// "gen:boxes:N" = N separate small boxes on a ground under a sun; anything else = a .gltf / .glb
// path. Warnings (skipped primitives, the default sun) go to Scene::warnings. Bad input throws
// penumbra::Error with one line.
Scene loadScene(const std::string& source, const SceneSourceOptions& options = {});

// Puts a ground under the scene, for a lone model that would otherwise float in the sky: a square
// of 4x the scene's larger horizontal extent, centred under its bounds, facing up a hair (1e-4 of
// that extent) below their lowest point, so that a floor of the scene's own at that height stays in
// front of it instead of fighting it in the depth test. Opaque, single-sided, matte neutral grey
// (base colour 0.5, metallic 0, roughness 1); it receives shadows but casts none (it is below
// everything). The renderer and the ray-traced reference both see it, as any other instance.
// A scene without a camera is given the automatic framing of its bounds before the plane grows
// them, so it is seen as it was. Throws penumbra::Error for a scene without geometry.
void addGroundPlane(Scene& scene);

// A .gltf or .glb file; see GltfLoadOptions for what it may read and cost.
Scene loadGltfScene(const std::string& path, const GltfLoadOptions& options = {});
Scene makeDemoScene();

}  // namespace penumbra
