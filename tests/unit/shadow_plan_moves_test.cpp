// ShadowPlanWorkspace::instanceMoved: a moved instance keeps the workspace's caster list and the
// receivers' union exact without a walk over the instances where it can (the cost of an edit follows
// what changed), and asks the next plan for a walk where it cannot. Every plan here must equal a
// fresh plan of the same scene.
#include <gtest/gtest.h>

#include "scene/scene_edits.h"
#include "shadow_test_scene.h"
#include "shadows/caster_culling.h"
#include "shadows/shadow_planner.h"
#include "spot_test_scenes.h"

using namespace penumbra;

namespace {

// A 40 m ground (y = 0) and 4 boxes 0.8 m tall at y 0.6 .. 1.4 (the receivers' top), a sun.
struct MovesFixture {
    Scene scene = test::spotGridScene(4, LightShadows::None);
    CameraView camera;
    ShadowSettings settings = shadow_test::sphereCascadeSettings();
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    PlanOptions options;

    MovesFixture() {
        shadow_test::addDirectionalLight(scene, {0.3f, -1.0f, 0.2f});
        camera = resolveCameraView(scene, 96, 54);
        options.sceneVersion = 1;  // the renderer's moves do not change it
        plan();
    }
    void plan() { ShadowPlanner::plan(scene, camera, settings, nullptr, options, frame, workspace); }
    // Moves the box `instance` to `wsCentre` and reports it as the renderer does.
    void move(uint32_t instance, glm::vec3 wsCentre) {
        const Aabb wsOld = scene.instances[instance].wsBounds;
        glm::mat4 transform(1.0f);
        transform[3] = glm::vec4(wsCentre, 1.0f);
        setInstanceWorldTransform(scene, instance, transform);
        workspace.instanceMoved(scene, instance, wsOld);
    }
    void expectFreshPlan() {
        const ShadowFrame fresh = ShadowPlanner::plan(scene, camera, settings);
        EXPECT_EQ(frame.directional.wsReceiverBounds.min, fresh.directional.wsReceiverBounds.min);
        EXPECT_EQ(frame.directional.wsReceiverBounds.max, fresh.directional.wsReceiverBounds.max);
        EXPECT_EQ(frame.stats.shadowCasters, fresh.stats.shadowCasters);
    }
};

}  // namespace

TEST(ShadowPlanMoves, AMoveInsideTheReceiversKeepsTheWorkspaceWithoutAWalk) {
    MovesFixture f;
    f.move(1, {3.0f, 1.0f, 2.0f});  // top still at 1.4, well inside the ground's x and z
    EXPECT_EQ(f.workspace.sceneVersion, 1u) << "no walk asked for";
    f.plan();
    f.expectFreshPlan();
}

TEST(ShadowPlanMoves, AMoveBeyondTheReceiversGrowsTheirUnionWithoutAWalk) {
    MovesFixture f;
    f.move(2, {0.0f, 5.0f, 0.0f});  // its top at 5.4, above every other receiver
    EXPECT_EQ(f.workspace.sceneVersion, 1u);
    EXPECT_FLOAT_EQ(f.workspace.wsReceiverBounds.max.y, 5.4f);
    f.plan();
    f.expectFreshPlan();
}

TEST(ShadowPlanMoves, AMoveAwayFromAFaceOfTheUnionItAloneReachedAsksForAWalk) {
    MovesFixture f;
    f.move(2, {0.0f, 5.0f, 0.0f});
    f.plan();
    f.move(2, {0.0f, 1.0f, 0.0f});  // back down: the union's top may fall to 1.4, which only a walk finds
    EXPECT_EQ(f.workspace.sceneVersion, 0u);
    f.plan();
    EXPECT_FLOAT_EQ(f.workspace.wsReceiverBounds.max.y, 1.4f);
    f.expectFreshPlan();
}

TEST(ShadowPlanMoves, BoundsThatBecomeInvalidAskForAWalk) {
    MovesFixture f;
    const Aabb wsOld = f.scene.instances[3].wsBounds;
    f.scene.instances[3].wsBounds = Aabb{};  // as a transform that leaves no valid bounds does
    f.workspace.instanceMoved(f.scene, 3, wsOld);
    EXPECT_EQ(f.workspace.sceneVersion, 0u) << "it leaves the casters and the receivers";
    f.plan();
    f.expectFreshPlan();
}

// The spot lights' reservation follows moves too (its answers are kept while nothing moves): the
// light whose only caster moved out of its cone has no tile in the next plan, as a fresh plan has it.
TEST(ShadowPlanMoves, ASpotLightWhoseOnlyCasterMovedAwayLosesItsTileInTheNextPlan) {
    Scene scene = test::spotGridScene(1);
    scene.instances[0].castShadows = false;  // the ground: the box is the light's only caster
    const CameraView camera = resolveCameraView(scene, 96, 54);
    const ShadowSettings settings = shadow_test::sphereCascadeSettings();
    PlanOptions options;
    options.sceneVersion = 1;
    ShadowFrame frame;
    ShadowPlanWorkspace workspace;
    ShadowPlanner::plan(scene, camera, settings, nullptr, options, frame, workspace);
    ASSERT_EQ(frame.other.lights.size(), 1u);
    ShadowPlanner::plan(scene, camera, settings, nullptr, options, frame, workspace);
    EXPECT_EQ(workspace.reservation.casterWalks, 0u) << "nothing moved: the answer stands";
    const Aabb wsOld = scene.instances[1].wsBounds;
    glm::mat4 transform(1.0f);
    transform[3] = glm::vec4(15.0f, 1.0f, 0.0f, 1.0f);
    setInstanceWorldTransform(scene, 1, transform);
    workspace.instanceMoved(scene, 1, wsOld);
    ShadowPlanner::plan(scene, camera, settings, nullptr, options, frame, workspace);
    EXPECT_TRUE(frame.other.lights.empty());
    EXPECT_EQ(ShadowPlanner::plan(scene, camera, settings).other.lights.size(), 0u);
}
