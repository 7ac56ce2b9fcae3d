// CPU time of the ray-traced shadow reference: a field of boxes on a ground quad under an oblique
// sun, traced at a few resolutions, BVH build included (numbers only; nothing is asserted).
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"

namespace {

using namespace penumbra;

void addBox(Mesh& mesh, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    // Counter-clockwise seen from outside.
    const uint32_t faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    for (const auto& f : faces) {
        const auto base = uint32_t(mesh.vertices.size());
        const glm::vec3 n = glm::normalize(glm::cross(c[f[1]] - c[f[0]], c[f[2]] - c[f[0]]));
        for (uint32_t i : f) mesh.vertices.push_back({c[i], n, glm::vec2(0.0f)});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
}

Scene boxField(int boxesPerSide) {
    Scene scene;
    scene.materials.push_back(Material{});
    Mesh mesh;
    mesh.vertices = {{{-50, 0, -50}, {0, 1, 0}, {}}, {{50, 0, -50}, {0, 1, 0}, {}},
                     {{50, 0, 50}, {0, 1, 0}, {}}, {{-50, 0, 50}, {0, 1, 0}, {}}};
    mesh.indices = {0, 2, 1, 0, 3, 2};
    for (int i = 0; i < boxesPerSide; ++i) {
        for (int j = 0; j < boxesPerSide; ++j) {
            const glm::vec3 lo(-40.0f + 80.0f * float(i) / float(boxesPerSide), 0.0f,
                               -40.0f + 80.0f * float(j) / float(boxesPerSide));
            addBox(mesh, lo, lo + glm::vec3(1.5f, 1.0f + float((i * 7 + j * 3) % 5), 1.5f));
        }
    }
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{});
    Light sun;
    sun.wsDirection = glm::normalize(glm::vec3(0.6f, -1.0f, 0.3f));
    scene.lights.push_back(sun);
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(glm::vec3(0, 30, 60), glm::vec3(0), glm::vec3(0, 1, 0)));
    scene.camera = camera;
    return scene;
}

void BM_TraceReferenceShadow(benchmark::State& state) {
    const Scene scene = boxField(32);
    const auto size = uint32_t(state.range(0));
    const CameraView view = makeCameraView(*scene.camera, size, size);
    for (auto _ : state) {
        ReferenceImages images = traceReferenceShadow(scene, view, 0, false);
        benchmark::DoNotOptimize(images.validPixels);
    }
    state.counters["pixels/s"] = benchmark::Counter(double(size) * size, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_TraceReferenceShadow)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);

void BM_CompareShadowImages(benchmark::State& state) {
    const auto size = uint32_t(state.range(0));
    Image reference(size, size, 1, 255), ours(size, size, 1, 255), mask(size, size, 1, 255);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size / 2; ++x) reference.at(x, y) = 0;
    for (auto _ : state) benchmark::DoNotOptimize(compareShadowImages(ours, reference, mask).falseLit);
}
BENCHMARK(BM_CompareShadowImages)->Arg(512)->Unit(benchmark::kMillisecond);

}  // namespace
