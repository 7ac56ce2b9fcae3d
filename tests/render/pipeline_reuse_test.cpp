// Compiled pipelines outlive their handles on a device: a second renderer of the same scene and
// settings compiles nothing and draws the same image; the kept pipelines are not live objects.
#include "penumbra/scene_loading.h"
#include "render_test_support.h"
#include "spot_render_scenes.h"

namespace penumbra::test {
namespace {

class PipelineReuseTest : public RenderTest {};

RenderRequest colourRequest() {
    RenderRequest request;
    request.width = 48;
    request.height = 32;
    request.output = OutputMode::Color;
    return request;
}

TEST_F(PipelineReuseTest, SecondRendererOfTheSameSceneCompilesNoPipelineAndDrawsTheSameImage) {
    const Scene scene = makeDemoScene();
    Image first;
    {
        Renderer renderer(device(), scene);
        first = renderer.render(colourRequest(), {}).image;
    }
    const DeviceObjectCounts before = device().liveObjects();
    EXPECT_GT(before.pipelinesParked, 0u);
    Renderer again(device(), scene);
    const Image second = again.render(colourRequest(), {}).image;
    const DeviceObjectCounts after = device().liveObjects();
    EXPECT_EQ(after.pipelinesCompiled, before.pipelinesCompiled);
    EXPECT_GT(after.pipelinesReused, before.pipelinesReused);
    EXPECT_TRUE(first.pixels == second.pixels);
}

TEST_F(PipelineReuseTest, DifferentSettingsCompileTheirOwnVariants) {
    Device own(testDeviceOptions());  // nothing parked by earlier tests
    const Scene scene = boxUnderLight(testSpot(LightShadows::Soft));
    Settings first = smallSpotAtlas(), second = smallSpotAtlas();
    first.shadows.spot.filter = ShadowFilter::PCF2x2;
    second.shadows.spot.filter = ShadowFilter::PCF7x7;  // another specialization of the lit pass
    {
        Renderer renderer(own, scene);
        renderer.render(colourRequest(), first);
    }
    const uint64_t compiled = own.liveObjects().pipelinesCompiled;
    Renderer renderer(own, scene);
    renderer.render(colourRequest(), second);
    EXPECT_GT(own.liveObjects().pipelinesCompiled, compiled);
    EXPECT_EQ(own.validationMessageCount(), 0u);
}

TEST_F(PipelineReuseTest, KeptPipelinesAreNotLiveObjects) {
    const uint32_t pipelinesBefore = device().liveObjects().pipelines;
    {
        Renderer renderer(device(), makeDemoScene());
        renderer.render(colourRequest(), {});
        EXPECT_GT(device().liveObjects().pipelines, pipelinesBefore);
    }
    const DeviceObjectCounts after = device().liveObjects();
    EXPECT_EQ(after.pipelines, pipelinesBefore);
    EXPECT_GT(after.pipelinesParked, 0u);
}

}  // namespace
}  // namespace penumbra::test
