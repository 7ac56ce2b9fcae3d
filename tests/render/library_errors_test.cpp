// The library's errors speak of what the caller passed (a light index, DeviceOptions::device), not
// of the CLI's flags: the programs name their own flags (cli_render_test.cpp checks the CLI's).
#include <string>

#include <gtest/gtest.h>

#include "penumbra/error.h"
#include "penumbra/scene_loading.h"
#include "render_test_support.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

// The message `make` throws as penumbra::Error ("" when it throws nothing).
template <typename Make>
std::string errorOf(Make make) {
    try {
        make();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_F(RenderTest, AovOfAMissingLightNamesTheLightIndex) {
    Renderer renderer(sharedDevice(), loadScene(""));
    RenderRequest request;
    request.width = 32;
    request.height = 24;
    request.output = OutputMode::ShadowAov;
    request.aovLight = 42;
    const std::string message = errorOf([&] { renderer.render(request, {}); });
    EXPECT_EQ(message.rfind("light 42 does not exist (the scene has ", 0), 0u) << message;
}

TEST(LibraryErrors, UnknownDeviceKindNamesTheAllowedKinds) {
    DeviceOptions options = testDeviceOptions();
    options.device = "fastest";
    EXPECT_EQ(errorOf([&] { Device device(options); }),
              "device kind must be auto, gpu, cpu or a device index, not 'fastest'");
}

TEST(LibraryErrors, DeviceIndexOutOfRangeNamesTheIndex) {
    DeviceOptions options = testDeviceOptions();
    options.device = "99";
    const std::string message = errorOf([&] { Device device(options); });
    EXPECT_EQ(message.rfind("no Vulkan device: device index 99 is out of range (", 0), 0u) << message;
}
