#pragma once
// Comparison of a rendered `--aov shadow` image with the ray-traced reference (reference_tracer.h).
// Both images are classified per pixel as lit or shadowed by one threshold on value / 255; the
// metrics count the pixels where the classes disagree, over the reference's valid pixels only.
#include <cstdint>
#include <string>

#include "penumbra/image.h"

namespace penumbra {

struct CompareMetrics {
    uint64_t validPixels = 0;
    uint64_t falseShadow = 0;  // reference lit, ours shadowed
    uint64_t falseLit = 0;     // reference shadowed, ours lit
    // "Interior" pixels are valid pixels farther than kBoundaryRadius pixels (Chebyshev) from a
    // reference shadow boundary: errors there are not a matter of where exactly an edge falls.
    uint64_t interiorPixels = 0;
    uint64_t interiorFalseShadow = 0;
    uint64_t interiorFalseLit = 0;
    double falseShadowPercent = 0.0;            // of validPixels
    double falseLitPercent = 0.0;               // of validPixels
    double misclassifiedPercent = 0.0;          // (falseShadow + falseLit) / validPixels
    double interiorMisclassifiedPercent = 0.0;  // of interiorPixels
    double meanAbsoluteError = 0.0;             // mean |ours - reference| / 255 over valid pixels
    float threshold = 0.5f;                     // the classification threshold used
};

// A reference pixel is on a shadow boundary when its class differs from any pixel within this
// Chebyshev radius (valid or not).
constexpr int kBoundaryRadius = 2;

// Compares channel 0 of each image. A pixel is lit when value / 255 >= threshold (0.5: lit means
// >= 128). With shadow strength s the reference's shadowed value is 255 × (1 - s); pick a threshold
// between that and 1, e.g. 1 - s / 2, when s < 1. A pixel is valid where validMask != 0.
// Throws penumbra::Error when the sizes differ, an image is empty or threshold is outside (0, 1].
CompareMetrics compareShadowImages(const Image& ours, const Image& reference, const Image& validMask,
                                   float threshold = 0.5f);

// An RGB picture of the disagreements: false shadow in red, false lit in cyan, over `dimBase` (gray
// or RGB, e.g. the colour render; empty = use the reference) dimmed to 50% on valid pixels and 20%
// on excluded ones. Same size rules as compareShadowImages.
Image makeDiffImage(const Image& dimBase, const Image& ours, const Image& reference, const Image& validMask,
                    float threshold = 0.5f);

std::string toJson(const CompareMetrics& metrics);  // one JSON object, keys = the field names
std::string toText(const CompareMetrics& metrics);  // a small human-readable table

}  // namespace penumbra
