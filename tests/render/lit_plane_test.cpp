// The lit pass against analytic expectations: Lambert N.L, the ambient sky light, culling, background,
// tone mapping.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "sky_light.glsl"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A 20 x 20 m white, fully rough dielectric plane at y = 0 facing +Y, seen from straight above.
Scene planeUnderSun(glm::vec3 wsSunDirection, float intensity, bool unlit = false) {
    Scene scene;
    Mesh plane;
    plane.vertices = {{{-10, 0, -10}, {0, 1, 0}, {0, 0}}, {{10, 0, -10}, {0, 1, 0}, {1, 0}},
                      {{10, 0, 10}, {0, 1, 0}, {1, 1}}, {{-10, 0, 10}, {0, 1, 0}, {0, 1}}};
    plane.indices = {0, 2, 1, 0, 3, 2};  // CCW seen from +Y
    plane.osBounds.extend({-10, 0, -10});
    plane.osBounds.extend({10, 0, 10});
    scene.meshes.push_back(plane);
    Material white;
    white.metallic = 0.0f;
    white.roughness = 1.0f;
    white.unlit = unlit;
    white.baseColorFactor = glm::vec4(unlit ? 0.5f : 1.0f);
    scene.materials.push_back(white);
    Instance instance;
    instance.wsBounds = plane.osBounds;
    scene.instances.push_back(instance);
    Light sun;
    sun.type = LightType::Directional;
    sun.wsDirection = glm::normalize(wsSunDirection);
    sun.intensity = intensity;
    sun.shadows = LightShadows::None;
    scene.lights.push_back(sun);
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(glm::vec3(0, 10, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1)));
    camera.yfov = glm::radians(40.0f);
    scene.camera = camera;
    scene.wsBounds = plane.osBounds;
    return scene;
}

// No ambient, and the linear output these analytic values are stated in: no tone mapping (the default
// Khronos PBR Neutral would take 0.04 off mid tones) and a black background (the culling tests read
// black where no surface is drawn).
Settings noAmbient() {
    Settings settings;
    settings.render.ambient = 0.0f;
    settings.render.toneMapping = ToneMapping::None;
    settings.render.background = Background::Black;
    return settings;
}

uint8_t srgbByte(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(255.0f * encoded));
}

float centreLinear(const Image& image) { return srgbToLinear(image.at(image.width / 2, image.height / 2, 0)); }

}  // namespace

TEST_F(RenderTest, LitPlaneBrightnessFollowsLambertCosine) {
    // Diffuse radiance = albedo / pi * E * N.L; with E = pi lux it is N.L (minus the small Fresnel
    // share taken by the GGX lobe, which at roughness 1 stays under 6 %).
    for (float degrees : {0.0f, 45.0f, 60.0f}) {
        const float radians = glm::radians(degrees);
        const glm::vec3 direction(std::sin(radians), -std::cos(radians), 0.0f);
        const RenderResult result = renderScene(planeUnderSun(direction, float(M_PI)), {64, 64}, noAmbient());
        EXPECT_NEAR(centreLinear(result.image), std::cos(radians), 0.06f) << "sun at " << degrees << " degrees";
    }
}

TEST_F(RenderTest, SurfaceFacingAwayFromTheSunIsBlack) {
    const RenderResult result = renderScene(planeUnderSun({0, 1, 0}, float(M_PI)), {32, 32}, noAmbient());
    EXPECT_EQ(result.image.at(16, 16, 0), 0);
}

namespace {

// The linear output of noAmbient() with render.ambient at its default.
Settings defaultAmbient() {
    Settings settings = noAmbient();
    settings.render.ambient = Settings{}.render.ambient;
    return settings;
}

// The centre pixel's three sRGB bytes against `linear` (white albedo), within one level each: the
// 8-bit rounding of the output plus lavapipe's float arithmetic.
void expectCentreColour(const Image& image, glm::vec3 linear, const std::string& what) {
    for (uint32_t c = 0; c < 3; ++c)
        EXPECT_NEAR(int(image.at(image.width / 2, image.height / 2, c)), int(srgbByte(linear[c])), 1)
            << what << ", channel " << c;
}

}  // namespace

TEST_F(RenderTest, SurfaceFacingAwayFromTheSunShowsTheSkyLight) {
    // An upward plane lit from below, and a double-sided plane seen from below while the sun is
    // above (its shading normal turns to the viewer: straight down): the sun adds nothing to either,
    // the ambient term is render.ambient x the gradient's irradiance (sky_light.glsl) x albedo 1, in
    // both main views, which share shade_surface.glsl.
    const float ambient = Settings{}.render.ambient;
    ASSERT_GT(ambient, 0.0f);
    Scene below = planeUnderSun({0, -1, 0}, float(M_PI));
    below.materials[0].doubleSided = true;
    below.camera->worldFromView = glm::inverse(glm::lookAt(glm::vec3(0, -10, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1)));
    for (MainView mainView : {MainView::Forward, MainView::Visibility}) {
        Settings settings = defaultAmbient();
        settings.render.mainView = mainView;
        const std::string view = mainViewName(mainView);
        const RenderResult up = renderScene(planeUnderSun({0, 1, 0}, float(M_PI)), {32, 32}, settings);
        expectCentreColour(up.image, ambient * gpu_data::look::skyIrradiance({0, 1, 0}), view + ", facing up");
        const RenderResult down = renderScene(below, {32, 32}, settings);
        expectCentreColour(down.image, ambient * gpu_data::look::skyIrradiance({0, -1, 0}), view + ", facing down");
    }
}

TEST_F(RenderTest, AmbientChangesTheColourOnlyNeverTheShadowOrCascadesAov) {
    // The demo scene with the ambient off and at its default: the colour differs, the AOVs are the
    // same to the bit, in both main views.
    Renderer renderer(device(), makeDemoScene());
    Settings off;
    off.render.ambient = 0.0f;
    for (MainView mainView : {MainView::Forward, MainView::Visibility}) {
        Settings on;
        on.render.mainView = off.render.mainView = mainView;
        for (OutputMode output : {OutputMode::Color, OutputMode::ShadowAov, OutputMode::CascadesAov}) {
            const RenderRequest request{96, 64, output, 0, false};
            const Image withAmbient = renderer.render(request, on).image;
            const Image without = renderer.render(request, off).image;
            ASSERT_EQ(withAmbient.pixels.size(), without.pixels.size());
            if (output == OutputMode::Color)
                EXPECT_GT(shareOfPixelsOver(withAmbient, without, 8), 0.3) << mainViewName(mainView);
            else
                EXPECT_TRUE(withAmbient.pixels == without.pixels) << mainViewName(mainView) << ", AOV " << int(output);
        }
    }
}

TEST_F(RenderTest, UnlitMaterialShowsItsBaseColourWhateverTheLight) {
    const RenderResult result = renderScene(planeUnderSun({0, 1, 0}, 100.0f, true), {32, 32}, noAmbient());
    EXPECT_NEAR(centreLinear(result.image), 0.5f, 0.01f);
}

TEST_F(RenderTest, BackFacesOfSingleSidedMaterialsAreCulled) {
    Scene scene = planeUnderSun({0, -1, 0}, float(M_PI));
    scene.camera->worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0, -10, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1)));
    const RenderResult result = renderScene(scene, {32, 32}, noAmbient());
    EXPECT_EQ(result.image.at(16, 16, 0), 0);
    scene.materials[0].doubleSided = true;
    scene.materials[0].unlit = true;
    const RenderResult doubleSided = renderScene(scene, {32, 32}, noAmbient());
    EXPECT_GT(doubleSided.image.at(16, 16, 0), 200);
}

TEST_F(RenderTest, ShadowAovIsWhereNoShadowIsCast) {
    RenderRequest request{32, 32, OutputMode::ShadowAov, 0, false};
    const RenderResult result = renderScene(planeUnderSun({0, -1, 0}, 1.0f), request);
    ASSERT_EQ(result.image.channels, 1u);
    for (uint8_t v : result.image.pixels) ASSERT_EQ(v, 255);
}

TEST_F(RenderTest, ToneMappingOnTheGpuIsTheCurveOfToneMappingGlsl) {
    // Unlit grey 0.5 at exposure 1 and 2: mid tones, and a highlight past Neutral's compression start.
    for (float exposure : {1.0f, 2.0f}) {
        for (ToneMapping mode : {ToneMapping::None, ToneMapping::Neutral, ToneMapping::Aces}) {
            Settings settings = noAmbient();
            settings.render.exposure = exposure;
            settings.render.toneMapping = mode;
            const RenderResult result = renderScene(planeUnderSun({0, 1, 0}, 1.0f, true), {32, 32}, settings);
            const float expected = gpu_data::look::toneMap(glm::vec3(0.5f * exposure), uint32_t(mode)).r;
            EXPECT_NEAR(int(result.image.at(16, 16, 0)), int(srgbByte(expected)), 1)
                << toneMappingName(mode) << " at exposure " << exposure;
        }
    }
    // The curves differ by more than the tolerance at both points, so the loop above tells them apart.
    for (float x : {0.5f, 1.0f}) {
        const int none = srgbByte(x), neutral = srgbByte(gpu_data::look::toneMapNeutral(glm::vec3(x)).r),
                  aces = srgbByte(gpu_data::look::toneMapAces(glm::vec3(x)).r);
        EXPECT_GT(std::abs(none - neutral), 3);
        EXPECT_GT(std::abs(none - aces), 3);
        EXPECT_GT(std::abs(neutral - aces), 3);
    }
}
