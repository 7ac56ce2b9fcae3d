#pragma once
// The largest image Penumbra decodes (textures, `penumbra diff` inputs): a file's header can promise
// any size, so the decoder refuses more than this before allocating (1 GiB of RGBA8 at most).
#include <cstdint>

namespace penumbra {

inline constexpr uint32_t kMaxDecodedImageSide = 16384;
inline constexpr uint64_t kMaxDecodedImagePixels = uint64_t(kMaxDecodedImageSide) * kMaxDecodedImageSide;

}  // namespace penumbra
