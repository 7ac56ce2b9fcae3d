// Fuzz target: the texture decode path of the glTF loader (PNG / JPEG bytes to RGBA8 through libpng
// and libjpeg-turbo, with the size limits) and the downscale applied to textures over the device's image size limit.
#include <cstddef>
#include <cstdint>

#include "core/image_decode.h"
#include "penumbra/error.h"
#include "penumbra/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // Headers may promise up to 16384^2 pixels, which the decoder accepts; decoding that much garbage
    // is correct but slow, so the fuzzer spends its time on smaller images.
    try {
        const penumbra::ImageHeader header = penumbra::readImageHeader(data, size, "fuzz image");
        if (uint64_t(header.width) * header.height > (1u << 22)) return 0;
    } catch (const penumbra::Error&) {
    }
    try {
        const penumbra::Image rgba = penumbra::decodeImageRgba(data, size, "fuzz image");
        if (rgba.pixels.size() != size_t(rgba.width) * rgba.height * 4) __builtin_trap();
        const penumbra::Image small = penumbra::downscaleToFit(rgba, 1 + data[0] % 64);
        if (small.width > 64 || small.height > 64 || small.pixels.size() != size_t(small.width) * small.height * 4)
            __builtin_trap();
    } catch (const penumbra::Error&) {
    }
    return 0;
}
