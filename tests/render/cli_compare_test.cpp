// `penumbra compare` and `penumbra reference` on a canonical scene, as a user runs them.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"
#include "penumbra/settings.h"
#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"
#include "penumbra/camera.h"
#include "scene/canonical_scenes.h"
#include "scene/gltf_loader.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

std::string scenePath(const std::string& name) {
    return std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/" + canonicalSceneFileName(name);
}

std::string deviceArgs() {
    const char* device = std::getenv("PENUMBRA_DEVICE");
    return std::string(" --device ") + (device ? device : "cpu") + " --validation";
}

std::string tempPath(const std::string& stem) {
    return (std::filesystem::temp_directory_path() / (stem + "_" + std::to_string(::getpid()) + ".png")).string();
}

}  // namespace

TEST(CliCompare, JsonOutputHoldsConsistentMetrics) {
    const CliRun run = runPenumbra("compare " + scenePath("low_sun") + " --width 128 --height 72 --json" + deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json m = nlohmann::json::parse(run.out);
    const auto valid = m.at("validPixels").get<uint64_t>();
    EXPECT_GT(valid, 128u * 72u / 4);  // most of the view is open ground facing the low sun
    const auto wrong = m.at("falseShadow").get<uint64_t>() + m.at("falseLit").get<uint64_t>();
    EXPECT_NEAR(m.at("misclassifiedPercent").get<double>(), 100.0 * double(wrong) / double(valid), 1e-9);
    EXPECT_LE(m.at("interiorPixels").get<uint64_t>(), valid);
    EXPECT_GE(m.at("meanAbsoluteError").get<double>(), 0.0);
    EXPECT_LE(m.at("meanAbsoluteError").get<double>(), 1.0);
    EXPECT_EQ(m.at("threshold").get<double>(), 0.5);
}

TEST(CliCompare, DiffImageIsAnRgbPictureOfTheView) {
    const std::string diff = tempPath("penumbra_diff");
    const CliRun run =
        runPenumbra("compare " + scenePath("foliage") + " --width 96 --height 54 --diff " + diff + deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("misclassified"), std::string::npos) << run.out;
    const Image image = readPng(diff);
    std::filesystem::remove(diff);
    EXPECT_EQ(image.width, 96u);
    EXPECT_EQ(image.height, 54u);
    EXPECT_EQ(image.channels, 3u);
}

// The CLI's reference image, compared with the library's trace of the same view, differs nowhere:
// `compare` of an image with itself is zero on a real scene, and the CLI adds nothing to the trace.
TEST(CliCompare, ReferenceImageComparedWithItselfIsExact) {
    const std::string png = tempPath("penumbra_ref"), mask = tempPath("penumbra_mask");
    const CliRun run = runPenumbra("reference " + scenePath("thin_wall") + " --width 96 --height 54 -o " + png +
                                   " --mask " + mask + deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const Image cliShadow = readPng(png, 1), cliMask = readPng(mask, 1);
    std::filesystem::remove(png);
    std::filesystem::remove(mask);

    const Scene scene = loadGltfScene(scenePath("thin_wall"));
    const CameraView view = resolveCameraView(scene, 96, 54);
    ReferenceOptions options;
    options.maxShadowDistance = Settings{}.shadows.maxDistance;  // the CLI ran with the default settings
    const ReferenceImages library = traceReferenceShadow(scene, view, 0, false, options);
    EXPECT_EQ(cliMask.pixels, library.validMask.pixels);
    const CompareMetrics self = compareShadowImages(cliShadow, library.shadow, library.validMask);
    EXPECT_GT(self.validPixels, 1000u);
    EXPECT_EQ(self.falseShadow + self.falseLit, 0u);
    EXPECT_EQ(self.meanAbsoluteError, 0.0);
}

TEST(CliCompare, ShimmerFlagAddsTheTwoFrameMeasurement) {
    const CliRun run = runPenumbra("compare " + scenePath("low_sun") + " --width 128 --height 72 --json --shimmer" +
                                   deviceArgs());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json m = nlohmann::json::parse(run.out);
    const auto pixels = m.at("shimmerPixels").get<uint64_t>();
    EXPECT_GT(pixels, m.at("validPixels").get<uint64_t>() / 2);  // a 2 cm step keeps most pixels valid
    EXPECT_NEAR(m.at("shimmerPercent").get<double>(),
                100.0 * double(m.at("shimmerFlickering").get<uint64_t>()) / double(pixels), 1e-9);
    EXPECT_GT(m.at("shimmerReferenceFlips").get<uint64_t>(), 0u) << "the truth moves at the shadow edges";
    EXPECT_TRUE(m.contains("edgeBalance"));
}

TEST(CliCompare, SoftComparesWithTheAreaLightReference) {
    const std::string args = "compare " + scenePath("pcss_contact") + " --width 96 --height 54 --json" + deviceArgs();
    const CliRun hard = runPenumbra(args), soft = runPenumbra(args + " --soft 32");
    ASSERT_EQ(hard.exitCode, 0) << hard.err;
    ASSERT_EQ(soft.exitCode, 0) << soft.err;
    // The pcss sun's shadow against a point-sun truth has more error than against its area truth.
    EXPECT_LT(nlohmann::json::parse(soft.out).at("meanAbsoluteError").get<double>(),
              nlohmann::json::parse(hard.out).at("meanAbsoluteError").get<double>());
}
