#include "penumbra/image.h"

#include "core/error.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
// stb_image's implementation is compiled by tinygltf (src/scene/tinygltf_impl.cpp).
#include <stb_image.h>

namespace penumbra {

void writePng(const Image& image, const std::string& path) {
    if (image.empty()) throw Error("cannot write " + path + ": empty image");
    const int ok = stbi_write_png(path.c_str(), int(image.width), int(image.height), int(image.channels),
                                  image.pixels.data(), int(image.width * image.channels));
    if (!ok) throw Error("cannot write " + path + ": the file could not be created");
}

Image readPng(const std::string& path, uint32_t desiredChannels) {
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, int(desiredChannels));
    if (!data) throw Error("cannot read " + path + ": " + stbi_failure_reason());
    Image image(uint32_t(w), uint32_t(h), desiredChannels ? desiredChannels : uint32_t(n));
    std::copy(data, data + image.pixels.size(), image.pixels.begin());
    stbi_image_free(data);
    return image;
}

Image decodeImageRgba(const uint8_t* data, size_t size, const std::string& what) {
    int w = 0, h = 0, n = 0;
    stbi_uc* pixels = stbi_load_from_memory(data, int(size), &w, &h, &n, 4);
    if (!pixels) throw Error(what + ": image failed to decode (" + stbi_failure_reason() + ")");
    Image image(uint32_t(w), uint32_t(h), 4);
    std::copy(pixels, pixels + image.pixels.size(), image.pixels.begin());
    stbi_image_free(pixels);
    return image;
}

}  // namespace penumbra
