#pragma once
// 8-bit images in memory and their PNG I/O (stb). Pixel (0,0) is top-left.
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;  // 1 = gray, 3 = RGB, 4 = RGBA
    std::vector<uint8_t> pixels;

    Image() = default;
    Image(uint32_t w, uint32_t h, uint32_t c, uint8_t fill = 0) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}

    uint8_t& at(uint32_t x, uint32_t y, uint32_t c = 0) { return pixels[(size_t(y) * width + x) * channels + c]; }
    uint8_t at(uint32_t x, uint32_t y, uint32_t c = 0) const { return pixels[(size_t(y) * width + x) * channels + c]; }
    bool empty() const { return pixels.empty(); }
};

// Throws penumbra::Error naming the path when the file can't be written or read.
void writePng(const Image& image, const std::string& path);
Image readPng(const std::string& path, uint32_t desiredChannels = 0);
// Decodes a PNG or JPEG held in memory to RGBA8; throws Error naming `what` on failure, for any other
// format, and for images over 16384 pixels a side (checked from the header, before decoding).
Image decodeImageRgba(const uint8_t* data, size_t size, const std::string& what);
// The image scaled down (area average, aspect kept) so that neither side exceeds maxSide; the image
// itself when it fits.
Image downscaleToFit(const Image& image, uint32_t maxSide);

}  // namespace penumbra
