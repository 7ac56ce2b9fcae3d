// Seeing the virtual shadow maps: the per-level page counts of FrameStats::virtualMaps (the viewer's
// page view, --stats' virtualPages.perMap) and the cascades AOV, which shows the level each pixel
// samples. Lavapipe, 256x144, validation on (any message fails).
#include <algorithm>
#include <numeric>

#include "compare_test_support.h"
#include "scene_structs.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

Settings virtualSettings() {
    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.maxDistance = 150.0f;
    return settings;
}

RenderRequest request(OutputMode output) {
    RenderRequest r;
    r.width = kCompareWidth;
    r.height = kCompareHeight;
    r.output = output;
    return r;
}

uint32_t sum(const std::array<uint32_t, 16>& values) { return std::accumulate(values.begin(), values.end(), 0u); }

// The level a cascades-AOV pixel shows, -1 for none.
int levelOf(const Image& image, size_t pixel) { return aovCascadeIndexOf(image, pixel, 16); }

// The mean level over the valid pixels of rows [firstRow, lastRow).
double meanLevel(const Image& levels, const Image& valid, uint32_t firstRow, uint32_t lastRow) {
    double total = 0.0;
    size_t count = 0;
    for (uint32_t y = firstRow; y < lastRow; ++y)
        for (uint32_t x = 0; x < levels.width; ++x) {
            const size_t p = size_t(y) * levels.width + x;
            if (valid.pixels[p] == 0) continue;
            total += levelOf(levels, p);
            ++count;
        }
    return count > 0 ? total / double(count) : -1.0;
}

class VirtualPageViewTest : public CompareTest {};

}  // namespace

TEST_F(VirtualPageViewTest, EachMapsLevelCountsAddUpToItsPageCounts) {
    const Scene& scene = canonicalScene("far_field");
    Renderer renderer(device(), scene);
    const RenderResult first = renderer.render(request(OutputMode::ShadowAov), virtualSettings());
    const RenderResult still = renderer.render(request(OutputMode::ShadowAov), virtualSettings());
    for (const RenderResult* result : {&first, &still}) {
        const FrameStats& stats = result->stats;
        ASSERT_EQ(stats.virtualPages.maps, 1u);
        const FrameStats::VirtualMapLevels& levels = stats.virtualMaps[0];
        EXPECT_EQ(levels.levelCount, virtualSettings().shadows.virtualMaps.levelCount);
        EXPECT_EQ(sum(levels.requested), stats.virtualPages.requested);
        EXPECT_EQ(sum(levels.cached), stats.virtualPages.cached);
        EXPECT_EQ(sum(levels.drawn), stats.virtualPages.drawn);
        EXPECT_GE(std::count_if(levels.requested.begin(), levels.requested.end(), [](uint32_t n) { return n > 0; }), 3)
            << "a far-field view spans several levels";
    }
    EXPECT_EQ(sum(still.stats.virtualMaps[0].drawn), 0u);
    EXPECT_EQ(still.stats.virtualMaps[0].cached, still.stats.virtualMaps[0].requested) << "every page kept";
    EXPECT_EQ(still.stats.virtualMaps[1].levelCount, 0u) << "one directional light, one map";
}

TEST_F(VirtualPageViewTest, TheCascadesAovShowsTheLevelEachPixelSamplesCoarserWithDistance) {
    const Scene& scene = canonicalScene("far_field");
    const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
    Renderer renderer(device(), scene);
    const Image levels = renderer.render(request(OutputMode::CascadesAov), virtualSettings(), view).image;
    const ReferenceImages& reference = cachedReference("far_field", 0, virtualSettings());
    ASSERT_EQ(levels.channels, 3u);
    // Every receiving pixel within the shadow distance samples a level (no black, no colour between).
    size_t valid = 0, unserved = 0, offPalette = 0;
    for (size_t p = 0; p < size_t(levels.width) * levels.height; ++p) {
        if (reference.validMask.pixels[p] == 0) continue;
        ++valid;
        const int level = levelOf(levels, p);
        unserved += level < 0;
        const glm::vec3 c = glm::vec3(levels.pixels[p * 3], levels.pixels[p * 3 + 1], levels.pixels[p * 3 + 2]) / 255.0f;
        offPalette += glm::distance(c, gpu_data::aovCascadeColor(level)) > 0.01f;
    }
    EXPECT_LT(double(unserved), 0.01 * double(valid));
    EXPECT_EQ(offPalette, 0u);
    // The ground recedes up the image (the sky above it): its far rows need coarser texels than its
    // near rows.
    uint32_t top = 0;
    while (top < levels.height && meanLevel(levels, reference.validMask, top, top + 1) < 0.0) ++top;
    const uint32_t third = (levels.height - top) / 3;
    const double far = meanLevel(levels, reference.validMask, top, top + third);
    const double near = meanLevel(levels, reference.validMask, levels.height - third, levels.height);
    EXPECT_GT(far, near + 1.5) << "far rows " << far << ", near rows " << near;
}
