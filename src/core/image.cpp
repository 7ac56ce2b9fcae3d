#include "penumbra/image.h"

#include <algorithm>

#include "core/error.h"
#include "penumbra/files.h"
#include "core/image_decode.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace penumbra {

void writePng(const Image& image, const std::string& path) {
    if (image.empty()) throw Error("cannot write " + path + ": empty image");
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels || image.channels < 1 ||
        image.channels > 4)
        throw Error("cannot write " + path + ": the image's size and pixels disagree");
    int length = 0;
    unsigned char* png = stbi_write_png_to_mem(image.pixels.data(), int(image.width * image.channels), int(image.width),
                                               int(image.height), int(image.channels), &length);
    if (!png) throw Error("cannot write " + path + ": PNG encoding failed");
    try {
        writeFileAtomically(path, png, size_t(length));
    } catch (...) {
        STBIW_FREE(png);
        throw;
    }
    STBIW_FREE(png);
}

Image readPng(const std::string& path, uint32_t desiredChannels) {
    std::vector<uint8_t> bytes;
    try {
        bytes = readFileBytes(path);
    } catch (const Error& e) {
        throw Error(std::string("cannot read ") + e.what());
    }
    if (!isPngData(bytes.data(), bytes.size())) throw Error("cannot read " + path + ": not a PNG file");
    return decodePngOrJpeg(bytes.data(), bytes.size(), desiredChannels, "cannot read " + path);
}

Image decodeImageRgba(const uint8_t* data, size_t size, const std::string& what) {
    return decodePngOrJpeg(data, size, 4, what);
}

Image downscaleToFit(const Image& image, uint32_t maxSide) {
    if (maxSide == 0) throw Error("internal: downscaleToFit to 0 pixels");
    if (image.width <= maxSide && image.height <= maxSide) return image;
    // Area average over the source pixels each destination pixel covers (integer footprints).
    const double scale = double(std::max(image.width, image.height)) / double(maxSide);
    const uint32_t width = std::max(1u, std::min(maxSide, uint32_t(double(image.width) / scale)));
    const uint32_t height = std::max(1u, std::min(maxSide, uint32_t(double(image.height) / scale)));
    Image out(width, height, image.channels);
    for (uint32_t y = 0; y < height; ++y) {
        const uint32_t y0 = uint32_t(uint64_t(y) * image.height / height);
        const uint32_t y1 = std::max(y0 + 1, uint32_t(uint64_t(y + 1) * image.height / height));
        for (uint32_t x = 0; x < width; ++x) {
            const uint32_t x0 = uint32_t(uint64_t(x) * image.width / width);
            const uint32_t x1 = std::max(x0 + 1, uint32_t(uint64_t(x + 1) * image.width / width));
            for (uint32_t c = 0; c < image.channels; ++c) {
                uint64_t sum = 0;
                for (uint32_t sy = y0; sy < y1; ++sy)
                    for (uint32_t sx = x0; sx < x1; ++sx) sum += image.at(sx, sy, c);
                const uint64_t count = uint64_t(y1 - y0) * (x1 - x0);
                out.at(x, y, c) = uint8_t((sum + count / 2) / count);
            }
        }
    }
    return out;
}

}  // namespace penumbra
