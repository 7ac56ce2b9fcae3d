#pragma once
// Shared by the compare_* tests: the canonical scenes of tests/scenes/, and the rasterized shadow AOV
// compared with the ray-traced reference exactly as `penumbra compare` does it.
#include <map>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"
#include "render_test_support.h"
#include "penumbra/camera.h"
#include "scene/canonical_scenes.h"
#include "scene/gltf_loader.h"

namespace penumbra::test {

// Small enough for CI on lavapipe, large enough that shadows of the thin casters span pixels.
constexpr uint32_t kCompareWidth = 256;
constexpr uint32_t kCompareHeight = 144;

inline std::string canonicalScenePath(const std::string& name) {
    return std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/" + canonicalSceneFileName(name);
}

// Loaded once per test program: the tests read the same files a user passes to `penumbra compare`.
inline const Scene& canonicalScene(const std::string& name) {
    static std::map<std::string, Scene> scenes;
    auto it = scenes.find(name);
    if (it == scenes.end()) it = scenes.emplace(name, loadGltfScene(canonicalScenePath(name))).first;
    return it->second;
}

// As src/app/reference_command.cpp: the reference fades and ends shadows where the rasterizer does.
inline ReferenceOptions referenceOptionsFor(const Settings& settings, const CameraView& view) {
    ReferenceOptions options;
    options.maxShadowDistance = std::min(settings.shadows.maxDistance, view.zFar);
    options.distanceFade = settings.shadows.distanceFade;
    options.squaredFade = settings.shadows.fadeMode == ShadowFadeMode::Squared;
    return options;
}

// The reference depends on the light and the distance settings only, not on the filter: traced once.
inline const ReferenceImages& cachedReference(const std::string& name, uint32_t light, const Settings& settings) {
    static std::map<std::tuple<std::string, uint32_t, float, float>, ReferenceImages> cache;
    const auto key = std::make_tuple(name, light, settings.shadows.maxDistance, settings.shadows.distanceFade);
    auto it = cache.find(key);
    if (it == cache.end()) {
        const Scene& scene = canonicalScene(name);
        const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
        it = cache.emplace(key, traceReferenceShadow(scene, view, light, false, referenceOptionsFor(settings, view))).first;
    }
    return it->second;
}

struct SceneComparison {
    CompareMetrics metrics;
    RenderResult ours;  // the rasterized shadow AOV and the renderer's stats
};

class CompareTest : public RenderTest {
protected:
    SceneComparison compareCanonicalScene(const std::string& name, uint32_t light, const Settings& settings) {
        const Scene& scene = canonicalScene(name);
        const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
        const ReferenceImages& reference = cachedReference(name, light, settings);
        Renderer renderer(device(), scene);
        SceneComparison result;
        result.ours = renderAov(renderer, settings, view, light);
        result.metrics = compareShadowImages(result.ours.image, reference.shadow, reference.validMask);
        return result;
    }

    // The shadow AOV of light `light` at the compare size, from `renderer` (which keeps its caches).
    static RenderResult renderAov(Renderer& renderer, const Settings& settings, const CameraView& view, uint32_t light = 0) {
        RenderRequest request;
        request.width = kCompareWidth;
        request.height = kCompareHeight;
        request.output = OutputMode::ShadowAov;
        request.aovLight = light;
        return renderer.render(request, settings, view);
    }

    // A canonical scene through the forward path and the visibility buffer, in that order (the settings
    // otherwise as given).
    std::pair<SceneComparison, SceneComparison> forwardAndVisibility(const std::string& name, uint32_t light,
                                                                     Settings settings) {
        settings.render.mainView = MainView::Forward;
        SceneComparison forward = compareCanonicalScene(name, light, settings);
        settings.render.mainView = MainView::Visibility;
        return {std::move(forward), compareCanonicalScene(name, light, settings)};
    }

    // Two frames of one still view of a canonical scene in one renderer (what a cache keeps).
    std::pair<RenderResult, RenderResult> twoStillFrames(const std::string& name, const Settings& settings,
                                                         uint32_t light = 0) {
        const Scene& scene = canonicalScene(name);
        const CameraView view = resolveCameraView(scene, kCompareWidth, kCompareHeight);
        Renderer renderer(device(), scene);
        RenderResult first = renderAov(renderer, settings, view, light);
        return {std::move(first), renderAov(renderer, settings, view, light)};
    }

    // The AOV of `renderer`'s scene against the ray tracer of that very scene (after any edits).
    static CompareMetrics againstTruth(Renderer& renderer, const RenderResult& result, const Settings& settings,
                                       const CameraView& view, uint32_t light = 0) {
        const ReferenceImages reference =
            traceReferenceShadow(renderer.scene(), view, light, false, referenceOptionsFor(settings, view));
        return compareShadowImages(result.image, reference.shadow, reference.validMask);
    }
};

}  // namespace penumbra::test
