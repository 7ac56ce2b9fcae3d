#include <algorithm>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/caster_culling.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

bool contains(const std::vector<uint32_t>& list, uint32_t value) {
    return std::find(list.begin(), list.end(), value) != list.end();
}

// Two cascades around the origin: sphere 0 of radius 5, sphere 1 of radius 20; light straight down.
struct CullingFixture {
    Scene scene = baseScene();
    std::vector<CascadeSphere> spheres{{0.1f, 5.0f, glm::vec3(0.0f), 5.0f}, {5.0f, 20.0f, glm::vec3(0.0f), 20.0f}};
    glm::mat4 rotation = lightRotationFromWorld(glm::vec3(0.0f, -1.0f, 0.0f));

    TileCasters cull(uint32_t cascade, float factor) const {
        const std::vector<uint32_t> casters = shadowCasterInstances(scene);
        const std::vector<Aabb> rsBounds = rotatedCasterBounds(scene, casters, rotation);
        const CascadeLightView view = fitCascadeLightView(rotation, spheres[cascade], 512);
        const std::vector<Aabb> receivers = shadowReceiverBounds(scene);
        return cullTileCasters(scene, casters, rsBounds, view, spheres, cascade, BlendCulling{factor, &receivers});
    }
};

}  // namespace

TEST(CasterCulling, KeepsACasterInsideTheBox) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {1, 0, 1}, {2, 1, 2});
    EXPECT_TRUE(contains(f.cull(0, 0.0f).instances, box));
}

TEST(CasterCulling, ExcludesACasterOutsideTheBox) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {6, 0, 0}, {7, 1, 1});  // beyond x = 5 of cascade 0
    EXPECT_FALSE(contains(f.cull(0, 0.0f).instances, box));
    EXPECT_TRUE(contains(f.cull(1, 0.0f).instances, box));
}

TEST(CasterCulling, KeepsACasterFarTowardTheLight) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {0, 500, 0}, {1, 501, 1});  // high above, off-screen
    const TileCasters casters = f.cull(0, 0.0f);
    EXPECT_TRUE(contains(casters.instances, box));
    EXPECT_NEAR(casters.lsMaxZ, 501.0f, 0.01f);
}

TEST(CasterCulling, ExcludesACasterBeyondTheFarSideOfTheSphere) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {0, -9, 0}, {1, -6, 1});  // below sphere 0 (radius 5)
    EXPECT_FALSE(contains(f.cull(0, 0.0f).instances, box));
}

TEST(CasterCulling, ExcludesNonCastingInstancesAndShadowsOffMaterials) {
    CullingFixture f;
    const uint32_t noCast = addBox(f.scene, {0, 0, 0}, {1, 1, 1}, /*castShadows=*/false);
    const uint32_t off = addBox(f.scene, {0, 0, 0}, {1, 1, 1}, true, /*mesh with shadows Off=*/1);
    const uint32_t on = addBox(f.scene, {0, 0, 0}, {1, 1, 1});
    const std::vector<uint32_t> kept = f.cull(0, 0.0f).instances;
    EXPECT_FALSE(contains(kept, noCast));
    EXPECT_FALSE(contains(kept, off));
    EXPECT_TRUE(contains(kept, on));
}

TEST(CasterCulling, BlendCullingFactorIsPointEightMinusTheCascadeFade) {
    EXPECT_FLOAT_EQ(cascadeBlendCullingFactor(0.1f), 0.7f);
    EXPECT_FLOAT_EQ(cascadeBlendCullingFactor(0.9f), 0.0f);
}

TEST(CasterCulling, BlendCullingSkipsACasterInsideASmallerCascadeInBiggerOnes) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {0, 0, 0}, {1, 1, 1});  // within 0.7 x sphere 0 (3.5)
    EXPECT_TRUE(contains(f.cull(0, 0.7f).instances, box));
    const TileCasters bigger = f.cull(1, 0.7f);
    EXPECT_FALSE(contains(bigger.instances, box));
    EXPECT_EQ(bigger.skippedByBlendCulling, 1u);
}

TEST(CasterCulling, BlendCullingKeepsACasterInTheSmallerCascadesFadeBand) {
    CullingFixture f;
    const uint32_t box = addBox(f.scene, {3.8f, 0, 0}, {4.2f, 0.2f, 0.2f});  // beyond 0.7 x 5 = 3.5
    EXPECT_TRUE(contains(f.cull(1, 0.7f).instances, box));
    EXPECT_TRUE(contains(f.cull(1, 0.0f).instances, box));  // factor 0 culls nothing
}

TEST(CasterCulling, ShadowOnAFlatGroundIsTheCastersFootprintMovedAlongTheLight) {
    const Aabb post{{0, 0, 0}, {0.1f, 1, 0.1f}};
    const Aabb ground{{-50, -0.1f, -50}, {50, 0, 50}};
    const Aabb shadow = shadowOnReceiver(post, glm::normalize(glm::vec3(1, -0.5f, 0)), ground);
    ASSERT_TRUE(shadow.valid());
    EXPECT_NEAR(shadow.min.x, 0.0f, 1e-5f);
    EXPECT_NEAR(shadow.max.x, 0.1f + 2.2f, 1e-4f);  // the top of the post lands 2 m further, at y = -0.1
    EXPECT_NEAR(shadow.min.y, -0.1f, 1e-6f);
    EXPECT_NEAR(shadow.max.z, 0.1f, 1e-6f);
}

TEST(CasterCulling, ShadowMissesAReceiverTheSweepDoesNotMeet) {
    const Aabb box{{0, 1, 0}, {1, 2, 1}};
    EXPECT_FALSE(shadowOnReceiver(box, {0, -1, 0}, Aabb{{5, -1, 5}, {6, 0, 6}}).valid());  // beside it
    EXPECT_FALSE(shadowOnReceiver(box, {0, -1, 0}, Aabb{{0, 3, 0}, {1, 4, 1}}).valid());   // toward the light
}

TEST(CasterCulling, BlendCullingKeepsACasterWhoseShadowLeavesTheSmallerSphere) {
    CullingFixture f;
    f.rotation = lightRotationFromWorld(glm::normalize(glm::vec3(1, -0.2f, 0)));  // a low sun toward +X
    addBox(f.scene, {-30, -0.1f, -30}, {30, 0, 30});                       // ground, a receiver
    const uint32_t post = addBox(f.scene, {0, 0, 0}, {0.1f, 1, 0.1f});      // inside 0.7 x sphere 0
    EXPECT_TRUE(contains(f.cull(1, 0.7f).instances, post)) << "its 5 m shadow ends outside sphere 0";
}
