// --ground as a user runs it: a lone model (Debian's 2CylinderEngine, no lights, no camera) gets a
// plane under it that receives its shadow, in our shadow AOV and in the ray-traced reference alike;
// without --ground the same pixels show the background.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_process.h"
#include "penumbra/image.h"
#include "penumbra/scene_loading.h"

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// `penumbra COMMAND` of the engine at 160 x 90 with `options`, its output PNG as one channel.
Image runOnEngine(const std::string& command, const std::string& name, const std::string& options) {
    const fs::path out = processTempPath("penumbra_cli_ground", name);
    fs::remove(out);
    const CliRun run = runPenumbra(command + " " + kDefaultFieldModel + " --device cpu --validation --width 160 --height 90 -o " +
                                   out.string() + " " + options);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    return fs::exists(out) ? readPng(out.string(), 1) : Image{};
}

// The engine's cascades AOV without and with --ground (the same camera frames the engine both
// times), and the plane: the pixels that are background (black) without and surface (a cascade's
// colour) with it.
struct PlaneView {
    Image without = runOnEngine("render", "cascades.png", "--aov cascades");
    Image with = runOnEngine("render", "ground_cascades.png", "--aov cascades --ground");
    std::vector<size_t> plane;

    PlaneView() {
        EXPECT_FALSE(without.empty());
        EXPECT_EQ(with.pixels.size(), without.pixels.size());
        for (size_t i = 0; i < std::min(with.pixels.size(), without.pixels.size()); ++i)
            if (with.pixels[i] != 0 && without.pixels[i] == 0) plane.push_back(i);
    }

    // How many plane pixels a shadow AOV (or reference) of the same view shows in shadow.
    size_t shadowedIn(const Image& shadow) const {
        EXPECT_EQ(shadow.pixels.size(), without.pixels.size());
        size_t shadowed = 0;
        for (size_t i : plane) shadowed += i < shadow.pixels.size() && shadow.pixels[i] < 128;
        return shadowed;
    }
};

}  // namespace

TEST(CliGround, LoneModelStandsOnAPlaneThatReceivesItsShadow) {
    const PlaneView view;
    const Image shadow = runOnEngine("render", "shadow.png", "--aov shadow");
    const Image groundShadow = runOnEngine("render", "ground_shadow.png", "--aov shadow --ground");
    EXPECT_GT(view.plane.size(), view.without.pixels.size() / 5) << "the plane should fill a good part of the view";
    // The engine's shadow on it, and the sun's light around that.
    const size_t shadowed = view.shadowedIn(groundShadow), lit = view.plane.size() - shadowed;
    const size_t shadowedWithout = view.shadowedIn(shadow);
    std::printf("plane %zu pixels: %zu shadowed, %zu lit\n", view.plane.size(), shadowed, lit);
    EXPECT_GT(shadowed, 200u) << "the engine casts no shadow on the plane";
    EXPECT_GT(lit, shadowed) << "the plane should be mostly sunlit";
    EXPECT_EQ(shadowedWithout, 0u) << "without --ground those pixels are background (shadow AOV 1)";
}

TEST(CliGround, ReferenceTracesThePlaneAndAgreesWithTheShadowAov) {
    const PlaneView view;
    const Image ours = runOnEngine("render", "ground_shadow.png", "--aov shadow --ground");
    const Image reference = runOnEngine("reference", "ground_reference.png", "--ground");
    ASSERT_EQ(ours.pixels.size(), view.without.pixels.size());
    ASSERT_EQ(reference.pixels.size(), view.without.pixels.size());
    const size_t shadowed = view.shadowedIn(reference);
    size_t agree = 0;
    for (size_t i : view.plane) agree += (reference.pixels[i] < 128) == (ours.pixels[i] < 128);
    std::printf("plane %zu pixels: %zu shadowed in the reference, %zu agree\n", view.plane.size(), shadowed, agree);
    EXPECT_GT(shadowed, 200u) << "the reference has no shadow on the plane";
    EXPECT_GT(double(agree), 0.97 * double(view.plane.size()));
}
