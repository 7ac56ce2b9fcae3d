#pragma once
// The built-in demo scene used when no glTF is given: a scene holding what Catlike Coding's "Directional
// Shadows" and "Spotlight Shadows" tutorials exercise: a large ground, boxes, spheres and a thin wall near
// the camera, far objects (40-80 m) so that cascades matter, an alpha-clipped quad, a transparent (dithered
// shadows) sphere, an unlit box, a sun and two coloured shadowed spot lights. Exposure: Lambert =
// baseColor/pi x intensity x N.L, so pi lux is full white; the sun gives ~3 lux and the spots ~1-2 lux at the
// spots they aim at.
#include "penumbra/scene_loading.h"

namespace penumbra {

// Declared in penumbra/scene_loading.h.

}  // namespace penumbra
