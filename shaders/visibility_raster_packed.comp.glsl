#version 460
// Visibility rasterizer, pass 1, for the packed items of meshes of one small meshlet (visibility_raster_items.glsl).
#define PENUMBRA_PACKED_ITEMS
#include "visibility_raster_items.glsl"
