#pragma once
// The checks every Scene passes before the renderer (or anything that indexes its arrays on the GPU)
// uses it, whatever made it: the glTF loader, SceneBuilder, or a program's own code. Every index is
// in range, every number finite and within its documented range, so no bad scene reaches a shader as
// an out-of-bounds read or a NaN. Each throws penumbra::Error naming the first bad object and value,
// e.g. "scene: mesh 3 'wheel': index 17 is 40, not below the vertex count 12".
#include <string>

#include "penumbra/scene.h"
#include "penumbra/scene_builder.h"  // validateScene, public

namespace penumbra {

// World coordinates beyond this (in any unit) are refused: shadow math squares distances, and a float
// holds no useful position that large anyway (its spacing there is over 1000 units).
inline constexpr float kMaxWorldCoordinate = 1.0e10f;

// One light or material, named `what` in the message ("light 2 'sun'"). validateLight wants a unit
// wsDirection (Renderer::setLight normalizes the caller's first).
void validateLight(const Light& light, const std::string& what);
void validateInstance(const Scene& scene, const Instance& instance, const std::string& what);
void validateMaterial(const Material& material, size_t textureCount, const std::string& what);
// A camera: finite transform with non-degenerate axes, yfov in (0, pi), 0 < zNear < zFar.
void validateCamera(const Camera& camera, const std::string& what);

}  // namespace penumbra
