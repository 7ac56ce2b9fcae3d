// shadows.raster = auto and render.mainView = auto (render/raster_choice.h): a device table decides on
// datacenter NVIDIA GPUs without measuring; elsewhere the first measured frames of each path decide.
#include <gtest/gtest.h>

#include <string>

#include "render/raster_choice.h"

namespace penumbra {
namespace {

constexpr int kPerPath = RasterChoice::kWarmup + RasterChoice::kSamples;

void measure(RasterChoice& choice, double hwMs, double computeMs) {
    for (int i = 0; i < kPerPath; ++i) choice.measured(false, hwMs);
    for (int i = 0; i < kPerPath; ++i) choice.measured(true, computeMs);
}

TEST(RasterChoice, ADatacenterGpuIsDecidedByTheTableWithoutMeasuringFrames) {
    for (const char* name : {"NVIDIA H100 80GB HBM3", "NVIDIA H200", "NVIDIA A100-SXM4-40GB", "NVIDIA GH200 480GB"}) {
        const RasterChoice choice(true, name);
        EXPECT_TRUE(choice.decided()) << name;
        EXPECT_TRUE(choice.useCompute(ShadowRaster::Auto)) << name;
        EXPECT_NE(std::string(choice.describe()).find("device table"), std::string::npos) << choice.describe();
    }
}

TEST(RasterChoice, TheTableDecisionIsNotChangedByLaterTimings) {
    RasterChoice choice(true, "NVIDIA H200");
    measure(choice, 0.1, 50.0);
    EXPECT_TRUE(choice.useCompute(ShadowRaster::Auto));
}

TEST(RasterChoice, AnotherGpuMeasuresTheHardwarePathFirstThenTheComputePath) {
    RasterChoice choice(true, "NVIDIA GeForce RTX 4090");
    EXPECT_FALSE(choice.decided());
    EXPECT_FALSE(choice.useCompute(ShadowRaster::Auto));
    for (int i = 0; i < kPerPath; ++i) choice.measured(false, 2.0);
    EXPECT_FALSE(choice.decided());
    EXPECT_TRUE(choice.useCompute(ShadowRaster::Auto));
    EXPECT_STREQ(choice.describe(), "measuring");
}

TEST(RasterChoice, AnotherGpuKeepsTheFasterMeasuredPath) {
    RasterChoice hwWins(true, "AMD Radeon RX 7900 XTX");
    measure(hwWins, 1.0, 3.0);
    EXPECT_TRUE(hwWins.decided());
    EXPECT_FALSE(hwWins.useCompute(ShadowRaster::Auto));
    RasterChoice computeWins(true, "AMD Radeon RX 7900 XTX");
    measure(computeWins, 3.0, 1.0);
    EXPECT_TRUE(computeWins.useCompute(ShadowRaster::Auto));
    EXPECT_NE(std::string(computeWins.describe()).find("measured"), std::string::npos) << computeWins.describe();
}

TEST(RasterChoice, AFrameOfTheOtherPhaseIsNotCountedAsASample) {
    RasterChoice choice(true, "llvmpipe (LLVM 15.0.6, 256 bits)");
    for (int i = 0; i < kPerPath; ++i) choice.measured(false, 1.0);
    choice.measured(false, 100.0);  // a hardware frame still in flight when the phase turned
    for (int i = 0; i < kPerPath; ++i) choice.measured(true, 2.0);
    EXPECT_FALSE(choice.useCompute(ShadowRaster::Auto));
}

TEST(RasterChoice, WithoutTimestampsAnotherGpuUsesTheHardwarePath) {
    const RasterChoice choice(false, "Intel(R) UHD Graphics 770");
    EXPECT_TRUE(choice.decided());
    EXPECT_FALSE(choice.useCompute(ShadowRaster::Auto));
}

TEST(RasterChoice, AnExplicitSettingOverridesTheChoice) {
    const RasterChoice choice(true, "NVIDIA H100 PCIe");
    EXPECT_FALSE(choice.useCompute(ShadowRaster::Hw));
    EXPECT_TRUE(choice.useCompute(ShadowRaster::Compute));
}

}  // namespace
}  // namespace penumbra
