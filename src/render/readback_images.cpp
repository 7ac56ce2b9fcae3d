#include "render/readback_images.h"

#include <algorithm>
#include <cstring>

namespace penumbra {

Image outputImageFromRgba(const void* rgba, uint32_t width, uint32_t height, uint32_t channels) {
    const auto* source = static_cast<const uint8_t*>(rgba);
    Image image(width, height, channels);
    for (size_t p = 0; p < size_t(width) * height; ++p)
        for (uint32_t c = 0; c < channels; ++c) image.pixels[p * channels + c] = source[p * 4 + c];
    return image;
}

Image depthToGray(const void* depth, uint32_t size) {
    const auto* source = static_cast<const uint8_t*>(depth);
    Image gray(size, size, 1);
    for (size_t p = 0; p < size_t(size) * size; ++p) {
        float value = 0.0f;
        std::memcpy(&value, source + p * 4, sizeof(float));
        gray.pixels[p] = uint8_t(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    return gray;
}

Image sideBySide(const Image& left, const Image& right) {
    Image image(left.width + right.width, std::max(left.height, right.height), 1);
    std::fill(image.pixels.begin(), image.pixels.end(), uint8_t(255));
    for (uint32_t y = 0; y < left.height; ++y)
        std::copy_n(&left.pixels[size_t(y) * left.width], left.width, &image.pixels[size_t(y) * image.width]);
    for (uint32_t y = 0; y < right.height; ++y)
        std::copy_n(&right.pixels[size_t(y) * right.width], right.width,
                    &image.pixels[size_t(y) * image.width + left.width]);
    return image;
}

}  // namespace penumbra
