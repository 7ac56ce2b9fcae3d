// Receiver culling of cascade casters (shadows/caster_culling.h ReceiverVolume): a caster is left out of
// a cascade only when its shadow, grown by the lit pass's lookup reach, cannot land where a receiver
// that samples the cascade can be.
#include <algorithm>

#include <gtest/gtest.h>

#include "shadow_test_scene.h"
#include "shadows/caster_culling.h"
#include "shadows/shadow_gpu_packing.h"
#include "shadows/visible_surfaces.h"

using namespace penumbra;
using namespace penumbra::shadow_test;

namespace {

bool contains(const std::vector<uint32_t>& list, uint32_t value) {
    return std::find(list.begin(), list.end(), value) != list.end();
}

// A camera 10 m above the origin looking straight down (-y), 16:9, 60° vertical field: it sees the ground
// y = 0 over |x| <= 10.26, |z| <= 5.77.
CameraView downwardCamera() { return cameraLookingAt({0, 10, 0}, {0, 0, 0}, 1000.0f, 160, 90); }
constexpr float kHalfWidth = 10.264f;  // 10 tan(30°) 16/9

const Aabb kGround{{-100, -0.01f, -100}, {100, 0, 100}};  // thin: the view widens with depth
const glm::vec3 kStraightDown{0, -1, 0};

}  // namespace

TEST(ReceiverCulling, TheCameraVolumeHoldsWhatTheCameraSees) {
    const ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    ASSERT_TRUE(volume.valid);
    EXPECT_TRUE(boxMeetsReceiverVolume({{-0.1f, -0.1f, -0.1f}, {0.1f, 0.1f, 0.1f}}, volume));
    EXPECT_TRUE(boxMeetsReceiverVolume({{kHalfWidth - 0.05f, 0, 0}, {kHalfWidth - 0.01f, 0, 0}}, volume));
    EXPECT_FALSE(boxMeetsReceiverVolume({{kHalfWidth + 0.01f, 0, 0}, {kHalfWidth + 0.05f, 0, 0}}, volume));
    EXPECT_FALSE(boxMeetsReceiverVolume({{-1, 11, -1}, {1, 12, 1}}, volume));  // behind the camera
    // The view depth plane measures depth along the view: the ground lies 10 m deep.
    const glm::vec3 ground(3, 0, 2);
    EXPECT_NEAR(glm::dot(glm::vec3(volume.wsDepthPlane), ground) + volume.wsDepthPlane.w, 10.0f, 1e-4f);
}

TEST(ReceiverCulling, ADepthRangeAndASphereNarrowTheVolume) {
    ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    const Aabb groundPatch{{-1, -0.01f, -1}, {1, 0, 1}};  // 10 to 10.01 m deep
    volume.vsDepthRange = {10.02f, 20.0f};
    EXPECT_FALSE(boxMeetsReceiverVolume(groundPatch, volume));
    volume.vsDepthRange = {5.0f, 9.995f};
    EXPECT_FALSE(boxMeetsReceiverVolume(groundPatch, volume));
    volume.vsDepthRange = {10.005f, 20.0f};
    EXPECT_TRUE(boxMeetsReceiverVolume(groundPatch, volume));
    volume.vsDepthRange = {-kAnyDepth, kAnyDepth};
    volume.wsSphere = glm::vec4(5, 0, 0, 3.9f);
    EXPECT_FALSE(boxMeetsReceiverVolume(groundPatch, volume));
    volume.wsSphere.w = 4.1f;
    EXPECT_TRUE(boxMeetsReceiverVolume(groundPatch, volume));
}

TEST(ReceiverCulling, SkipsACasterWhoseShadowFallsOutsideTheView) {
    const ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    const Aabb outside{{kHalfWidth + 1, 0, -1}, {kHalfWidth + 2, 1, 1}};
    EXPECT_FALSE(shadowMeetsReceiverVolume(outside, 0.1f, kStraightDown, kGround, volume));
    // Casters above the camera (behind its near plane, toward the light) shade the ground in view.
    const Aabb overhead{{-1, 20, -1}, {1, 21, 1}};
    EXPECT_TRUE(shadowMeetsReceiverVolume(overhead, 0.1f, kStraightDown, kGround, volume));
}

TEST(ReceiverCulling, KeepsACasterOutsideTheViewWhoseShadowReachesIntoIt) {
    const ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    const Aabb pole{{kHalfWidth + 1, 0, -0.1f}, {kHalfWidth + 1.2f, 4, 0.1f}};
    const glm::vec3 lowSun = glm::normalize(glm::vec3(-1, -0.5f, 0));  // the pole's 8 m shadow runs toward -x
    EXPECT_TRUE(shadowMeetsReceiverVolume(pole, 0.1f, lowSun, kGround, volume));
    EXPECT_FALSE(shadowMeetsReceiverVolume(pole, 0.1f, kStraightDown, kGround, volume));
}

// A receiver at the view's edge filters texels up to the reach beyond it: a shadow ending 5 cm outside the
// view still darkens it, so a reach of 10 cm keeps the caster and none would lose it.
TEST(ReceiverCulling, KeepsACasterWhoseShadowEndsWithinTheLookupReachOfTheView) {
    const ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    const Aabb justOutside{{kHalfWidth + 0.05f, 0, -1}, {kHalfWidth + 1, 1, 1}};
    EXPECT_TRUE(shadowMeetsReceiverVolume(justOutside, 0.1f, kStraightDown, kGround, volume));
    EXPECT_FALSE(shadowMeetsReceiverVolume(justOutside, 0.0f, kStraightDown, kGround, volume));
}

TEST(ReceiverCulling, ACasterWhoseShadowMissesEveryReceiverIsSkipped) {
    const ReceiverVolume volume = cameraReceiverVolume(downwardCamera());
    const Aabb besideTheGround{{200, 0, 0}, {201, 1, 1}};  // in view of nothing: the ground ends at x = 100
    EXPECT_FALSE(shadowMeetsReceiverVolume(besideTheGround, 0.1f, kStraightDown, kGround, volume));
}

// The planner: a box beside the view whose shadow stays beside it is in no cascade's list with receiver
// culling on, and in some with it off (the sphere fit's squares reach far past the view's sides; the
// tight fit's hug it, and TightCascadesReachOnlyTheirSliceOfViewDepth checks their volumes); the box in
// view is in both.
TEST(ReceiverCulling, ThePlannerSkipsCastersWhoseShadowTheCameraCannotSee) {
    Scene scene = baseScene();
    addBox(scene, {-50, -1, -50}, {50, 0, 50});
    const uint32_t inView = addBox(scene, {-1, 0, -6}, {1, 2, -4});
    const uint32_t beside = addBox(scene, {13, 0, -21}, {14, 1, -20});  // the view is 11.5 m wide each side at 20 m
    addDirectionalLight(scene, {0.2f, -1, 0.1f});
    const CameraView camera = cameraLookingAt({0, 3, 0}, {0, 0, -10});
    ShadowSettings settings = sphereCascadeSettings();
    settings.maxDistance = 30.0f;
    const ShadowFrame culled = ShadowPlanner::plan(scene, camera, settings);
    settings.directional.receiverCulling = false;
    const ShadowFrame all = ShadowPlanner::plan(scene, camera, settings);
    bool besideListed = false, besideListedWithout = false, inViewListed = false;
    for (const ShadowTile& tile : culled.directional.tiles) {
        besideListed |= contains(tile.casterInstances, beside);
        inViewListed |= contains(tile.casterInstances, inView);
    }
    for (const ShadowTile& tile : all.directional.tiles) besideListedWithout |= contains(tile.casterInstances, beside);
    EXPECT_FALSE(besideListed);
    EXPECT_TRUE(besideListedWithout) << "the test scene must put the box in a cascade's square";
    EXPECT_TRUE(inViewListed);
    EXPECT_GT(culled.stats.skippedByReceiverCulling, 0u);
    EXPECT_EQ(all.stats.skippedByReceiverCulling, 0u);
}

// Tight cascades are chosen by view depth: each tile's volume spans its slice, reaching back over the
// previous cascade's blend band, and a shadow in the first slice (short of its band) reaches no later one.
TEST(ReceiverCulling, TightCascadesReachOnlyTheirSliceOfViewDepth) {
    Scene scene = baseScene();
    addBox(scene, {-50, -1, -50}, {50, 0, 50});
    addDirectionalLight(scene, {0.0f, -1, 0.05f});
    const CameraView camera = cameraLookingAt({0, 3, 0}, {0, 0, -10});
    const VisibleSurfaces visible = visibleSurfacesFromDepth(groundDepth(camera), camera);
    ShadowSettings settings;  // tight fit, log splits, 4 cascades
    settings.maxDistance = 30.0f;
    const ShadowFrame frame = ShadowPlanner::plan(scene, camera, settings, &visible);
    ASSERT_TRUE(frame.directional.tight);
    ASSERT_EQ(frame.directional.tiles.size(), 4u);
    const float fade = settings.directional.cascadeFade;
    for (uint32_t i = 0; i < 4; ++i) {
        const ReceiverVolume& volume = frame.directional.tiles[i].receiverVolume;
        const CascadeSphere& slice = frame.directional.cascades[i];
        EXPECT_FLOAT_EQ(volume.vsDepthRange.x, i == 0 ? -kAnyDepth : slice.vsNear * (1.0f - fade)) << i;
        EXPECT_FLOAT_EQ(volume.vsDepthRange.y, slice.vsFar) << i;
        EXPECT_LT(volume.wsSphere.w, 0.0f) << "no sphere: tight cascades are not chosen by sphere";
    }
    const float firstBand = frame.directional.cascades[0].vsFar * (1.0f - fade);
    const Aabb box{{-0.1f, 0, -0.5f * firstBand - 0.1f}, {0.1f, 0.2f, -0.5f * firstBand + 0.1f}};
    const Aabb ground{{-50, -1, -50}, {50, 0, 50}};
    const glm::vec3 light = glm::normalize(glm::vec3(0.0f, -1, 0.05f));
    const float reach = frame.directional.tiles[1].wsReceiverReach;
    EXPECT_TRUE(shadowMeetsReceiverVolume(box, reach, light, ground, frame.directional.tiles[0].receiverVolume));
    EXPECT_FALSE(shadowMeetsReceiverVolume(box, reach, light, ground, frame.directional.tiles[1].receiverVolume));
}

// Each cascade's reach is the lit pass's lookup reach at its own texel size.
TEST(ReceiverCulling, EachCascadeReachesAsFarAsItsLookups) {
    const ShadowFrame frame = groundAndBoxPlan(4);
    ASSERT_EQ(frame.directional.tiles.size(), 4u);
    const ReservedDirectionalLight& light = frame.directional.lights[0];
    for (const ShadowTile& tile : frame.directional.tiles) {
        EXPECT_TRUE(tile.receiverVolume.valid);
        const float texels = lookupReachTexels(light.normalBias, light.pcssTanRadius > 0.0f, ShadowSettings{}.directional.filter);
        EXPECT_FLOAT_EQ(tile.wsReceiverReach, tile.wsTexelSize * texels);
    }
}
