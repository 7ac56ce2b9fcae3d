// Simplified levels of shadow casters (shadows.lodErrorTexels, scene/meshlets.h addShadowLods): the
// compute rasterizer draws a caster far from the camera, in a coarse cascade or page, with a
// simplified level of its mesh whose error is a fraction of that tile's texel. What it draws changes;
// the shadow may change only where a texel's coverage does: the shadow term of frames with and without
// is compared by its lit / shadowed class (a tolerance stated per test), and the work items that drew
// a simplified level are counted by the stats.
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "render_test_support.h"

namespace penumbra::test {
namespace {

constexpr uint32_t kWidth = 160, kHeight = 90;

// A field of finely tessellated spheres (9216 triangles, 72 meshlets each) on a ground plane under
// the sun, the camera high above it: the far spheres fall into coarse cascades or pages.
Scene sphereField(MaterialShadowMode shadowMode = MaterialShadowMode::On) {
    SceneBuilder builder;
    Material white;
    white.metallic = 0.0f;
    white.shadows = shadowMode;
    if (shadowMode == MaterialShadowMode::Clip) white.alphaMode = AlphaMode::Mask;
    const uint32_t material = builder.addMaterial(white);
    const uint32_t sphere = builder.addMesh(makeSphereMesh(1.0f, material, 96, 48));
    const uint32_t ground = builder.addMesh(makePlaneMesh({120.0f, 120.0f}, material));
    for (int x = -4; x <= 4; ++x)
        for (int z = -4; z <= 4; ++z)
            builder.addInstance(sphere, glm::translate(glm::mat4(1.0f), {8.0f * float(x), 1.0f, 8.0f * float(z)}));
    builder.addInstance(ground, glm::mat4(1.0f));
    builder.addLight(makeDirectionalLight({-0.4f, -1.0f, -0.3f}, 3.0f));
    builder.setCamera(makeLookAtCamera({0.0f, 14.0f, 40.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
    return builder.build();
}

Settings computeSettings(DirectionalShadowMode mode, float lodErrorTexels) {
    Settings settings;
    settings.shadows.raster = ShadowRaster::Compute;
    settings.shadows.directional.mode = mode;
    settings.shadows.directional.atlasSize = 1024;
    settings.shadows.maxDistance = 80.0f;
    settings.shadows.lodErrorTexels = lodErrorTexels;
    return settings;
}

RenderRequest shadowRequest() { return {kWidth, kHeight, OutputMode::ShadowAov, 0, false}; }

class ShadowLodTest : public RenderTest {
protected:
    // A first frame of its own renderer: every setting starts from the same fit and an empty cache.
    RenderResult firstFrame(const Scene& scene, DirectionalShadowMode mode, float lodErrorTexels) {
        Renderer renderer(device(), scene);
        return renderer.render(shadowRequest(), computeSettings(mode, lodErrorTexels));
    }
};

// Both directional modes: the far spheres' items draw simplified levels, and the shadow term differs
// from full meshes' on at most 0.3 % of the pixels (a class flip: more than half the range).
TEST_F(ShadowLodTest, FarCastersDrawSimplifiedLevelsAndTheShadowKeepsItsClass) {
    const Scene scene = sphereField();
    for (DirectionalShadowMode mode : {DirectionalShadowMode::Cascades, DirectionalShadowMode::Virtual}) {
        const RenderResult full = firstFrame(scene, mode, 0.0f);
        const RenderResult simplified = firstFrame(scene, mode, 0.5f);
        const char* name = mode == DirectionalShadowMode::Virtual ? "virtual" : "cascades";
        std::printf("%s: %llu of %llu work items simplified (full meshes: %llu items)\n", name,
                    (unsigned long long)simplified.stats.rasterSimplifiedItems,
                    (unsigned long long)simplified.stats.rasterWorkItems, (unsigned long long)full.stats.rasterWorkItems);
        EXPECT_EQ(full.stats.rasterSimplifiedItems, 0u) << name;
        EXPECT_GT(simplified.stats.rasterSimplifiedItems, 0u) << name;
        EXPECT_LE(shareOfPixelsOver(full.image, simplified.image, 127), 0.003) << name;
    }
}

// A larger error allows coarser levels: fewer meshlets, so fewer work items (two meshlets each), and
// the shadow stays within the tolerance above at 2 texels (4x the default).
TEST_F(ShadowLodTest, ALargerErrorDrawsCoarserLevels) {
    const Scene scene = sphereField();
    const DirectionalShadowMode mode = DirectionalShadowMode::Cascades;
    const RenderResult full = firstFrame(scene, mode, 0.0f), half = firstFrame(scene, mode, 0.5f), two = firstFrame(scene, mode, 2.0f);
    auto items = [](const RenderResult& r) { return (unsigned long long)r.stats.rasterWorkItems; };
    std::printf("work items: full %llu, 0.5 texels %llu, 2 texels %llu\n", items(full), items(half), items(two));
    EXPECT_LT(items(half), items(full));
    EXPECT_LT(items(two), items(half));
    EXPECT_LE(shareOfPixelsOver(full.image, two.image, 127), 0.003);
}

// Cached cascade tiles and virtual pages were drawn with the levels of the old setting: a new one
// draws them again in the next frame (an unchanged one would reuse them and draw nothing).
TEST_F(ShadowLodTest, ChangingTheErrorDrawsCachedTilesAndPagesAgain) {
    const Scene scene = sphereField();
    for (DirectionalShadowMode mode : {DirectionalShadowMode::Cascades, DirectionalShadowMode::Virtual}) {
        Renderer renderer(device(), scene);
        const char* name = mode == DirectionalShadowMode::Virtual ? "virtual" : "cascades";
        renderer.render(shadowRequest(), computeSettings(mode, 0.0f));
        const RenderResult cached = renderer.render(shadowRequest(), computeSettings(mode, 0.0f));
        EXPECT_EQ(cached.stats.rasterWorkItems, 0u) << name;
        const RenderResult changed = renderer.render(shadowRequest(), computeSettings(mode, 0.5f));
        EXPECT_GT(changed.stats.rasterSimplifiedItems, 0u) << name;
    }
}

// An alpha-tested caster's cut-outs follow its texture coordinates over the full mesh's triangles:
// it is never simplified.
TEST_F(ShadowLodTest, AlphaTestedCastersAreDrawnInFull) {
    Renderer renderer(device(), sphereField(MaterialShadowMode::Clip));
    const RenderResult clipped = renderer.render(shadowRequest(), computeSettings(DirectionalShadowMode::Cascades, 4.0f));
    EXPECT_GT(clipped.stats.rasterWorkItems, 0u);
    EXPECT_EQ(clipped.stats.rasterSimplifiedItems, 0u);
}

}  // namespace
}  // namespace penumbra::test
