#pragma once
// Scene to glTF 2.0: a self-contained .gltf (buffers as base64 data URIs) or a .glb, chosen by the
// path's extension. Each instance becomes a node with a matrix (and `castShadows` in extras), each
// light a node whose -Z axis is the light's direction, the camera a node named "camera".
// Materials carry KHR_materials_unlit and the shadow extras of docs/scene-format.md; textures are PNG.
// Loading the written file with loadGltfScene gives back the same lights, materials, textures,
// instance transforms and camera (meshes without instances are written but not instanced).
#include <string>

#include <penumbra/scene.h>

namespace penumbra {

// Throws penumbra::Error naming the path when the extension is neither .gltf nor .glb or the file
// cannot be written.
void writeGltfScene(const Scene& scene, const std::string& path);

}  // namespace penumbra
