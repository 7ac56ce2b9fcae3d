#pragma once
// Shared fixture of the GPU tests: one lavapipe device with validation on for the whole test
// program; every test fails if any validation message appeared while it ran.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "gpu/device_access.h"
#include "penumbra/device.h"
#include "penumbra/renderer.h"
#include "penumbra/scene_builder.h"
#include "scene/generated_scenes.h"
#include "scene_structs.h"

namespace penumbra::test {

// A box on a ground under a sun and a shadowed spot: both atlases (or both kinds of virtual map) and
// every pass of a frame are used.
inline Scene sunAndSpotBoxScene() {
    SceneBuilder builder;
    const uint32_t ground = builder.addMesh(makePlaneMesh(glm::vec2(20.0f), 0));
    builder.addInstance(ground, glm::mat4(1.0f));
    const uint32_t box = builder.addMesh(makeBoxMesh(glm::vec3(0.5f), 0));
    glm::mat4 boxFromWorld(1.0f);
    boxFromWorld[3] = glm::vec4(0.0f, 0.5f, 0.0f, 1.0f);
    builder.addInstance(box, boxFromWorld);
    builder.addLight(makeDirectionalLight({0.3f, -1.0f, -0.2f}, 3.0f));
    builder.addLight(makeSpotLight({0.0f, 4.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 30.0f, 10.0f, 0.6f, 0.5f));
    builder.setCamera(makeLookAtCamera({0.0f, 4.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
    return builder.build();
}

// A colour image of width x height.
inline RenderRequest colourRequest(uint32_t width, uint32_t height) {
    RenderRequest request;
    request.width = width;
    request.height = height;
    return request;
}

// The options of the shared device: lavapipe (or PENUMBRA_DEVICE), validation on.
inline DeviceOptions testDeviceOptions() {
    DeviceOptions options;
    const char* choice = std::getenv("PENUMBRA_DEVICE");
    options.device = choice ? choice : "cpu";
    options.validation = true;
    return options;
}

inline Device& sharedDevice() {
    static std::unique_ptr<Device> device = std::make_unique<Device>(testDeviceOptions());
    return *device;
}

class RenderTest : public ::testing::Test {
protected:
    void SetUp() override { messagesBefore_ = sharedDevice().validationMessageCount(); }
    void TearDown() override {
        EXPECT_EQ(sharedDevice().validationMessageCount(), messagesBefore_) << "Vulkan validation messages appeared";
    }
    Device& device() { return sharedDevice(); }

    RenderResult renderScene(const Scene& scene, const RenderRequest& request, const Settings& settings = {}) {
        Renderer renderer(device(), scene);
        return renderer.render(request, settings);
    }

private:
    uint32_t messagesBefore_ = 0;
};

// The culling lists per storage buffer on a device made to hold only that many (the 64-byte instance
// records still fit one), and a scene whose 18 shadow tiles then lie in two buffers: gen:boxes's boxes
// (turned, of non-uniform heights) under its sun (4 cascades), two shadowed point lights (12 faces) and
// two shadowed spot lights, all 4 m or more above the boxes.
constexpr uint64_t kSplitListsPerBuffer = 16;
constexpr uint32_t kSplitListBoxes = 400;
constexpr size_t kSplitListTiles = 18;
inline Scene boxesWithEighteenShadowTiles(uint32_t boxes) {
    Scene scene = makeBoxesScene(boxes);
    for (float x : {-3.0f, 3.0f}) {
        scene.lights.push_back(makePointLight({x, 6.0f, 1.0f}, 20.0f, 10.0f));
        scene.lights.push_back(makeSpotLight({x, 6.0f, -2.0f}, {0.1f, -1.0f, 0.05f}, 30.0f, 20.0f, 0.8f, 0.6f));
    }
    return scene;
}

// The share of pixels of two same-sized images where some channel differs by more than `levels`.
inline double shareOfPixelsOver(const Image& a, const Image& b, int levels) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    size_t over = 0;
    for (size_t p = 0; p + a.channels <= std::min(a.pixels.size(), b.pixels.size()); p += a.channels) {
        bool differs = false;
        for (uint32_t c = 0; c < a.channels; ++c) differs |= std::abs(int(a.pixels[p + c]) - int(b.pixels[p + c])) > levels;
        over += differs;
    }
    return double(over) / double(std::max<size_t>(a.pixels.size() / a.channels, 1));
}

// The cascade (or virtual shadow map level) a pixel of an RGB cascades AOV shows: the nearest of
// gpu_data::aovCascadeColor's colours for -1 (none) to count - 1.
inline int aovCascadeIndexOf(const Image& image, size_t pixel, int count) {
    const glm::vec3 c = glm::vec3(image.pixels[pixel * 3], image.pixels[pixel * 3 + 1], image.pixels[pixel * 3 + 2]) / 255.0f;
    int best = -1;
    for (int i = 0; i < count; ++i)
        if (glm::distance(c, gpu_data::aovCascadeColor(i)) < glm::distance(c, gpu_data::aovCascadeColor(best))) best = i;
    return best;
}

// sRGB 8-bit → linear [0,1].
inline float srgbToLinear(uint8_t value) {
    const float c = float(value) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Whether one of a frame's warnings contains `text`.
inline bool hasWarning(const FrameStats& stats, const std::string& text) {
    for (const std::string& warning : stats.warnings)
        if (warning.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace penumbra::test
