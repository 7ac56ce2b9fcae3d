// Clustered light culling on the CPU: the froxels hold every pixel that maps to
// them, and a light left out of a cluster adds exactly nothing anywhere inside it.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "penumbra/scene_builder.h"
#include "render/light_clusters.h"
#include "render/light_packing.h"

using namespace penumbra;

namespace {

constexpr uint32_t kWidth = 320, kHeight = 180;

CameraView testView(float zFar = INFINITY) {
    Camera camera = makeLookAtCamera({0.0f, 4.0f, 12.0f}, {0.0f, 0.0f, 0.0f}, 0.9f, 0.1f);
    camera.zFar = zFar;
    return makeCameraView(camera, kWidth, kHeight);
}

Aabb sceneBounds() {
    Aabb bounds;
    bounds.extend(glm::vec3(-20.0f, 0.0f, -20.0f));
    bounds.extend(glm::vec3(20.0f, 3.0f, 20.0f));
    return bounds;
}

// The world position seen at pixel (x, y) at view depth vsDepth.
glm::vec3 worldPointAt(const CameraView& view, float x, float y, float vsDepth) {
    const glm::mat4 viewFromClip = glm::inverse(view.clipFromView);
    const glm::vec4 p = viewFromClip * glm::vec4(2.0f * x / float(view.width) - 1.0f, 2.0f * y / float(view.height) - 1.0f, 0.5f, 1.0f);
    const glm::vec3 onRay = glm::vec3(p) / p.w;
    return glm::vec3(view.worldFromView * glm::vec4(onRay * (vsDepth / -onRay.z), 1.0f));
}

// lighting.glsl rangeAttenuation x spotAttenuation: what the lit pass multiplies the light by.
float shaderAttenuation(const gpu_data::LightData& light, const glm::vec3& wsPoint) {
    const glm::vec3 offset = light.wsPosition - wsPoint;
    const float distanceSquared = glm::dot(offset, offset);
    float attenuation = 1.0f;
    if (light.invRangeSquared > 0.0f) {
        const float ratio = distanceSquared * light.invRangeSquared;
        const float window = std::clamp(1.0f - ratio * ratio, 0.0f, 1.0f);
        attenuation = window * window;
    }
    if (light.type == gpu_data::kLightSpot) {
        const glm::vec3 wsFromLight = -offset * (1.0f / std::sqrt(std::max(distanceSquared, 1e-8f)));
        const float t = std::clamp(glm::dot(-light.wsToLight, wsFromLight) * light.spotScale + light.spotOffset,
                                   0.0f, 1.0f);
        attenuation *= t * t;
    }
    return attenuation;
}

// Point and spot lights of assorted ranges and cones over the scene, packed after one sun.
std::vector<gpu_data::LightData> assortedLights(uint32_t count) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<gpu_data::LightData> lights = {packLight(makeDirectionalLight({0.3f, -1.0f, 0.2f}, 3.0f), 0, kNoShadowSlot)};
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 position(40.0f * unit(random) - 20.0f, 3.0f * unit(random), 40.0f * unit(random) - 20.0f);
        const float range = 0.5f + 6.0f * unit(random);
        Light light = makePointLight(position, 5.0f, range);
        if (i % 2 == 1) {
            const glm::vec3 direction = glm::normalize(glm::vec3(unit(random) - 0.5f, -1.0f, unit(random) - 0.5f));
            light = makeSpotLight(position, direction, 5.0f, range, 0.1f + 1.2f * unit(random), 0.05f);
        }
        lights.push_back(packLight(light, i + 1, kNoShadowSlot));
    }
    return lights;
}

}  // namespace

TEST(LightClusters, SlicesRunFromTheNearPlaneToTheFarEndOfTheSceneWhenTheCameraHasNoFarPlane) {
    const CameraView view = testView();
    const gpu_data::LightClusterData clusters = makeLightClusterData(view, sceneBounds(), 1, 10, true);
    EXPECT_FLOAT_EQ(clusters.nearDepth, 0.1f);
    EXPECT_GT(clusters.farDepth, 30.0f);  // the far corners of a 40 m square seen from 12 m out
    EXPECT_LT(clusters.farDepth, 40.0f);
    EXPECT_FLOAT_EQ(testView(25.0f).zFar, 25.0f);
    EXPECT_FLOAT_EQ(makeLightClusterData(testView(25.0f), sceneBounds(), 1, 10, true).farDepth, 25.0f);
    EXPECT_EQ(clusters.lightCount, 10u);
    EXPECT_EQ(clusters.firstLight, 1u);
    EXPECT_EQ(clusters.wordsPerCluster, 1u);
    EXPECT_EQ(clusters.clustered, 1u);
    EXPECT_EQ(makeLightClusterData(view, sceneBounds(), 1, 33, true).wordsPerCluster, 2u);
    EXPECT_EQ(makeLightClusterData(view, sceneBounds(), 1, 0, true).clustered, 0u) << "no light: nothing to cull";
}

TEST(LightClusters, EveryPixelAndDepthFallsInAClusterWhoseBoxHoldsIt) {
    const CameraView view = testView();
    const gpu_data::LightClusterData clusters = makeLightClusterData(view, sceneBounds(), 1, 4, true);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const glm::vec2 pixel(float(kWidth) * unit(random), float(kHeight) * unit(random));
        const float vsDepth = clusters.nearDepth * std::pow(clusters.farDepth / clusters.nearDepth, unit(random));
        const int32_t cluster = clusterOfPixel(clusters, pixel, vsDepth);
        ASSERT_GE(cluster, 0);
        const uint32_t x = uint32_t(cluster) % 16, y = (uint32_t(cluster) / 16) % 9, slice = uint32_t(cluster) / 144;
        const ViewBox box = clusterViewBox(clusters, x, y, slice);
        const glm::vec3 vsPoint = glm::vec3(view.viewFromWorld * glm::vec4(worldPointAt(view, pixel.x, pixel.y, vsDepth), 1.0f));
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(vsPoint, box.vsMin)) && glm::all(glm::lessThanEqual(vsPoint, box.vsMax)))
            << "pixel " << pixel.x << ", " << pixel.y << " depth " << vsDepth << " in cluster " << cluster;
    }
    EXPECT_EQ(clusterOfPixel(clusters, {1.0f, 1.0f}, 1.01f * clusters.farDepth), -1) << "beyond the slices";
}

TEST(LightClusters, ALightLeftOutOfAClusterAddsNothingAnywhereInIt) {
    const CameraView view = testView();
    const std::vector<gpu_data::LightData> lights = assortedLights(64);
    const gpu_data::LightClusterData clusters = makeLightClusterData(view, sceneBounds(), 1, 64, true);
    const std::vector<uint32_t> masks = clusterLightMasks(clusters, lights);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    size_t culled = 0, checked = 0;
    for (int i = 0; i < 40000; ++i) {
        const glm::vec2 pixel(float(kWidth) * unit(random), float(kHeight) * unit(random));
        const float vsDepth = clusters.nearDepth * std::pow(clusters.farDepth / clusters.nearDepth, unit(random));
        const int32_t cluster = clusterOfPixel(clusters, pixel, vsDepth);
        const glm::vec3 wsPoint = worldPointAt(view, pixel.x, pixel.y, vsDepth);
        for (uint32_t light = 0; light < 64; ++light) {
            if ((masks[size_t(cluster) * clusters.wordsPerCluster + light / 32] >> (light % 32)) & 1u) continue;
            ++culled;
            const float attenuation = shaderAttenuation(lights[1 + light], wsPoint);
            checked += attenuation > 0.0f;
            ASSERT_EQ(attenuation, 0.0f) << "light " << light << " culled from cluster " << cluster;
        }
    }
    EXPECT_GT(culled, 40000u * 64u * 8u / 10u) << "most lights are culled from most clusters";
}

TEST(LightClusters, ASmallPointLightTouchesOnlyTheClustersAroundIt) {
    const CameraView view = testView();
    std::vector<gpu_data::LightData> lights = {packLight(makePointLight({0.0f, 1.0f, 0.0f}, 5.0f, 1.0f), 0, kNoShadowSlot)};
    const gpu_data::LightClusterData clusters = makeLightClusterData(view, sceneBounds(), 0, 1, true);
    const std::vector<uint32_t> masks = clusterLightMasks(clusters, lights);
    size_t touched = 0;
    const glm::vec3 vsLight = glm::vec3(view.viewFromWorld * glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
    for (uint32_t cluster = 0; cluster < gpu_data::kClusterCount; ++cluster) {
        if (masks[cluster] == 0u) continue;
        ++touched;
        const ViewBox box = clusterViewBox(clusters, cluster % 16, (cluster / 16) % 9, cluster / 144);
        EXPECT_LE(glm::length(glm::clamp(vsLight, box.vsMin, box.vsMax) - vsLight), 1.001f) << "cluster " << cluster;
    }
    EXPECT_GT(touched, 0u);
    EXPECT_LT(touched, gpu_data::kClusterCount / 50);
    // Its own cluster holds it.
    const glm::vec4 clip = view.clipFromWorld * glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    const glm::vec2 pixel((clip.x / clip.w * 0.5f + 0.5f) * float(kWidth), (clip.y / clip.w * 0.5f + 0.5f) * float(kHeight));
    const float vsDepth = -(view.viewFromWorld * glm::vec4(0.0f, 1.0f, 0.0f, 1.0f)).z;
    EXPECT_EQ(masks[size_t(clusterOfPixel(clusters, pixel, vsDepth))], 1u);
}

TEST(LightClusters, APointLightWithoutRangeTouchesEveryCluster) {
    const std::vector<gpu_data::LightData> lights = {packLight(makePointLight({50.0f, 1.0f, 0.0f}, 5.0f, 0.0f), 0, kNoShadowSlot)};
    const std::vector<uint32_t> masks = clusterLightMasks(makeLightClusterData(testView(), sceneBounds(), 0, 1, true), lights);
    for (uint32_t word : masks) ASSERT_EQ(word, 1u);
}

TEST(LightClusters, ASpotLightTouchesNothingBehindItOrOutsideItsCone) {
    // Under the camera's eye, 1 m up, pointing away from the camera and down: its narrow cone (10°)
    // covers a few clusters in front of it; a point light at the same place with the same range covers more.
    const CameraView view = testView();
    const glm::vec3 position(0.0f, 1.0f, 4.0f);
    const Light spot = makeSpotLight(position, glm::normalize(glm::vec3(0.0f, -0.2f, -1.0f)), 5.0f, 8.0f, 0.17f, 0.1f);
    const std::vector<gpu_data::LightData> lights = {packLight(spot, 0, kNoShadowSlot),
                                                     packLight(makePointLight(position, 5.0f, 8.0f), 1, kNoShadowSlot)};
    const std::vector<uint32_t> masks = clusterLightMasks(makeLightClusterData(view, sceneBounds(), 0, 2, true), lights);
    size_t spotClusters = 0, pointClusters = 0;
    for (uint32_t word : masks) {
        spotClusters += word & 1u;
        pointClusters += (word >> 1) & 1u;
        ASSERT_FALSE((word & 1u) && !(word & 2u)) << "the cone lies inside the range sphere";
    }
    EXPECT_GT(spotClusters, 0u);
    EXPECT_LT(3 * spotClusters, pointClusters);
}
