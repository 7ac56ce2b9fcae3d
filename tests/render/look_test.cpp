// The look of the colour output (tone mapping, background) as penumbra render gives it: render.background
// draws a sky gradient only where no surface is, and the shadow and cascade AOVs stay exactly what they were
// (no tone mapping, their own backgrounds). The GPU's curves: lit_plane_test.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "cli_process.h"
#include "penumbra/image.h"

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path tempPath(const std::string& name) {
    // One folder per test process: ctest runs tests in parallel, and two tests writing one file (two
    // viewers watching the same reloaded.gltf) fail each other.
    const fs::path dir = fs::temp_directory_path() / ("penumbra_look_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

// `penumbra render` of the demo scene at 320 x 180 with `options`.
Image renderDemo(const std::string& name, const std::string& options) {
    const fs::path out = tempPath(name);
    fs::remove(out);
    const CliRun run = runPenumbra("render --device cpu --validation --width 320 --height 180 -o " + out.string() + " " + options);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    return fs::exists(out) ? readPng(out.string()) : Image{};
}

bool isBlack(const Image& image, uint32_t x, uint32_t y) {
    for (uint32_t c = 0; c < 3; ++c)
        if (image.at(x, y, c) != 0) return false;
    return true;
}

bool samePixel(const Image& a, const Image& b, uint32_t x, uint32_t y) {
    for (uint32_t c = 0; c < a.channels; ++c)
        if (a.at(x, y, c) != b.at(x, y, c)) return false;
    return true;
}

}  // namespace

TEST(Look, DefaultSceneBackgroundIsAGradientBehindUnchangedSurfaces) {
    const Image sky = renderDemo("sky.png", "");
    const Image black = renderDemo("black.png", "--set render.background=black");
    ASSERT_EQ(sky.pixels.size(), black.pixels.size());
    ASSERT_FALSE(sky.empty());
    // The background fills only what no surface covers: every pixel that differs is black without it.
    size_t background = 0, overwritten = 0;
    double firstRow[3] = {}, lastRow[3] = {};
    int first = -1, last = -1;
    for (uint32_t y = 0; y < sky.height; ++y) {
        size_t rowCount = 0;
        double row[3] = {};
        for (uint32_t x = 0; x < sky.width; ++x) {
            if (samePixel(sky, black, x, y)) continue;
            if (!isBlack(black, x, y)) ++overwritten;
            ++background;
            ++rowCount;
            for (uint32_t c = 0; c < 3; ++c) row[c] += sky.at(x, y, c);
        }
        if (rowCount < sky.width / 4) continue;  // rows that show enough of the background
        if (first < 0) first = int(y);
        last = int(y);
        for (uint32_t c = 0; c < 3; ++c) (first == int(y) ? firstRow : lastRow)[c] = row[c] / double(rowCount);
    }
    EXPECT_EQ(overwritten, 0u) << "the background drew over surfaces";
    EXPECT_GT(double(background) / double(sky.width * sky.height), 0.1) << "the demo's camera should see the sky";
    ASSERT_GE(first, 0);
    ASSERT_GT(last - first, int(sky.height) / 8) << "background rows " << first << ".." << last;
    // A gradient: the highest and the lowest background rows differ by measurement (the zenith is bluer).
    double difference = 0.0;
    for (uint32_t c = 0; c < 3; ++c) difference = std::max(difference, std::abs(firstRow[c] - lastRow[c]));
    std::printf("background rows %d..%d: top (%.0f %.0f %.0f), bottom (%.0f %.0f %.0f)\n", first, last, firstRow[0],
                firstRow[1], firstRow[2], lastRow[0], lastRow[1], lastRow[2]);
    EXPECT_GT(difference, 10.0);
    EXPECT_GT(firstRow[2], firstRow[0]) << "the top of the sky should be blue";
}

TEST(Look, ShadowAndCascadeAovsIgnoreToneMappingAndBackground) {
    // The shadow AOV stays the exact shadow term (255 where no surface is) and the cascade AOV its
    // colours on black, whatever render.toneMapping and render.background say.
    const std::string plain = "--set render.toneMapping=none --set render.background=black";
    for (const std::string aov : {"shadow", "cascades"}) {
        for (const std::string look : {"", "--set render.toneMapping=aces"}) {
            const Image looked = renderDemo(aov + "_look.png", "--aov " + aov + " " + look);
            const Image linear = renderDemo(aov + "_plain.png", "--aov " + aov + " " + plain);
            ASSERT_EQ(looked.pixels.size(), linear.pixels.size()) << aov;
            ASSERT_FALSE(looked.empty());
            size_t classDiffers = 0, bytesDiffer = 0;
            for (size_t i = 0; i < looked.pixels.size(); ++i) {
                classDiffers += (looked.pixels[i] >= 128) != (linear.pixels[i] >= 128);
                bytesDiffer += looked.pixels[i] != linear.pixels[i];
            }
            EXPECT_EQ(classDiffers, 0u) << aov << " " << look;
            EXPECT_EQ(bytesDiffer, 0u) << aov << " " << look;
        }
    }
    const Image shadow = renderDemo("shadow_default.png", "--aov shadow");
    EXPECT_EQ(shadow.at(0, 0), 255) << "the shadow AOV's background is 1 (the demo's top-left corner is sky)";
}

TEST(Look, BadToneMappingOrBackgroundIsOneLineError) {
    expectOneLineError(runPenumbra("render --set render.toneMapping=filmic"), "render.toneMapping");
    expectOneLineError(runPenumbra("render --set render.background=sky"), "render.background");
    const fs::path settings = tempPath("bad_look.json");
    { std::ofstream(settings) << R"({"render": {"toneMapping": "reinhard"}})"; }
    expectOneLineError(runPenumbra("render --settings " + settings.string() + " -o " + tempPath("x.png").string()),
                       "allowed none, neutral, aces");
}
