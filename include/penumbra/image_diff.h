#pragma once
// Per-pixel difference of two images of the same size and channel count: the check that the GPU
// and lavapipe give the same picture (docs/cli.md: the images and their conventions).
#include <array>
#include <cstdint>
#include <string>

#include <penumbra/image.h>

namespace penumbra {

struct ImageDifference {
    uint32_t maxAbsDifference = 0;   // over all pixels and channels, in 8-bit levels
    double meanAbsDifference = 0.0;  // over all channel values
    uint64_t pixelCount = 0;
    uint64_t pixelsOver1 = 0;        // pixels with some channel differing by more than 1 level
    uint64_t pixelsOver8 = 0;        // ... by more than 8 levels
};

// Throws Error when sizes or channel counts differ.
ImageDifference diffImages(const Image& a, const Image& b);
std::string toJson(const ImageDifference& difference);

}  // namespace penumbra
