#include "penumbra/image_diff.h"

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace penumbra {

ImageDifference diffImages(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw Error("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + "x" +
                    std::to_string(a.channels) + " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                    "x" + std::to_string(b.channels));
    ImageDifference d;
    d.pixelCount = uint64_t(a.width) * a.height;
    uint64_t sum = 0;
    for (uint64_t p = 0; p < d.pixelCount; ++p) {
        uint32_t pixelMax = 0;
        for (uint32_t c = 0; c < a.channels; ++c) {
            const uint32_t delta = uint32_t(std::abs(int(a.pixels[p * a.channels + c]) - int(b.pixels[p * a.channels + c])));
            sum += delta;
            pixelMax = std::max(pixelMax, delta);
        }
        d.maxAbsDifference = std::max(d.maxAbsDifference, pixelMax);
        d.pixelsOver1 += pixelMax > 1;
        d.pixelsOver8 += pixelMax > 8;
    }
    d.meanAbsDifference = d.pixelCount ? double(sum) / double(d.pixelCount * a.channels) : 0.0;
    return d;
}

std::string toJson(const ImageDifference& d) {
    return nlohmann::json{{"maxAbsDifference", d.maxAbsDifference}, {"meanAbsDifference", d.meanAbsDifference},
                          {"pixels", d.pixelCount}, {"pixelsOver1", d.pixelsOver1}, {"pixelsOver8", d.pixelsOver8}}
        .dump();
}

}  // namespace penumbra
