#pragma once
// Shared fixture of the GPU tests: one lavapipe device with validation on for the whole test
// program; every test fails if any validation message appeared while it ran.
#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/device.h"
#include "penumbra/renderer.h"

namespace penumbra::test {

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

// sRGB 8-bit → linear [0,1].
inline float srgbToLinear(uint8_t value) {
    const float c = float(value) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace penumbra::test
