#pragma once
// Comparison of a rendered `--aov shadow` image with the ray-traced reference (<penumbra/reference.h>).
// Both images are classified per pixel as lit or shadowed by one threshold on value / 255; the
// metrics count the pixels where the classes disagree, over the reference's valid pixels only.
#include <cstdint>
#include <string>

#include <penumbra/image.h>

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
    // Edge placement. edgePixels = valid shadowed reference pixels with a lit 4-neighbour: the length of
    // the true shadow edges in pixels. edgeErrorPixels = (falseShadow + falseLit) / edgePixels: the mean width, in pixels,
    // of the error band along the true edges; a shadow displaced by d pixels raises it by about d.
    // edgeBalance = (falseShadow - falseLit) / (falseShadow + falseLit) in [-1, 1]: > 0 shadows too
    // large (acne, blur), < 0 too small (leaks, peter-panning, over-bias); 0 when nothing is wrong.
    uint64_t edgePixels = 0;
    double edgeErrorPixels = 0.0;
    double edgeBalance = 0.0;
    float threshold = 0.5f;  // the classification threshold used
};

// Temporal stability between two frames whose cameras differ by a small step (penumbra compare
// --shimmer): over the pixels valid in both reference masks, the % whose class flips in ours while the
// reference's does not (only the shadow map moved, not the truth).
struct ShimmerMetrics {
    uint64_t pixels = 0;         // valid in both frames
    uint64_t flickering = 0;     // ours flips, the reference does not
    uint64_t referenceFlips = 0; // the reference flips (the truth moved): not counted
    double shimmerPercent = 0.0; // flickering / pixels
    // The same away from shadow edges: pixels farther than kBoundaryRadius from a reference boundary in
    // both frames. Edge pixels flip where our edge and the truth's differ by a fraction of the step;
    // interior flips mean the shadow map itself changed (unstable cascades, depth ties).
    uint64_t interiorPixels = 0;
    uint64_t interiorFlickering = 0;
    double interiorShimmerPercent = 0.0;
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
ShimmerMetrics compareShimmer(const Image& ours0, const Image& ours1, const Image& reference0,
                              const Image& reference1, const Image& validMask0, const Image& validMask1,
                              float threshold = 0.5f);

Image makeDiffImage(const Image& dimBase, const Image& ours, const Image& reference, const Image& validMask,
                    float threshold = 0.5f);

std::string toJson(const CompareMetrics& metrics);  // one JSON object, keys = the field names
std::string toText(const CompareMetrics& metrics);  // a small human-readable table
// The same with the shimmer keys (shimmerPixels, shimmerFlickering, shimmerReferenceFlips, shimmerPercent).
std::string toJson(const CompareMetrics& metrics, const ShimmerMetrics& shimmer);
std::string toText(const ShimmerMetrics& shimmer);

}  // namespace penumbra
