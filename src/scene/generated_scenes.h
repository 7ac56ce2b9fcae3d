#pragma once
// Built-in scale scenes (`gen:` sources), so any performance number can be reproduced without files:
//   gen:field:N[:S[:P]]  N copies of a real model on a square grid on a ground, a sun, S shadowed spot
//                    lights spread over the field and P unshadowed point lights near the ground, a
//                    camera that sees the whole field and its shadows;
//   gen:boxes:N[:P]  N separate small boxes (one instance each) on a ground under a sun, P point lights.
#include <cstdint>
#include <optional>
#include <string>

#include "penumbra/scene.h"

namespace penumbra {

struct GeneratedSceneSpec {
    enum class Kind { Field, Boxes } kind = Kind::Field;
    uint32_t count = 1;       // copies (field) or boxes
    uint32_t spotLights = 0;  // field only
    uint32_t pointLights = 0;
};

// nullopt when `source` does not start with "gen:"; throws Error for a malformed or out-of-range spec.
std::optional<GeneratedSceneSpec> parseGeneratedSceneSpec(const std::string& source);

// `model`: the scene to copy (its meshes, materials, textures and instances; lights and cameras are
// dropped). Each copy is scaled to 2 m across, stands on the ground and is turned by a fixed angle.
Scene makeFieldScene(const Scene& model, uint32_t copies, uint32_t spotLights, uint32_t pointLights = 0);
Scene makeBoxesScene(uint32_t boxes, uint32_t pointLights = 0);

inline constexpr uint32_t kMaxFieldCopies = 10000;
inline constexpr uint32_t kMaxFieldSpotLights = 64;
inline constexpr uint32_t kMaxBoxes = 4000000;
inline constexpr uint32_t kMaxPointLights = 1024;

}  // namespace penumbra
