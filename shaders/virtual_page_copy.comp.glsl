#version 460
// The virtual page copy (virtual_page_copy.glsl) into an R16_UNORM pool: devices with
// shaderStorageImageExtendedFormats (render/virtual_page_storage.h virtualPoolFormat).
#define PENUMBRA_POOL_FORMAT r16
#include "virtual_page_copy.glsl"
