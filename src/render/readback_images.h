#pragma once
// Host copies of what a frame rendered, as the CLI writes them: the colour (RGB) or AOV (gray)
// image, and the shadow atlases' depth as gray.
#include <cstdint>

#include "penumbra/image.h"

namespace penumbra {

// Tightly packed RGBA8 -> `channels` (1 = the red channel, 3 = RGB) per pixel.
Image outputImageFromRgba(const void* rgba, uint32_t width, uint32_t height, uint32_t channels);
// 32-bit float depth of a size x size atlas (0 = near the light, 1 = empty) to 8-bit gray.
Image depthToGray(const void* depth, uint32_t size);
// --dump-atlas: `left` (the directional atlas) then `right` (the spot/point atlas), top-aligned; the
// rest is white (depth 1, empty).
Image sideBySide(const Image& left, const Image& right);

}  // namespace penumbra
