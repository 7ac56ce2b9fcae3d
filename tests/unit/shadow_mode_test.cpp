// shadows.directional.mode = auto and shadows.spot.mode = auto: virtual shadow maps on a GPU, cascades and
// the spot atlas on a CPU device (render/frame_setup.h, resolveDirectionalShadowMode and
// resolveSpotShadowMode; the renderer resolves both in fitShadowSettings).
#include <gtest/gtest.h>

#include <vector>

#include "penumbra/settings.h"
#include "render/frame_setup.h"

namespace penumbra {
namespace {

TEST(DirectionalShadowMode, TheDefaultIsAutoAndAutoHasItsName) {
    EXPECT_EQ(Settings{}.shadows.directional.mode, DirectionalShadowMode::Auto);
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

TEST(SpotShadowMode, TheDefaultIsAutoAndAutoHasItsName) {
    EXPECT_EQ(Settings{}.shadows.spot.mode, SpotShadowMode::Auto);
    EXPECT_STREQ(spotShadowModeName(SpotShadowMode::Auto), "auto");
}

TEST(SpotShadowMode, AutoIsVirtualOnAGpu) {
    EXPECT_EQ(resolveSpotShadowMode(SpotShadowMode::Auto, false), SpotShadowMode::Virtual);
}

TEST(SpotShadowMode, AutoIsTheAtlasOnACpuDevice) {
    EXPECT_EQ(resolveSpotShadowMode(SpotShadowMode::Auto, true), SpotShadowMode::Atlas);
}

TEST(SpotShadowMode, AnExplicitModeIsKeptOnEveryDevice) {
    for (const bool cpu : {false, true}) {
        EXPECT_EQ(resolveSpotShadowMode(SpotShadowMode::Atlas, cpu), SpotShadowMode::Atlas);
        EXPECT_EQ(resolveSpotShadowMode(SpotShadowMode::Virtual, cpu), SpotShadowMode::Virtual);
    }
}

TEST(SpotShadowMode, TheFittedSettingsCarryTheResolvedMode) {
    std::vector<std::string> warnings;
    ShadowSettings requested;
    requested.spot.mode = SpotShadowMode::Auto;
    EXPECT_EQ(fitShadowSettings(requested, 16384, false, warnings).spot.mode, SpotShadowMode::Virtual);
    EXPECT_EQ(fitShadowSettings(requested, 16384, true, warnings).spot.mode, SpotShadowMode::Atlas);
    EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace penumbra
