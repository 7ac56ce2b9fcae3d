#version 460
// The virtual page copy (virtual_page_copy.glsl) into an R32_SFLOAT pool holding the same values: devices
// without storage images of R16_UNORM (render/virtual_page_storage.h virtualPoolFormat).
#define PENUMBRA_POOL_FORMAT r32f
#include "virtual_page_copy.glsl"
