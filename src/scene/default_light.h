#pragma once
// Scenes without any light (common among glTF samples) would render in ambient light only. The CLI
// adds one shadowed sun to them, as glTF viewers add a default light, and says so on stderr.
#include "penumbra/scene.h"

namespace penumbra {

// Appends a directional light (from above, behind the viewer's left shoulder, ~55° elevation,
// intensity 3 lux, soft shadows) when scene.lights is empty; returns whether it did.
bool addDefaultSunIfUnlit(Scene& scene);

}  // namespace penumbra
