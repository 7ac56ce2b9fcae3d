// Penumbra's own passes read the installed shadow sampling (penumbra/shadows.glsl) in their pushed set,
// its descriptors from binding kLitShadowBindingBase on, its specialization at constants 2, 3 (spot/point)
// and 4, 5 (directional).
#ifndef PENUMBRA_LIT_SHADOWS_GLSL
#define PENUMBRA_LIT_SHADOWS_GLSL
#include "pass_bindings.h"
#define PENUMBRA_SHADOW_SET kPassSet
#define PENUMBRA_SHADOW_BINDING_BASE kLitShadowBindingBase
#define PENUMBRA_SHADOW_CONSTANT_ID 2
#include "penumbra/shadows.glsl"
#endif
