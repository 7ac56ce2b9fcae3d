// The GPU data that <penumbra/shadows.glsl> reads: the headers C++ packs the same structs from
// (installed beside this file; Penumbra's build finds them in shaders/shared).
#ifndef PENUMBRA_SHADOWS_STRUCTS_GLSL
#define PENUMBRA_SHADOWS_STRUCTS_GLSL
#include "shadow_view_structs.h"
#include "shadow_structs.h"
#include "other_shadow_structs.h"
#include "virtual_lit_structs.h"
#endif
