// The tight fit's depth reduction on the GPU (render/visible_surface_pass.h, visible_bounds.comp)
// against the CPU's exact reduction of the same depth (shadows/visible_surfaces.h), on lavapipe with
// validation, and the real-time frames that plan with it.
//
// Tolerances: the GPU reconstructs each pixel's world position with its own rounding, so boxes are
// compared to 2 mm, depths to 1e-5 of themselves. A point near a bin's edge may fall in the bin next to
// the one the CPU picks, so a slice's GPU box (slices as far as the shadow distance, beyond which the
// bins reach) must hold the CPU's exact box of the slice and lie within the exact box of the slice
// widened by three bins on either side (the query takes one more bin each way, plus one bin of
// rounding). A real-time frame's tiles, planned from the bins, have texels at most one step of the
// quantized tile size (2^(1/8)) coarser than a one-shot frame's, planned from every point.
#include <algorithm>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "render/visible_surface_pass.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"
#include "shadows/cascades.h"
#include "virtual_shadow_test_support.h"

namespace penumbra::test {
namespace {

constexpr float kBoxTolerance = 2e-3f;  // metres

bool holds(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.min, inner.min + kBoxTolerance)) &&
           glm::all(glm::greaterThanEqual(outer.max, inner.max - kBoxTolerance));
}

glm::mat4 directionalRotation(const Scene& scene) {
    for (const Light& light : scene.lights)
        if (light.type == LightType::Directional) return lightRotationFromWorld(light.wsDirection);
    throw std::runtime_error("the scene has no directional light");
}

class VisibleBoundsTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }

    // The GPU's bins of the scene's view against the exact points of the same depth: the depth range,
    // and the boxes of six slices of it in the light's space and the world's.
    void expectAgreement(const Scene& scene, const std::string& name) {
        const CameraView view = resolveCameraView(scene, 320, 180);
        const SceneDepth depth = renderSceneDepth(gpu(), scene, view);
        const VisibleSurfaces exact = visibleSurfacesFromDepth(depth.image, view);
        const glm::mat4 light = directionalRotation(scene);
        const float vsShadowDistance = shadowDistance(view, 100.0f);
        GpuScene gpuScene(gpu(), scene);
        MainPass mainPass(gpu(), gpuScene, scene, PipelineWarmup::OnDemand);
        VisibleSurfacePass pass(gpu(), gpuScene, mainPass);
        const VisibleSurfaces binned = pass.boundsNow(depth.texture, view, std::vector<glm::mat4>{light}, vsShadowDistance);
        gpu().destroy(depth.texture);
        ASSERT_FALSE(exact.empty()) << name;
        ASSERT_TRUE(binned.wsPoints.empty()) << name;
        EXPECT_NEAR(binned.vsMinDepth, exact.vsMinDepth, 1e-5f * exact.vsMinDepth) << name;
        EXPECT_NEAR(binned.vsMaxDepth, exact.vsMaxDepth, 1e-5f * exact.vsMaxDepth) << name;
        ASSERT_EQ(binned.bins.spaceCount, 2u) << name << ": the light's space and the world's";
        const float step = std::exp(3.0f / binned.bins.binsPerLogDepth);  // three bins
        // Slices as far as the plan asks: to the shadow distance.
        const float vsFarthest = std::min(exact.vsMaxDepth, vsShadowDistance);
        const float ratio = std::pow(vsFarthest / exact.vsMinDepth, 1.0f / 6.0f);
        for (const glm::mat4& rotation : {light, glm::mat4(1.0f)})
            for (int slice = 0; slice < 6; ++slice) {
                const float vsNear = exact.vsMinDepth * std::pow(ratio, float(slice));
                const float vsFar = vsNear * ratio;
                const Aabb exactBox = rotatedVisibleBounds(exact, rotation, vsNear, vsFar);
                if (!exactBox.valid()) continue;
                const Aabb gpuBox = rotatedVisibleBounds(binned, rotation, vsNear, vsFar);
                const Aabb outerBox = rotatedVisibleBounds(exact, rotation, vsNear / step, vsFar * step);
                EXPECT_TRUE(holds(gpuBox, exactBox)) << name << ", slice " << slice << ": a visible point left out";
                EXPECT_TRUE(holds(outerBox, gpuBox)) << name << ", slice " << slice << ": points from beyond the bins next to it";
            }
    }
};

TEST_F(VisibleBoundsTest, GpuBinsHoldEveryVisiblePointOfTheCanonicalScenesAndLittleMore) {
    for (const char* name : {"near_far_casters", "thin_wall", "poles", "grazing", "foliage", "low_sun", "far_field",
                             "thin_slabs", "grazing_sun", "fence", "field_of_objects", "cube"})
        expectAgreement(makeCanonicalScene(name), name);
}

// Real-time frames plan the tight fit from the GPU's bins of a finished frame; a one-shot render plans
// it from every point. Same splits, texels within one quantization step.
TEST_F(VisibleBoundsTest, RealTimeFramesPlanTheTightFitFromTheGpuBinsAsAOneShotFrameDoes) {
    for (const char* name : {"field_of_objects", "low_sun", "cube"}) {
        const Scene scene = makeCanonicalScene(name);
        RenderRequest request;
        request.width = 160;
        request.height = 90;
        const CameraView view = resolveCameraView(scene, request.width, request.height);
        Renderer oneShot(device(), scene);
        const nlohmann::json expected =
            nlohmann::json::parse(toJson(oneShot.render(request, {}, view).stats.shadows))["directional"];
        Renderer realTime(device(), scene);
        for (int i = 0; i < 4; ++i) realTime.submitFrame(request, {}, view);
        realTime.waitIdle();
        const std::vector<FrameStats> frames = realTime.takeCompletedFrames();
        ASSERT_EQ(frames.size(), 4u);
        const nlohmann::json actual = nlohmann::json::parse(toJson(frames.back().shadows))["directional"];
        ASSERT_EQ(actual["fit"], "tight") << name;
        const std::vector<float> splits = actual["cascadeSplits"], expectedSplits = expected["cascadeSplits"];
        ASSERT_EQ(splits.size(), expectedSplits.size()) << name;
        for (size_t i = 0; i < splits.size(); ++i) EXPECT_NEAR(splits[i], expectedSplits[i], 1e-4f * expectedSplits[i]) << name;
        const std::vector<float> texels = actual["texelSizeMetres"], expectedTexels = expected["texelSizeMetres"];
        ASSERT_EQ(texels.size(), expectedTexels.size()) << name;
        for (size_t i = 0; i < texels.size(); ++i) {
            EXPECT_GE(texels[i], expectedTexels[i] * 0.999f) << name << ", tile " << i;
            EXPECT_LE(texels[i], expectedTexels[i] * std::exp2(1.0f / 8.0f) * 1.001f) << name << ", tile " << i;
        }
    }
}

// Only the first real-time frame waits for its own reduction: the frames after it plan from it until
// their own reductions come back, however many are in flight (one-shot frames always wait).
TEST_F(VisibleBoundsTest, OnlyTheFirstRealTimeFrameWaitsForTheTightFitsReduction) {
    const Scene scene = makeCanonicalScene("poles");
    RenderRequest request;
    request.width = 160;
    request.height = 90;
    const CameraView view = resolveCameraView(scene, request.width, request.height);
    Settings settings;
    settings.shadows.directional.fit = CascadeFit::Tight;
    Renderer renderer(device(), scene);
    for (int i = 0; i < 4; ++i) renderer.submitFrame(request, settings, view);
    renderer.waitIdle();
    const std::vector<FrameStats> frames = renderer.takeCompletedFrames();
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_TRUE(frames[0].tightFitWaited);
    for (size_t i = 1; i < frames.size(); ++i) EXPECT_FALSE(frames[i].tightFitWaited) << "frame " << i;
    EXPECT_TRUE(renderer.render(request, settings, view).stats.tightFitWaited) << "a one-shot frame";
}

}  // namespace
}  // namespace penumbra::test
