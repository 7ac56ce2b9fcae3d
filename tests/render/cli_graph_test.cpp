// `penumbra graph`: the frame graph of a real frame of the demo scene, as Mermaid or Graphviz dot.
#include <gtest/gtest.h>

#include "cli_process.h"

using namespace penumbra::test;

namespace {

const std::string kSmall = " --width 64 --height 36 --device cpu --validation --set shadows.directional.atlasSize=256";

TEST(CliGraph, PrintsTheDemoFramesPassesAndTheirDependenciesAsMermaid) {
    const CliRun run = runPenumbra("graph" + kSmall);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out.rfind("flowchart TD\n", 0), 0u) << run.out;
    EXPECT_NE(run.out.find("[\"shadows.culling"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("[\"shadows.directional"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("[\"main ("), std::string::npos) << run.out;  // with its barriers
    EXPECT_NE(run.out.find("-->|\"directional atlas\"|"), std::string::npos) << run.out;
}

TEST(CliGraph, ASecondFrameOfCachedTilesDrawsNoShadowAtlas) {
    const CliRun run = runPenumbra("graph --frames 2 --raster hw" + kSmall);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out.find("[\"shadows.directional"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("[\"main"), std::string::npos) << run.out;
}

TEST(CliGraph, PrintsGraphvizDotOnRequest) {
    const CliRun run = runPenumbra("graph --format dot" + kSmall);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out.rfind("digraph frame {\n", 0), 0u) << run.out;
    EXPECT_NE(run.out.find(" -> "), std::string::npos) << run.out;
}

TEST(CliGraph, AnUnknownFormatIsAOneLineError) {
    const CliRun run = runPenumbra("graph --format svg" + kSmall);
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_TRUE(isOneLineError(run.err)) << run.err;
}

}  // namespace
