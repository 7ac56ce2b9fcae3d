#pragma once
// Shared pieces of the directional shadow render tests: small in-memory scenes (a ground plane with
// boxes under a sun), settings with a small atlas, the analytic shadow of axis-aligned boxes, and a
// fixture that renders AOVs and compares them with the ray-traced reference.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"
#include "render_test_support.h"
#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"

namespace penumbra::test {

struct Box {
    glm::vec3 min, max;
};

// A white, fully rough dielectric: its look doesn't matter to the shadow AOV, only its flags.
inline Material matteMaterial(glm::vec4 baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f)) {
    Material material;
    material.baseColorFactor = baseColor;
    material.metallic = 0.0f;
    material.roughness = 1.0f;
    return material;
}

inline uint32_t addBox(SceneBuilder& builder, const Box& box, uint32_t material, bool castShadows = true) {
    const uint32_t mesh = builder.addMesh(makeBoxMesh(0.5f * (box.max - box.min), material));
    const glm::mat4 worldFromObject = glm::translate(glm::mat4(1.0f), 0.5f * (box.min + box.max));
    return builder.addInstance(mesh, worldFromObject, castShadows);
}

inline uint32_t addGround(SceneBuilder& builder, float size, uint32_t material) {
    return builder.addInstance(builder.addMesh(makePlaneMesh({size, size}, material)), glm::mat4(1.0f));
}

// Settings with a small atlas (the tests run on lavapipe) and a shadow distance that fits the scenes,
// and sphere-fitted cascades (culling spheres, manual ratios): these tests check the behaviour of
// Catlike Coding "Directional Shadows"; the tight fit and log splits (the defaults) have their own tests.
inline Settings shadowSettings(float maxDistance = 30.0f, uint32_t cascadeCount = 4, uint32_t atlasSize = 1024,
                               ShadowFilter filter = ShadowFilter::PCF2x2, CascadeBlend blend = CascadeBlend::Hard) {
    Settings settings;
    settings.shadows.maxDistance = maxDistance;
    settings.shadows.directional.atlasSize = atlasSize;
    settings.shadows.directional.cascadeCount = cascadeCount;
    settings.shadows.directional.filter = filter;
    settings.shadows.directional.cascadeBlend = blend;
    settings.shadows.directional.fit = CascadeFit::Sphere;
    settings.shadows.directional.cascadeSplits = CascadeSplitMode::Manual;
    return settings;
}

// Ray / axis-aligned box slab test: the entry distance t >= 0, or nullopt.
inline std::optional<float> rayBoxHit(glm::vec3 origin, glm::vec3 direction, const Box& box) {
    float tNear = 0.0f, tFar = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(direction[axis]) < 1e-9f) {
            if (origin[axis] < box.min[axis] || origin[axis] > box.max[axis]) return std::nullopt;
            continue;
        }
        float t0 = (box.min[axis] - origin[axis]) / direction[axis];
        float t1 = (box.max[axis] - origin[axis]) / direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        tNear = std::max(tNear, t0);
        tFar = std::min(tFar, t1);
        if (tNear > tFar) return std::nullopt;
    }
    return tNear;
}

// Where the primary ray of pixel (x, y) meets the ground plane y = 0 within |x|, |z| <= groundHalf,
// when no box is in front of it.
inline std::optional<glm::vec3> visibleGroundPoint(const CameraView& view, uint32_t x, uint32_t y,
                                                   float groundHalf, const std::vector<Box>& boxes) {
    const glm::vec3 direction = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
    if (direction.y >= -1e-6f) return std::nullopt;
    const float t = -view.wsPosition.y / direction.y;
    const glm::vec3 ground = view.wsPosition + t * direction;
    if (std::abs(ground.x) > groundHalf || std::abs(ground.z) > groundHalf) return std::nullopt;
    for (const Box& box : boxes) {
        if (auto hit = rayBoxHit(view.wsPosition, direction, box); hit && *hit < t) return std::nullopt;
    }
    return ground;
}

// Analytic shadow AOV of boxes on the ground under a directional light (strength 1, no fade): 0 where a
// ray from the ground point toward the light meets a box, else 255. Pixels not on the visible ground,
// or next to one that isn't, are marked invalid in `validMask`.
struct AnalyticShadow {
    Image shadow;
    Image validMask;
};

inline AnalyticShadow analyticGroundShadow(const CameraView& view, float groundHalf, const std::vector<Box>& boxes,
                                           glm::vec3 wsLightDirection) {
    AnalyticShadow result{Image(view.width, view.height, 1, 255), Image(view.width, view.height, 1, 0)};
    Image onGround(view.width, view.height, 1, 0);
    const glm::vec3 toLight = -glm::normalize(wsLightDirection);
    for (uint32_t y = 0; y < view.height; ++y) {
        for (uint32_t x = 0; x < view.width; ++x) {
            const auto ground = visibleGroundPoint(view, x, y, groundHalf, boxes);
            if (!ground) continue;
            onGround.at(x, y) = 1;
            for (const Box& box : boxes) {
                if (rayBoxHit(*ground + 1e-4f * toLight, toLight, box)) result.shadow.at(x, y) = 0;
            }
        }
    }
    for (uint32_t y = 1; y + 1 < view.height; ++y) {
        for (uint32_t x = 1; x + 1 < view.width; ++x) {
            bool all = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) all = all && onGround.at(x + dx, y + dy);
            result.validMask.at(x, y) = all ? 255 : 0;
        }
    }
    return result;
}

// Boxes spread in depth on an 80 m ground, so that every cascade of a 4-cascade split (maxDistance 40)
// holds some shadow.
inline std::vector<Box> boxesInDepth() {
    std::vector<Box> boxes;
    for (float z : {3.0f, -2.0f, -8.0f, -16.0f, -26.0f}) {
        const float half = 0.5f + 0.08f * std::abs(z);
        boxes.push_back({{-2.5f - half, 0.0f, z - half}, {-2.5f + half, 2.0f * half, z + half}});
    }
    return boxes;
}

inline Scene boxesInDepthScene() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(matteMaterial());
    addGround(builder, 80.0f, material);
    for (const Box& box : boxesInDepth()) addBox(builder, box, material);
    builder.addLight(makeDirectionalLight({0.8f, -1.0f, 0.35f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 5.0f, 9.0f}, {0.0f, 0.0f, -10.0f}, glm::radians(55.0f)));
    return builder.build();
}

// Pixels whose value lies strictly between `low` and `high`: the penumbra of a filtered shadow.
inline uint32_t countBetween(const Image& image, uint8_t low, uint8_t high) {
    return uint32_t(std::count_if(image.pixels.begin(), image.pixels.end(),
                                  [&](uint8_t v) { return v > low && v < high; }));
}

class DirectionalShadowTest : public RenderTest {
protected:
    int dumpCounter_ = 0;  // numbers the AOVs written to $PENUMBRA_TEST_DUMP, when set (for debugging)

    Image renderShadowAov(const Scene& scene, const Settings& settings, uint32_t size, uint32_t light = 0) {
        Image aov = renderScene(scene, RenderRequest{size, size, OutputMode::ShadowAov, light, false}, settings).image;
        if (const char* dir = std::getenv("PENUMBRA_TEST_DUMP")) {
            const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
            writePng(aov, std::string(dir) + "/" + info->name() + "_" + std::to_string(dumpCounter_++) + ".png");
        }
        return aov;
    }

    // The rendered shadow AOV of `light` against the ray-traced reference with the same fade settings.
    CompareMetrics compareWithReference(const Scene& scene, const Image& aov, const Settings& settings,
                                        uint32_t light = 0, float threshold = 0.5f) {
        const CameraView view = resolveCameraView(scene, aov.width, aov.height);
        ReferenceOptions options;
        options.maxShadowDistance = settings.shadows.maxDistance;
        options.distanceFade = settings.shadows.distanceFade;
        options.squaredFade = settings.shadows.fadeMode == ShadowFadeMode::Squared;
        const ReferenceImages reference = traceReferenceShadow(scene, view, light, false, options);
        return compareShadowImages(aov, reference.shadow, reference.validMask, threshold);
    }
};

}  // namespace penumbra::test
