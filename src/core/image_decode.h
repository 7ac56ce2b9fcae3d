#pragma once
// PNG and JPEG decoding (libpng's simplified API, libjpeg-turbo's TurboJPEG): the formats glTF
// images may have. Both libraries are fuzzed upstream (OSS-Fuzz); stb_image 2.27 (Debian 12) was not
// kept, as fuzz_texture found an out-of-bounds write in its JPEG Huffman tables (docs/robustness.md).
#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/image.h"

namespace penumbra {

struct ImageHeader {
    uint32_t width = 0, height = 0;
};

bool isPngData(const uint8_t* data, size_t size);
bool isJpegData(const uint8_t* data, size_t size);

// The size a PNG or JPEG header promises; throws Error "<what>: ..." for another format or a bad header.
ImageHeader readImageHeader(const uint8_t* data, size_t size, const std::string& what);

// Decodes to `channels` (1 gray, 2 gray + alpha, 3 RGB, 4 RGBA; 0 = the file's own count). Refuses
// images over kMaxDecodedImageSide (src/core/image_limits.h) from the header, before allocating.
// Problems the decoder recovered from (a truncated JPEG scan, ...) are appended to `warnings`.
Image decodePngOrJpeg(const uint8_t* data, size_t size, uint32_t channels, const std::string& what,
                      std::vector<std::string>* warnings = nullptr);

}  // namespace penumbra
