#version 460
// Visibility rasterizer, pass 1, for the meshlet items (visibility_raster_items.glsl).
#include "visibility_raster_items.glsl"
