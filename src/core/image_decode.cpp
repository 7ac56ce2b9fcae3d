#include "core/image_decode.h"

#include <cstring>
#include <limits>
#include <memory>

#include <png.h>
#include <turbojpeg.h>

#include "core/error.h"
#include "core/image_limits.h"

namespace penumbra {

namespace {

void checkSize(const ImageHeader& header, const std::string& what) {
    if (header.width == 0 || header.height == 0) throw Error(what + ": the image has no pixels");
    if (header.width > kMaxDecodedImageSide || header.height > kMaxDecodedImageSide ||
        uint64_t(header.width) * header.height > kMaxDecodedImagePixels)
        throw Error(what + ": the image is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                    ", larger than the " + std::to_string(kMaxDecodedImageSide) + "x" +
                    std::to_string(kMaxDecodedImageSide) + " Penumbra decodes");
}

// ---- PNG

struct PngImage {
    png_image image{};
    PngImage() { image.version = PNG_IMAGE_VERSION; }
    ~PngImage() { png_image_free(&image); }
};

void beginPng(PngImage& png, const uint8_t* data, size_t size, const std::string& what) {
    if (!png_image_begin_read_from_memory(&png.image, data, size))
        throw Error(what + ": PNG failed to decode (" + png.image.message + ")");
}

png_uint_32 pngFormat(png_uint_32 fileFormat, uint32_t channels) {
    switch (channels) {
        case 1: return PNG_FORMAT_GRAY;
        case 2: return PNG_FORMAT_GA;
        case 3: return PNG_FORMAT_RGB;
        case 4: return PNG_FORMAT_RGBA;
        default: return fileFormat & ~(PNG_FORMAT_FLAG_COLORMAP | PNG_FORMAT_FLAG_LINEAR);  // 8 bits per channel
    }
}

Image decodePng(const uint8_t* data, size_t size, uint32_t channels, const std::string& what,
                std::vector<std::string>* warnings) {
    PngImage png;
    beginPng(png, data, size, what);
    checkSize({png.image.width, png.image.height}, what);
    png.image.format = pngFormat(png.image.format, channels);
    Image image(png.image.width, png.image.height, PNG_IMAGE_PIXEL_CHANNELS(png.image.format));
    if (!png_image_finish_read(&png.image, nullptr, image.pixels.data(), 0, nullptr))
        throw Error(what + ": PNG failed to decode (" + png.image.message + ")");
    if ((png.image.warning_or_error & PNG_IMAGE_WARNING) && warnings)
        warnings->push_back(what + ": PNG decoded with a warning (" + png.image.message + ")");
    return image;
}

// ---- JPEG

struct JpegDecoder {
    tjhandle handle = tjInitDecompress();
    ~JpegDecoder() {
        if (handle) tjDestroy(handle);
    }
};

std::string jpegError(const JpegDecoder& decoder) { return tjGetErrorStr2(decoder.handle); }

ImageHeader jpegHeader(JpegDecoder& decoder, const uint8_t* data, size_t size, const std::string& what) {
    if (!decoder.handle) throw Error(what + ": the JPEG decoder could not start");
    if (size > std::numeric_limits<unsigned long>::max()) throw Error(what + ": the JPEG is too large");
    int width = 0, height = 0, subsampling = 0, colorspace = 0;
    if (tjDecompressHeader3(decoder.handle, data, static_cast<unsigned long>(size), &width, &height, &subsampling,
                            &colorspace) != 0)
        throw Error(what + ": JPEG failed to decode (" + jpegError(decoder) + ")");
    if (width <= 0 || height <= 0) throw Error(what + ": the image has no pixels");
    return {uint32_t(width), uint32_t(height)};
}

int jpegPixelFormat(uint32_t channels) {
    switch (channels) {
        case 1: return TJPF_GRAY;
        case 3: return TJPF_RGB;
        default: return TJPF_RGBA;  // 0 and 4; 2 (gray + alpha) has no TurboJPEG format: RGBA too
    }
}

Image decodeJpeg(const uint8_t* data, size_t size, uint32_t channels, const std::string& what,
                 std::vector<std::string>* warnings) {
    JpegDecoder decoder;
    const ImageHeader header = jpegHeader(decoder, data, size, what);
    checkSize(header, what);
    const int format = jpegPixelFormat(channels);
    Image image(header.width, header.height, uint32_t(tjPixelSize[format]));
    // LIMITSCANS: refuse progressive JPEGs with absurd scan counts (a few bytes, minutes of decoding).
    const int flags = TJFLAG_LIMITSCANS;
    if (tjDecompress2(decoder.handle, data, static_cast<unsigned long>(size), image.pixels.data(), int(header.width), 0,
                      int(header.height), format, flags) != 0) {
        if (tjGetErrorCode(decoder.handle) != TJERR_WARNING)
            throw Error(what + ": JPEG failed to decode (" + jpegError(decoder) + ")");
        if (warnings) warnings->push_back(what + ": JPEG decoded with a warning (" + jpegError(decoder) + ")");
    }
    if (channels == 2) {  // RGBA -> gray + alpha (Rec. 601 luma)
        Image ga(header.width, header.height, 2);
        for (size_t i = 0; i < size_t(header.width) * header.height; ++i) {
            const uint8_t* p = &image.pixels[4 * i];
            ga.pixels[2 * i] = uint8_t((299u * p[0] + 587u * p[1] + 114u * p[2] + 500u) / 1000u);
            ga.pixels[2 * i + 1] = 255;
        }
        return ga;
    }
    return image;
}

}  // namespace

bool isPngData(const uint8_t* data, size_t size) {
    static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    return size >= 8 && std::memcmp(data, kSignature, 8) == 0;
}

bool isJpegData(const uint8_t* data, size_t size) { return size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF; }

ImageHeader readImageHeader(const uint8_t* data, size_t size, const std::string& what) {
    if (isPngData(data, size)) {
        PngImage png;
        beginPng(png, data, size, what);
        return {png.image.width, png.image.height};
    }
    if (isJpegData(data, size)) {
        JpegDecoder decoder;
        return jpegHeader(decoder, data, size, what);
    }
    throw Error(what + ": not a PNG or JPEG image");
}

Image decodePngOrJpeg(const uint8_t* data, size_t size, uint32_t channels, const std::string& what,
                      std::vector<std::string>* warnings) {
    if (channels > 4) throw Error("internal: decoding to " + std::to_string(channels) + " channels");
    if (isPngData(data, size)) return decodePng(data, size, channels, what, warnings);
    if (isJpegData(data, size)) return decodeJpeg(data, size, channels, what, warnings);
    throw Error(what + ": not a PNG or JPEG image");
}

}  // namespace penumbra
