// The lit shading of spot and point lights (shaders/shade_surface.glsl shadeLight): a light's shadow
// darkens the colour image whichever light the AOVs follow, and the lookup a light skips where it adds
// nothing (outside its cone, behind the surface) changes no pixel. Measured on the colour image: the
// pixels under a box lit by a shadowed spot light, against the same frame with that light unshadowed.
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "render_test_support.h"

namespace penumbra::test {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 64;

// A ground plane, a box on it, a dim sun (light 0: the AOV light) and a shadowed spot light (light 1)
// beside and above the box, casting its shadow across the ground towards +x, its cone narrower than its
// range sphere; the spot's shadow mode as given.
Scene boxUnderSpot(LightShadows spotShadows) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    const uint32_t material = builder.addMaterial(white);
    builder.addInstance(builder.addMesh(makePlaneMesh({12.0f, 12.0f}, material)), glm::mat4(1.0f));
    builder.addInstance(builder.addMesh(makeBoxMesh(glm::vec3(0.5f), material)),
                        glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}));
    builder.addLight(makeDirectionalLight({0.3f, -1.0f, 0.2f}, 0.05f));
    Light spot = makeSpotLight({-3.0f, 3.0f, 0.0f}, {0.9f, -1.0f, 0.0f}, 200.0f, 12.0f, 0.7f, 0.55f);
    spot.shadows = spotShadows;
    builder.addLight(spot);
    builder.setCamera(makeLookAtCamera({0.0f, 6.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
    return builder.build();
}

// The share of pixels where `a` is brighter than `b` by more than `levels` in some channel.
double shareBrighter(const Image& a, const Image& b, int levels) {
    size_t brighter = 0;
    for (size_t p = 0; p + a.channels <= std::min(a.pixels.size(), b.pixels.size()); p += a.channels) {
        bool any = false;
        for (uint32_t c = 0; c < 3; ++c) any |= int(a.pixels[p + c]) - int(b.pixels[p + c]) > levels;
        brighter += any;
    }
    return double(brighter) / double(std::max<size_t>(a.pixels.size() / a.channels, 1));
}

double meanLuma(const Image& image) {
    double sum = 0.0;
    for (size_t p = 0; p + 2 < image.pixels.size(); p += image.channels) sum += image.pixels[p] + image.pixels[p + 1] + image.pixels[p + 2];
    return sum / double(image.pixels.size() / image.channels) / 3.0;
}

class ShadeLightTest : public RenderTest {};

// Spot shadows in both modes (atlas, virtual faces): the shadowed frame is darker, by the box's shadow
// on the ground (2.5 % of the pixels darker by more than 16 levels here), and nowhere brighter.
TEST_F(ShadeLightTest, ASpotLightsShadowDarkensTheColourImageWhenTheAovsFollowAnotherLight) {
    for (SpotShadowMode mode : {SpotShadowMode::Atlas, SpotShadowMode::Virtual}) {
        Settings settings;
        settings.shadows.spot.mode = mode;
        settings.shadows.raster = ShadowRaster::Compute;
        RenderRequest request;
        request.width = kWidth;
        request.height = kHeight;
        request.aovLight = 0;  // the sun
        Renderer shadowed(device(), boxUnderSpot(LightShadows::Hard));
        Renderer unshadowed(device(), boxUnderSpot(LightShadows::None));
        const Image with = shadowed.render(request, settings).image;
        const Image without = unshadowed.render(request, settings).image;
        const char* name = mode == SpotShadowMode::Virtual ? "virtual" : "atlas";
        const double darker = shareOfPixelsOver(with, without, 16);
        std::printf("%s: %.1f %% of the pixels differ, mean %.1f against %.1f\n", name, 100.0 * darker, meanLuma(with),
                    meanLuma(without));
        EXPECT_GT(darker, 0.015) << name;
        EXPECT_EQ(shareBrighter(with, without, 16), 0.0) << name;
        EXPECT_LT(meanLuma(with), meanLuma(without) - 1.0) << name;
    }
}

}  // namespace
}  // namespace penumbra::test
