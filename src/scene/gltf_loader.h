#pragma once
// glTF 2.0 (.gltf / .glb) to Scene, as docs/scene-format.md specifies.
//
// - Every TRIANGLES primitive becomes one Mesh; other modes are skipped with a line in
//   Scene::warnings. A missing NORMAL gives flat normals (the primitive is unwelded).
// - The default scene (else scene 0, else every root node) is flattened to world space: one
//   Instance per (node, primitive). A node's `castShadows` extra applies to that node's own meshes
//   only; it is not inherited by its children.
// - Scene::lights[i] is KHR_lights_punctual's lights[i]. A light placed by a node gets the node's
//   world position and -Z axis; a light that no node of the scene references keeps the default
//   transform (at the origin, shining along -Z). When several nodes reference one light, the first
//   in traversal order places it (and a warning is recorded).
// - Camera: among the nodes of the scene with a perspective camera, the one named "camera", else
//   the one with the lowest node index.
// - Materials keep their glTF index; a default material is appended after them only if some
//   primitive has no material.
// Any bad input throws penumbra::Error with one line naming the file and the problem.
#include <cstdint>
#include <string>

#include "penumbra/scene_loading.h"

namespace penumbra {

// loadGltfScene(path, options) is declared in penumbra/scene_loading.h; external buffers and images
// are read through AssetAccess (scene/asset_access.h): inside the asset root, regular files only.

// A .gltf (JSON) or .glb (by its magic) held in memory, named `name` in messages. Only data: URIs
// and the GLB's own chunk are read: a URI naming an external file is an error.
Scene loadGltfSceneFromMemory(const uint8_t* data, size_t size, const std::string& name, const SceneLimits& limits = {});

// The same, its external files read as those of a file in `folder` would be (the fuzzer's entry, in a
// folder fixture with files beside and outside it).
Scene loadGltfSceneFromMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& folder,
                              const GltfLoadOptions& options);

}  // namespace penumbra
