// The viewer's frusta view (src/viewer/cascade_frusta.h): the cascades' boxes and culling spheres read
// from a real plan's stats JSON, the lines made of them, and their projection into an outside camera.
#include <cmath>

#include <gtest/gtest.h>

#include "render/shadow_stats_json.h"
#include "shadow_test_scene.h"
#include "shadows/shadow_planner.h"
#include "viewer/cascade_frusta.h"

using namespace penumbra;
using namespace penumbra::shadow_test;
using namespace penumbra::viewer;

namespace {

struct PlannedCascades {
    Scene scene = baseScene();
    CameraView camera = cameraLookingAt({0, 6, 15}, {0, 0, 0});
    ShadowSettings settings = sphereCascadeSettings();
    ShadowFrame plan;

    PlannedCascades() {
        settings.maxDistance = 40.0f;
        addBox(scene, {-20, -1, -20}, {20, 0, 20});
        addDirectionalLight(scene, {0.3f, -1, 0.2f});
        plan = ShadowPlanner::plan(scene, camera, settings);
    }
};

}  // namespace

TEST(CascadeFrusta, StatsJsonGivesThePlansSpheresAndTileBoxes) {
    PlannedCascades p;
    const CascadeGeometry geometry = cascadeGeometry(shadowPlanStats(p.plan));
    ASSERT_EQ(geometry.wsCullingSpheres.size(), p.plan.directional.cascades.size());
    ASSERT_EQ(geometry.boxes.size(), p.plan.directional.tiles.size());
    ASSERT_EQ(geometry.boxes.size(), 4u);
    for (size_t i = 0; i < geometry.wsCullingSpheres.size(); ++i) {
        const CascadeSphere& sphere = p.plan.directional.cascades[i];
        EXPECT_NEAR(glm::distance(glm::vec3(geometry.wsCullingSpheres[i]), sphere.wsCenter), 0.0f, 1e-4f);
        EXPECT_FLOAT_EQ(geometry.wsCullingSpheres[i].w, sphere.radius);
    }
    for (size_t i = 0; i < geometry.boxes.size(); ++i) {
        const ShadowTile& tile = p.plan.directional.tiles[i];
        EXPECT_EQ(geometry.boxes[i].cascade, tile.cascadeIndex);
        // A clip-cube corner taken to world space and back by the tile's own matrix.
        const glm::vec4 ws = geometry.boxes[i].worldFromClip * glm::vec4(1, -1, 1, 1);
        const glm::vec4 clip = tile.clipFromWorld * (ws / ws.w);
        EXPECT_NEAR(clip.x / clip.w, 1.0f, 1e-3f);
        EXPECT_NEAR(clip.y / clip.w, -1.0f, 1e-3f);
        EXPECT_NEAR(clip.z / clip.w, 1.0f, 1e-3f);
    }
    EXPECT_FLOAT_EQ(geometry.shadowDistance, p.plan.directional.cascades.back().vsFar);
    EXPECT_TRUE(cascadeGeometry(ShadowPlanStats{}).boxes.empty());
}

TEST(CascadeFrusta, LinesAreTheBoxesEdgesTheSpheresCirclesAndTheObservedFrustum) {
    PlannedCascades p;
    const CascadeGeometry geometry = cascadeGeometry(shadowPlanStats(p.plan));
    const std::vector<WorldLine> lines = cascadeLines(geometry, p.camera);
    size_t boxes = 0, spheres = 0, frustum = 0;
    for (const WorldLine& line : lines) {
        boxes += line.kind == LineKind::Box;
        frustum += line.kind == LineKind::ObservedFrustum;
        if (line.kind != LineKind::Sphere) continue;
        ++spheres;
        const glm::vec4& sphere = geometry.wsCullingSpheres[line.cascade];
        EXPECT_NEAR(glm::distance(line.wsFrom, glm::vec3(sphere)), sphere.w, 1e-3f * sphere.w);
    }
    EXPECT_EQ(boxes, 12 * geometry.boxes.size());
    EXPECT_EQ(spheres, 3 * kSphereSegments * geometry.wsCullingSpheres.size());
    EXPECT_EQ(frustum, 12u);
    // The observed frustum's far corners lie at the shadow distance along the view axis.
    for (const WorldLine& line : lines)
        if (line.kind == LineKind::ObservedFrustum) {
            const float depth = -(p.camera.viewFromWorld * glm::vec4(line.wsTo, 1.0f)).z;
            EXPECT_TRUE(std::abs(depth - p.camera.zNear) < 1e-3f || std::abs(depth - geometry.shadowDistance) < 1e-2f) << depth;
        }
}

TEST(CascadeFrusta, ProjectionClipsAtTheNearPlane) {
    const CameraView view = cameraLookingAt({0, 0, 10}, {0, 0, 0}, 100.0f, 64, 32);
    const auto centre = projectToPixels(view, {0, 0, 0}, {0, 0, -5});
    ASSERT_TRUE(centre.has_value());
    EXPECT_NEAR(centre->first.x, 32.0f, 1e-3f);
    EXPECT_NEAR(centre->first.y, 16.0f, 1e-3f);
    // Up in the world is up in the image (pixel y grows downwards).
    EXPECT_LT(projectToPixels(view, {0, 1, 0}, {0, 0, 0})->first.y, 16.0f);
    EXPECT_FALSE(projectToPixels(view, {0, 0, 12}, {1, 0, 15}).has_value()) << "wholly behind the camera";
    // From in front to behind: the end is moved to the near plane, so it stays finite.
    const auto crossing = projectToPixels(view, {0.1f, 0, 0}, {0.1f, 0, 20});
    ASSERT_TRUE(crossing.has_value());
    EXPECT_TRUE(std::isfinite(crossing->second.x) && std::isfinite(crossing->second.y));
    EXPECT_GT(crossing->second.x, crossing->first.x);
}

TEST(CascadeFrusta, OutsideCameraSeesTheObservedCameraAndWhatItLooksAt) {
    PlannedCascades p;
    Camera observed;
    observed.worldFromView = p.camera.worldFromView;
    observed.yfov = p.camera.yfov;
    const Camera outside = outsideCamera(observed, 40.0f);
    const CameraView view = makeCameraView(outside, 160, 90);
    const glm::vec3 wsForward = -glm::vec3(observed.worldFromView[2]);
    for (const glm::vec3& wsPoint : {p.camera.wsPosition, p.camera.wsPosition + 20.0f * wsForward,
                                     p.camera.wsPosition + 40.0f * wsForward}) {
        const auto pixel = projectToPixels(view, wsPoint, wsPoint);
        ASSERT_TRUE(pixel.has_value());
        EXPECT_GT(pixel->first.x, 0.0f);
        EXPECT_LT(pixel->first.x, 160.0f);
        EXPECT_GT(pixel->first.y, 0.0f);
        EXPECT_LT(pixel->first.y, 90.0f);
    }
}
