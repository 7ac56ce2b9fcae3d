// CPU cost of ShadowPlanner::plan on a synthetic city: ~10k box instances on a 100 x 100 grid, 4
// shadowed directional lights, 4 cascades. Prints ns per plan and the caster draws it produces.
#include <cmath>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/camera.h"
#include "shadows/shadow_planner.h"

namespace {

using namespace penumbra;

Scene syntheticCity(int gridSize) {
    Scene scene;
    scene.materials.resize(1);
    scene.meshes.resize(1);
    const float spacing = 3.0f;
    for (int z = 0; z < gridSize; ++z) {
        for (int x = 0; x < gridSize; ++x) {
            // Deterministic pseudo-random heights: a cheap hash of the cell.
            const uint32_t hash = uint32_t(x * 73856093) ^ uint32_t(z * 19349663);
            const float height = 1.0f + float(hash % 97) * 0.1f;
            const glm::vec3 base((float(x) - 0.5f * float(gridSize)) * spacing, 0.0f,
                                 (float(z) - 0.5f * float(gridSize)) * spacing);
            Instance instance;
            instance.wsBounds.extend(base - glm::vec3(1.0f, 0.0f, 1.0f));
            instance.wsBounds.extend(base + glm::vec3(1.0f, height, 1.0f));
            instance.worldFromObject = glm::translate(glm::mat4(1.0f), base);
            scene.wsBounds.extend(instance.wsBounds);
            scene.instances.push_back(instance);
        }
    }
    const glm::vec3 directions[] = {{0.3f, -1.0f, 0.2f}, {-0.6f, -1.0f, 0.1f}, {0.1f, -0.7f, -0.8f}, {0.9f, -0.4f, 0.3f}};
    for (const glm::vec3& direction : directions) {
        Light light;
        light.wsDirection = glm::normalize(direction);
        scene.lights.push_back(light);
    }
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(glm::vec3(0, 25, 60), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0)));
    camera.zNear = 0.1f;
    camera.zFar = 1000.0f;
    scene.camera = camera;
    return scene;
}

void BM_ShadowPlannerPlan(benchmark::State& state) {
    const Scene scene = syntheticCity(int(state.range(0)));
    const CameraView camera = resolveCameraView(scene, 1920, 1080);
    ShadowSettings settings;
    settings.directional.atlasSize = 4096;
    uint32_t draws = 0;
    for (auto _ : state) {
        const ShadowFrame frame = ShadowPlanner::plan(scene, camera, settings);
        draws = frame.stats.casterDraws;
        benchmark::DoNotOptimize(frame.directional.gpu);
    }
    state.counters["instances"] = double(scene.instances.size());
    state.counters["casterDraws"] = double(draws);
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(scene.instances.size()));
}
BENCHMARK(BM_ShadowPlannerPlan)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
