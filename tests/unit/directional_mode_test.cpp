// shadows.directional.mode = auto: virtual shadow maps on a GPU, cascades on a CPU device
// (render/frame_setup.h, resolveDirectionalShadowMode; the renderer resolves it in fitShadowSettings).
// The default stays cascades (docs/rendering.md, "Virtual shadow maps": why not yet virtual).
#include <gtest/gtest.h>

#include <vector>

#include "penumbra/settings.h"
#include "render/frame_setup.h"

namespace penumbra {
namespace {

TEST(DirectionalShadowMode, TheDefaultIsCascadesAndAutoHasItsName) {
    EXPECT_EQ(Settings{}.shadows.directional.mode, DirectionalShadowMode::Cascades);
    EXPECT_STREQ(directionalShadowModeName(DirectionalShadowMode::Auto), "auto");
}

TEST(DirectionalShadowMode, AutoIsVirtualOnAGpu) {
    EXPECT_EQ(resolveDirectionalShadowMode(DirectionalShadowMode::Auto, false), DirectionalShadowMode::Virtual);
}

TEST(DirectionalShadowMode, AutoIsCascadesOnACpuDevice) {
    EXPECT_EQ(resolveDirectionalShadowMode(DirectionalShadowMode::Auto, true), DirectionalShadowMode::Cascades);
}

TEST(DirectionalShadowMode, AnExplicitModeIsKeptOnEveryDevice) {
    for (const bool cpu : {false, true}) {
        EXPECT_EQ(resolveDirectionalShadowMode(DirectionalShadowMode::Cascades, cpu), DirectionalShadowMode::Cascades);
        EXPECT_EQ(resolveDirectionalShadowMode(DirectionalShadowMode::Virtual, cpu), DirectionalShadowMode::Virtual);
    }
}

TEST(DirectionalShadowMode, TheFittedSettingsCarryTheResolvedMode) {
    std::vector<std::string> warnings;
    ShadowSettings requested;
    requested.directional.mode = DirectionalShadowMode::Auto;
    EXPECT_EQ(fitShadowSettings(requested, 16384, false, warnings).directional.mode, DirectionalShadowMode::Virtual);
    EXPECT_EQ(fitShadowSettings(requested, 16384, true, warnings).directional.mode, DirectionalShadowMode::Cascades);
    EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace penumbra
