#include "penumbra/shadow_compare.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace penumbra {
namespace {

std::string sizeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

void checkSameSize(const Image& a, const char* aName, const Image& b, const char* bName) {
    if (a.empty() || b.empty())
        throw Error(std::string("compare: the ") + (a.empty() ? aName : bName) + " image is empty");
    if (a.width != b.width || a.height != b.height)
        throw Error(std::string("compare: the ") + aName + " image is " + sizeText(a) + " but the " + bName +
                    " image is " + sizeText(b));
}

void checkInputs(const Image& ours, const Image& reference, const Image& validMask, float threshold) {
    checkSameSize(ours, "rendered", reference, "reference");
    checkSameSize(validMask, "valid-mask", reference, "reference");
    if (!(threshold > 0.0f && threshold <= 1.0f))
        throw Error("compare: threshold " + std::to_string(threshold) + " is outside (0, 1]");
}

bool isLit(const Image& image, uint32_t x, uint32_t y, float threshold) {
    return float(image.at(x, y, 0)) >= threshold * 255.0f;
}

// Whether the reference class at (x, y) differs from any pixel within kBoundaryRadius.
bool nearBoundary(const Image& reference, uint32_t x, uint32_t y, float threshold) {
    const bool lit = isLit(reference, x, y, threshold);
    for (int dy = -kBoundaryRadius; dy <= kBoundaryRadius; ++dy) {
        for (int dx = -kBoundaryRadius; dx <= kBoundaryRadius; ++dx) {
            const int nx = int(x) + dx, ny = int(y) + dy;
            if (nx < 0 || ny < 0 || nx >= int(reference.width) || ny >= int(reference.height)) continue;
            if (isLit(reference, uint32_t(nx), uint32_t(ny), threshold) != lit) return true;
        }
    }
    return false;
}

// Whether a shadowed reference pixel has a lit 4-neighbour (in the image): one pixel per unit of edge
// length, counted on the shadowed side.
bool onShadowEdge(const Image& reference, uint32_t x, uint32_t y, float threshold) {
    const bool lit = isLit(reference, x, y, threshold);
    if (lit) return false;
    const int offsets[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : offsets) {
        const int nx = int(x) + d[0], ny = int(y) + d[1];
        if (nx < 0 || ny < 0 || nx >= int(reference.width) || ny >= int(reference.height)) continue;
        if (isLit(reference, uint32_t(nx), uint32_t(ny), threshold) != lit) return true;
    }
    return false;
}

double percent(uint64_t part, uint64_t whole) { return whole == 0 ? 0.0 : 100.0 * double(part) / double(whole); }

}  // namespace

CompareMetrics compareShadowImages(const Image& ours, const Image& reference, const Image& validMask,
                                   float threshold) {
    checkInputs(ours, reference, validMask, threshold);
    CompareMetrics m;
    m.threshold = threshold;
    double absoluteErrorSum = 0.0;
    for (uint32_t y = 0; y < reference.height; ++y) {
        for (uint32_t x = 0; x < reference.width; ++x) {
            if (validMask.at(x, y, 0) == 0) continue;
            ++m.validPixels;
            absoluteErrorSum += std::abs(int(ours.at(x, y, 0)) - int(reference.at(x, y, 0))) / 255.0;
            const bool referenceLit = isLit(reference, x, y, threshold);
            const bool oursLit = isLit(ours, x, y, threshold);
            const bool interior = !nearBoundary(reference, x, y, threshold);
            m.interiorPixels += interior ? 1 : 0;
            m.edgePixels += onShadowEdge(reference, x, y, threshold) ? 1 : 0;
            if (referenceLit && !oursLit) {
                ++m.falseShadow;
                m.interiorFalseShadow += interior ? 1 : 0;
            } else if (!referenceLit && oursLit) {
                ++m.falseLit;
                m.interiorFalseLit += interior ? 1 : 0;
            }
        }
    }
    m.falseShadowPercent = percent(m.falseShadow, m.validPixels);
    m.falseLitPercent = percent(m.falseLit, m.validPixels);
    m.misclassifiedPercent = percent(m.falseShadow + m.falseLit, m.validPixels);
    m.interiorMisclassifiedPercent = percent(m.interiorFalseShadow + m.interiorFalseLit, m.interiorPixels);
    m.meanAbsoluteError = m.validPixels == 0 ? 0.0 : absoluteErrorSum / double(m.validPixels);
    const uint64_t wrong = m.falseShadow + m.falseLit;
    m.edgeErrorPixels = m.edgePixels == 0 ? 0.0 : double(wrong) / double(m.edgePixels);
    m.edgeBalance = wrong == 0 ? 0.0 : (double(m.falseShadow) - double(m.falseLit)) / double(wrong);
    return m;
}

ShimmerMetrics compareShimmer(const Image& ours0, const Image& ours1, const Image& reference0,
                              const Image& reference1, const Image& validMask0, const Image& validMask1,
                              float threshold) {
    checkInputs(ours0, reference0, validMask0, threshold);
    checkInputs(ours1, reference1, validMask1, threshold);
    checkSameSize(reference1, "second reference", reference0, "reference");
    ShimmerMetrics s;
    for (uint32_t y = 0; y < reference0.height; ++y) {
        for (uint32_t x = 0; x < reference0.width; ++x) {
            if (validMask0.at(x, y, 0) == 0 || validMask1.at(x, y, 0) == 0) continue;
            ++s.pixels;
            const bool referenceFlips = isLit(reference0, x, y, threshold) != isLit(reference1, x, y, threshold);
            const bool oursFlips = isLit(ours0, x, y, threshold) != isLit(ours1, x, y, threshold);
            s.referenceFlips += referenceFlips ? 1 : 0;
            s.flickering += oursFlips && !referenceFlips ? 1 : 0;
            const bool interior = !nearBoundary(reference0, x, y, threshold) && !nearBoundary(reference1, x, y, threshold);
            s.interiorPixels += interior ? 1 : 0;
            s.interiorFlickering += interior && oursFlips && !referenceFlips ? 1 : 0;  // as flickering: ours only
        }
    }
    s.shimmerPercent = percent(s.flickering, s.pixels);
    s.interiorShimmerPercent = percent(s.interiorFlickering, s.interiorPixels);
    return s;
}

Image makeDiffImage(const Image& dimBase, const Image& ours, const Image& reference, const Image& validMask,
                    float threshold) {
    checkInputs(ours, reference, validMask, threshold);
    const Image& base = dimBase.empty() ? reference : dimBase;
    checkSameSize(base, "base", reference, "reference");
    Image diff(reference.width, reference.height, 3);
    for (uint32_t y = 0; y < reference.height; ++y) {
        for (uint32_t x = 0; x < reference.width; ++x) {
            const bool valid = validMask.at(x, y, 0) != 0;
            const bool referenceLit = isLit(reference, x, y, threshold);
            const bool oursLit = isLit(ours, x, y, threshold);
            if (valid && referenceLit && !oursLit) {
                diff.at(x, y, 0) = 255, diff.at(x, y, 1) = 0, diff.at(x, y, 2) = 0;  // false shadow: red
            } else if (valid && !referenceLit && oursLit) {
                diff.at(x, y, 0) = 0, diff.at(x, y, 1) = 255, diff.at(x, y, 2) = 255;  // false lit: cyan
            } else {
                const float dim = valid ? 0.5f : 0.2f;
                for (uint32_t c = 0; c < 3; ++c) {
                    const uint32_t sourceChannel = base.channels >= 3 ? c : 0;  // gray bases repeat
                    diff.at(x, y, c) = uint8_t(std::lround(dim * float(base.at(x, y, sourceChannel))));
                }
            }
        }
    }
    return diff;
}

namespace {

nlohmann::json metricsJson(const CompareMetrics& m) {
    return {
        {"validPixels", m.validPixels},
        {"falseShadow", m.falseShadow},
        {"falseLit", m.falseLit},
        {"interiorPixels", m.interiorPixels},
        {"interiorFalseShadow", m.interiorFalseShadow},
        {"interiorFalseLit", m.interiorFalseLit},
        {"falseShadowPercent", m.falseShadowPercent},
        {"falseLitPercent", m.falseLitPercent},
        {"misclassifiedPercent", m.misclassifiedPercent},
        {"interiorMisclassifiedPercent", m.interiorMisclassifiedPercent},
        {"meanAbsoluteError", m.meanAbsoluteError},
        {"edgePixels", m.edgePixels},
        {"edgeErrorPixels", m.edgeErrorPixels},
        {"edgeBalance", m.edgeBalance},
        {"threshold", m.threshold},
    };
}

}  // namespace

std::string toJson(const CompareMetrics& m) { return metricsJson(m).dump(2); }

std::string toJson(const CompareMetrics& m, const ShimmerMetrics& s) {
    nlohmann::json json = metricsJson(m);
    json["shimmerPixels"] = s.pixels;
    json["shimmerFlickering"] = s.flickering;
    json["shimmerReferenceFlips"] = s.referenceFlips;
    json["shimmerPercent"] = s.shimmerPercent;
    json["shimmerInteriorPixels"] = s.interiorPixels;
    json["shimmerInteriorFlickering"] = s.interiorFlickering;
    json["shimmerInteriorPercent"] = s.interiorShimmerPercent;
    return json.dump(2);
}

std::string toText(const ShimmerMetrics& s) {
    char buffer[256];
    std::snprintf(buffer, sizeof(buffer),
                  "shimmer pixels        %10llu\n"
                  "shimmer (ours flips)  %10llu  %7.3f %%  (reference flips: %llu, not counted)\n"
                  "interior shimmer      %10llu  %7.3f %%\n",
                  (unsigned long long)s.pixels, (unsigned long long)s.flickering, s.shimmerPercent,
                  (unsigned long long)s.referenceFlips, (unsigned long long)s.interiorFlickering,
                  s.interiorShimmerPercent);
    return buffer;
}

std::string toText(const CompareMetrics& m) {
    char buffer[1024];
    std::snprintf(buffer, sizeof(buffer),
                  "valid pixels          %10llu\n"
                  "false shadow          %10llu  %7.3f %%\n"
                  "false lit             %10llu  %7.3f %%\n"
                  "misclassified         %10llu  %7.3f %%\n"
                  "interior pixels       %10llu\n"
                  "interior misclassified%10llu  %7.3f %%  (%llu false shadow, %llu false lit)\n"
                  "mean absolute error   %10.5f\n"
                  "edge pixels           %10llu\n"
                  "edge error            %10.3f px (misclassified per reference edge pixel)\n"
                  "edge balance          %10.3f  (+1 all false shadow, -1 all false lit)\n"
                  "threshold             %10.3f\n",
                  (unsigned long long)m.validPixels, (unsigned long long)m.falseShadow, m.falseShadowPercent,
                  (unsigned long long)m.falseLit, m.falseLitPercent, (unsigned long long)(m.falseShadow + m.falseLit),
                  m.misclassifiedPercent, (unsigned long long)m.interiorPixels,
                  (unsigned long long)(m.interiorFalseShadow + m.interiorFalseLit), m.interiorMisclassifiedPercent,
                  (unsigned long long)m.interiorFalseShadow, (unsigned long long)m.interiorFalseLit,
                  m.meanAbsoluteError, (unsigned long long)m.edgePixels, m.edgeErrorPixels, m.edgeBalance,
                  double(m.threshold));
    return buffer;
}

}  // namespace penumbra
