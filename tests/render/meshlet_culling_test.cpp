// Meshlet culling of the compute rasterizers (render.meshletCulling): the visibility buffer
// skips meshlets outside the view and meshlets whose every triangle faces away from the camera, the
// compute shadow rasterizer meshlets outside their tile. Skipping changes what is drawn, never the
// image: frames with and without are compared pixel for pixel (both rasterizers keep the nearest
// depth by an atomic, whatever the order, so the tolerance is exact equality).
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "render_test_support.h"
#include "scene/canonical_scenes.h"
#include "scene/meshlets.h"
#include "cull_structs.h"

#include <vector>

namespace penumbra::test {
namespace {

constexpr int kSphereSegments = 96, kSphereRings = 48;

Settings computeSettings(bool meshletCulling) {
    Settings settings;
    settings.render.mainView = MainView::Visibility;
    settings.render.meshletCulling = meshletCulling;
    settings.shadows.raster = ShadowRaster::Compute;
    settings.shadows.directional.atlasSize = 512;  // lavapipe: keep the shadow passes small
    settings.shadows.spot.atlasSize = 512;
    return settings;
}

RenderRequest smallRequest() {
    RenderRequest request;
    request.width = 160;
    request.height = 90;
    return request;
}

// A finely tessellated sphere in front of the camera over a ground plane, lit by the sun; the
// sphere's material single- or double-sided, its instance mirrored (scale -1 in x) or not.
Scene sphereScene(bool doubleSided, bool mirrored) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    white.doubleSided = doubleSided;
    const uint32_t material = builder.addMaterial(white);
    const uint32_t sphere = builder.addMesh(makeSphereMesh(1.0f, material, kSphereSegments, kSphereRings));
    const uint32_t ground = builder.addMesh(makePlaneMesh({20.0f, 20.0f}, material));
    glm::mat4 place = glm::translate(glm::mat4(1.0f), {0.0f, 1.2f, 0.0f});
    if (mirrored) place = glm::scale(place, {-1.0f, 1.0f, 1.0f});
    builder.addInstance(sphere, place);
    builder.addInstance(ground, glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight({-0.3f, -1.0f, -0.4f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 2.0f, 5.0f}, {0.0f, 1.0f, 0.0f}, 0.9f));
    return builder.build();
}

size_t sphereMeshlets() {
    return buildMeshlets(makeSphereMesh(1.0f, 0, kSphereSegments, kSphereRings), gpu_data::kRasterBatch).meshlets.size();
}

class MeshletCullingTest : public RenderTest {};

TEST_F(MeshletCullingTest, ImagesEqualThoseWithoutMeshletCullingOnEveryCanonicalScene) {
    for (const CanonicalSceneInfo& info : canonicalScenes()) {
        const Scene scene = makeCanonicalScene(info.name);
        Renderer renderer(device(), scene);
        const RenderResult culled = renderer.render(smallRequest(), computeSettings(true));
        const RenderResult unculled = renderer.render(smallRequest(), computeSettings(false));
        ASSERT_EQ(culled.stats.mainView, "visibility") << info.name;
        ASSERT_EQ(culled.stats.shadowRaster, "compute") << info.name;
        EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0) << info.name;
        EXPECT_EQ(unculled.stats.viewMeshletsOutside + unculled.stats.viewMeshletsFacingAway +
                      unculled.stats.shadowMeshletsOutside, 0u) << info.name;
    }
}

TEST_F(MeshletCullingTest, MeshletsFacingAwayFromTheCameraAreSkipped) {
    const Scene scene = sphereScene(false, false);
    Renderer renderer(device(), scene);
    const RenderResult culled = renderer.render(smallRequest(), computeSettings(true));
    const RenderResult unculled = renderer.render(smallRequest(), computeSettings(false));
    // About half the sphere faces away; the meshlets on the silhouette hold both kinds.
    const double share = double(culled.stats.viewMeshletsFacingAway) / double(sphereMeshlets());
    std::printf("sphere meshlets facing away: %llu of %zu\n", (unsigned long long)culled.stats.viewMeshletsFacingAway,
                sphereMeshlets());
    EXPECT_GT(share, 0.25);
    EXPECT_LT(share, 0.6);
    EXPECT_EQ(unculled.stats.viewMeshletsFacingAway, 0u);
    EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0);
}

TEST_F(MeshletCullingTest, DoubleSidedMaterialsAndMirroredInstancesSkipNothingForFacing) {
    for (const auto& [doubleSided, mirrored] : {std::pair{true, false}, std::pair{false, true}}) {
        const Scene scene = sphereScene(doubleSided, mirrored);
        Renderer renderer(device(), scene);
        const RenderResult culled = renderer.render(smallRequest(), computeSettings(true));
        const RenderResult unculled = renderer.render(smallRequest(), computeSettings(false));
        EXPECT_EQ(culled.stats.viewMeshletsFacingAway, 0u) << "double-sided " << doubleSided << ", mirrored " << mirrored;
        EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0);
    }
}

// The camera close to the sphere sees part of it; the cascades' tiles hold parts of the ground's
// meshlets only (a 20 m plane of 2 triangles is one meshlet: the sphere's are what lie outside).
TEST_F(MeshletCullingTest, MeshletsOutsideTheViewAndOutsideShadowTilesAreSkipped) {
    const Scene scene = sphereScene(false, false);
    Renderer renderer(device(), scene);
    const CameraView close = makeCameraView(makeLookAtCamera({0.3f, 1.3f, 1.6f}, {0.6f, 1.0f, 0.0f}, 0.5f), 160, 90);
    Settings settings = computeSettings(true);
    settings.shadows.directional.cascadeCount = 4;
    settings.shadows.maxDistance = 30.0f;
    const RenderResult culled = renderer.render(smallRequest(), settings, close);
    settings.render.meshletCulling = false;
    const RenderResult unculled = renderer.render(smallRequest(), settings, close);
    std::printf("meshlets outside: view %llu, shadow tiles %llu\n", (unsigned long long)culled.stats.viewMeshletsOutside,
                (unsigned long long)culled.stats.shadowMeshletsOutside);
    EXPECT_GT(culled.stats.viewMeshletsOutside, sphereMeshlets() / 10);
    EXPECT_GT(culled.stats.shadowMeshletsOutside, 0u);
    EXPECT_EQ(unculled.stats.viewMeshletsOutside + unculled.stats.shadowMeshletsOutside, 0u);
    EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0);
}

// Seen from far away, the sphere's pages are of a level whose texels are wider than its meshlets: the
// meshlets that lie between the texel centres cover no texel and are skipped with those outside the
// page (279 of the 439 skipped here lie outside a page; meshletBetweenTexelCentres is checked triangle
// by triangle in tests/unit/meshlets_test.cpp); the image is the same. Full meshes: a simplified level
// of the far sphere (shadow_lod_test.cpp) has fewer, larger meshlets.
TEST_F(MeshletCullingTest, ShadowMeshletsBetweenTheTexelCentresOfACoarsePageAreSkippedWithoutChangingTheImage) {
    const Scene scene = sphereScene(false, false);
    Renderer renderer(device(), scene);
    const CameraView far = makeCameraView(makeLookAtCamera({120.0f, 150.0f, 160.0f}, {0.0f, 1.0f, 0.0f}, 0.5f), 160, 90);
    Settings settings = computeSettings(true);
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    settings.shadows.maxDistance = 400.0f;
    settings.shadows.lodErrorTexels = 0.0f;
    const RenderResult culled = renderer.render(smallRequest(), settings, far);
    settings.render.meshletCulling = false;
    const RenderResult unculled = renderer.render(smallRequest(), settings, far);
    std::printf("shadow meshlets skipped: %llu of the sphere's %zu\n", (unsigned long long)culled.stats.shadowMeshletsOutside,
                size_t(sphereMeshlets()));
    EXPECT_GT(culled.stats.shadowMeshletsOutside, 6 * sphereMeshlets());
    EXPECT_EQ(unculled.stats.shadowMeshletsOutside, 0u);
    EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0);
}

// Small one-meshlet objects are drawn several to a work item (packed): each instance's meshlet is still
// tested. Single-sided quads, 40 turned towards the camera and 40 away: 40 meshlets skipped, same image.
TEST_F(MeshletCullingTest, PackedSmallObjectsFacingAwayAreSkippedOneByOne) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    const uint32_t quad = builder.addMesh(makePlaneMesh({0.3f, 0.3f}, builder.addMaterial(white)));
    for (int i = 0; i < 80; ++i) {
        // Upright quads in a row across the view; the plane mesh faces +y, turned to face +z or -z.
        const float facing = i % 2 == 0 ? 1.0f : -1.0f;
        glm::mat4 place = glm::translate(glm::mat4(1.0f), {-4.0f + 0.1f * float(i), 1.0f, 0.0f});
        place = glm::rotate(place, facing * glm::half_pi<float>(), {1.0f, 0.0f, 0.0f});
        builder.addInstance(quad, place);
    }
    builder.addLight(makeDirectionalLight({-0.3f, -1.0f, -0.4f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 1.0f, 5.0f}, {0.0f, 1.0f, 0.0f}, 0.9f));
    Renderer renderer(device(), builder.build());
    const RenderResult culled = renderer.render(smallRequest(), computeSettings(true));
    const RenderResult unculled = renderer.render(smallRequest(), computeSettings(false));
    EXPECT_EQ(culled.stats.viewMeshletsFacingAway, 40u);
    EXPECT_EQ(unculled.stats.viewMeshletsFacingAway, 0u);
    EXPECT_EQ(shareOfPixelsOver(culled.image, unculled.image, 0), 0.0);
}

// The compute rasterizers' objects (both raster passes, the visibility buffer, the meshlets) go with
// their renderer: what the device holds afterwards is what it held before. (The asan preset's leak
// check leaves lavapipe's own allocations out, tests/lsan.supp; this is the check of ours.)
TEST_F(MeshletCullingTest, ARendererOfTheComputeRasterizersLeavesNoObjectBehind) {
    auto held = [&] {
        const DeviceObjectCounts c = device().liveObjects();
        return std::vector<uint32_t>{c.buffers, c.textures, c.samplers, c.pipelines, c.textureTables, c.pendingDestroys};
    };
    const std::vector<uint32_t> before = held();
    {
        Renderer renderer(device(), sphereScene(false, false));
        for (bool culling : {true, false}) renderer.render(smallRequest(), computeSettings(culling));
        EXPECT_NE(held(), before);
    }
    EXPECT_EQ(held(), before);
}

}  // namespace
}  // namespace penumbra::test
