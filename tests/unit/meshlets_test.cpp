// Meshlets (scene/meshlets.h) and the tests that let a compute rasterizer skip one whole
// (shaders/meshlet_culling.glsl, compiled here as C++): the split keeps every triangle, and whatever a
// test skips would have drawn nothing, checked triangle by triangle on real meshes from many views.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "meshlet_culling.glsl"
#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "scene/meshlets.h"

using namespace penumbra;
namespace mc = penumbra::gpu_data::meshlet_culling;

namespace {

constexpr uint32_t kMaxTriangles = 128;

// A triangle as its vertex indices rotated to start at the smallest (winding kept).
std::array<uint32_t, 3> canonical(const uint32_t* t) {
    const int first = t[0] <= t[1] && t[0] <= t[2] ? 0 : (t[1] <= t[2] ? 1 : 2);
    return {t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
}

std::vector<std::array<uint32_t, 3>> sortedTriangles(const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> triangles;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) triangles.push_back(canonical(&indices[i]));
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

// The largest mesh of the CAD engine (tests/scenes/cad_engine.glb), many flat faces in many directions.
Mesh engineMesh() {
    const Scene scene = loadScene(std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/cad_engine.glb");
    const Mesh* largest = &scene.meshes.front();
    for (const Mesh& mesh : scene.meshes)
        if (mesh.indices.size() > largest->indices.size()) largest = &mesh;
    return *largest;
}

std::vector<Mesh> testMeshes() {
    return {makeSphereMesh(1.0f, 0, 96, 48), makeBoxMesh(glm::vec3(1.0f, 2.0f, 0.5f), 0), makeCylinderMesh(0.5f, 2.0f, 0, 64),
            engineMesh()};
}

glm::vec3 position(const Mesh& mesh, uint32_t index) { return mesh.vertices[index].osPosition; }

// The mesh's centre and the diagonal of its box.
std::pair<glm::vec3, float> centreAndSize(const Mesh& mesh) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Vertex& v : mesh.vertices) lo = glm::min(lo, v.osPosition), hi = glm::max(hi, v.osPosition);
    return {0.5f * (lo + hi), glm::length(hi - lo)};
}

}  // namespace

TEST(Meshlets, EveryTriangleIsKeptOnceWithItsWinding) {
    for (const Mesh& mesh : testMeshes()) {
        const MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
        ASSERT_EQ(split.indices.size(), mesh.indices.size());
        EXPECT_EQ(sortedTriangles(split.indices), sortedTriangles(mesh.indices));
    }
}

TEST(Meshlets, MeshletsAreConsecutiveRunsOfAtMostTheLimit) {
    for (const Mesh& mesh : testMeshes()) {
        const MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
        uint32_t next = 0;
        for (const Meshlet& meshlet : split.meshlets) {
            EXPECT_EQ(meshlet.firstTriangle, next);
            EXPECT_GT(meshlet.triangleCount, 0u);
            EXPECT_LE(meshlet.triangleCount, kMaxTriangles);
            next += meshlet.triangleCount;
        }
        EXPECT_EQ(size_t(next) * 3, split.indices.size());
    }
    // Full meshlets: a smooth mesh needs few more work items than triangles / kMaxTriangles.
    const MeshletMesh sphere = buildMeshlets(makeSphereMesh(1.0f, 0, 96, 48), kMaxTriangles);
    const double fill = double(sphere.indices.size() / 3) / double(sphere.meshlets.size() * kMaxTriangles);
    std::printf("sphere: %zu meshlets, %.1f %% full\n", sphere.meshlets.size(), 100.0 * fill);
    EXPECT_GT(fill, 0.75);
}

TEST(Meshlets, BoxesHoldTheirVertices) {
    for (const Mesh& mesh : testMeshes()) {
        const MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
        for (const Meshlet& meshlet : split.meshlets)
            for (uint32_t i = meshlet.firstTriangle * 3; i < (meshlet.firstTriangle + meshlet.triangleCount) * 3; ++i) {
                const glm::vec3 p = position(mesh, split.indices[i]);
                EXPECT_TRUE(glm::all(glm::lessThanEqual(meshlet.osMin, p)) && glm::all(glm::lessThanEqual(p, meshlet.osMax)));
            }
    }
}

TEST(Meshlets, DegenerateTrianglesGetMeshletsWithoutACone) {
    Mesh mesh = makeSphereMesh(1.0f, 0, 16, 8);
    mesh.indices.insert(mesh.indices.end(), {0, 0, 1, 2, 3, 3});
    const MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
    EXPECT_EQ(sortedTriangles(split.indices), sortedTriangles(mesh.indices));
    const Meshlet& last = split.meshlets.back();
    EXPECT_EQ(last.triangleCount, 2u);
    EXPECT_GE(last.coneCutoff, 1.0f);
}

// meshletFacesAway says yes only when every triangle faces away from the eye (dot(p - eye, n) >= 0,
// n by the counter-clockwise winding), and says it for a good share of the meshlets of a closed mesh.
TEST(MeshletCulling, ConeTestSkipsOnlyMeshletsWhoseEveryTriangleFacesAway) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    // testMeshes(): a smooth closed sphere turns almost half its meshlets away from an eye outside; a
    // box's or a cylinder's meshlet holds faces in every direction; the engine's flat faces point every
    // way within most meshlets, so few of its meshlets are skipped.
    const double least[] = {0.3, 0.0, 0.0, 0.03};
    const std::vector<Mesh> meshes = testMeshes();
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Mesh& mesh = meshes[m];
        const MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
        const auto [center, size] = centreAndSize(mesh);
        size_t skipped = 0, tested = 0;
        for (int view = 0; view < 64; ++view) {
            glm::vec3 direction(unit(random), unit(random), unit(random));
            if (glm::length(direction) < 0.1f) continue;
            const glm::vec3 eye = center + glm::normalize(direction) * size * (0.6f + 2.0f * std::abs(unit(random)));
            for (const Meshlet& meshlet : split.meshlets) {
                ++tested;
                if (!mc::meshletFacesAway(meshlet.coneApex, meshlet.coneAxis, meshlet.coneCutoff, eye))
                    continue;
                ++skipped;
                for (uint32_t t = meshlet.firstTriangle; t < meshlet.firstTriangle + meshlet.triangleCount; ++t) {
                    const glm::vec3 a = position(mesh, split.indices[t * 3]), b = position(mesh, split.indices[t * 3 + 1]),
                                    c = position(mesh, split.indices[t * 3 + 2]);
                    const glm::vec3 n = glm::cross(b - a, c - a);
                    ASSERT_GE(glm::dot(a - eye, n), -1e-6f * glm::length(n) * size) << "a skipped triangle faces the eye";
                }
            }
        }
        std::printf("%zu of %zu meshlets face away\n", skipped, tested);
        EXPECT_GE(double(skipped) / double(tested), least[m]) << "mesh " << m << ": the cone test skips too little";
    }
}

namespace {

// The engine mesh, its meshlets and its box's centre and size: what the view tests look at.
struct ViewedEngine {
    Mesh mesh;
    MeshletMesh split;
    glm::vec3 center;
    float size;
};
ViewedEngine viewedEngine() {
    Mesh mesh = engineMesh();
    MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
    const auto [center, size] = centreAndSize(mesh);
    return {std::move(mesh), std::move(split), center, size};
}

}  // namespace

// meshletBoxOutside says yes only when every triangle's vertices lie beyond one side of the clip
// volume; from cameras inside and around the mesh, part of the meshlets lie outside.
TEST(MeshletCulling, BoxTestSkipsOnlyMeshletsOutsideOneSide) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const auto [mesh, split, center, size] = viewedEngine();
    const uint32_t sides = mc::kMeshletSidesXY | mc::kMeshletSidesDepth;
    size_t skipped = 0, tested = 0;
    for (int view = 0; view < 64; ++view) {
        // Inside the mesh's box, looking at a part of it.
        const glm::vec3 eye = center + 0.4f * size * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec3 target = center + 0.4f * size * glm::vec3(unit(random), unit(random), unit(random));
        // Reversed Z, as the main view: near at z = w.
        glm::mat4 projection = glm::perspective(0.4f + 0.4f * std::abs(unit(random)), 1.6f, 0.02f * size, 0.5f * size);
        const glm::mat4 reverse(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 0, 1, 1));
        const glm::mat4 clipFromObject = reverse * projection * glm::lookAt(eye, target, glm::vec3(0, 1, 0));
        for (const Meshlet& meshlet : split.meshlets) {
            ++tested;
            if (!mc::meshletBoxOutside(clipFromObject, meshlet.osMin, meshlet.osMax, sides)) continue;
            ++skipped;
            for (uint32_t t = meshlet.firstTriangle; t < meshlet.firstTriangle + meshlet.triangleCount; ++t) {
                uint32_t common = sides;
                for (int i = 0; i < 3; ++i)
                    common &= mc::meshletOutcode(clipFromObject * glm::vec4(position(mesh, split.indices[t * 3 + i]), 1.0f), sides);
                ASSERT_NE(common, 0u) << "a skipped triangle reaches into the view";
            }
        }
    }
    std::printf("%zu of %zu meshlets outside the view\n", skipped, tested);
    EXPECT_GT(skipped, tested / 10);
    EXPECT_LT(skipped, tested);
}

// meshletBetweenTexelCentres says yes only when no triangle of the meshlet can cover a texel: each one's
// snapped window-space vertices (as the rasterizer's setup: 1/256 texel) hold no texel centre along x or
// along y. Orthographic views of the mesh whose texels are about its size, as a coarse virtual page sees
// small meshes: many meshlets lie between the centres.
TEST(MeshletCulling, BetweenTexelCentresSkipsOnlyMeshletsThatCoverNoTexel) {
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const auto [mesh, split, center, size] = viewedEngine();
    size_t skipped = 0, tested = 0;
    for (int view = 0; view < 64; ++view) {
        const glm::vec3 direction = glm::normalize(glm::vec3(unit(random), -1.0f, unit(random)));
        const float texel = size * (0.05f + 0.5f * std::abs(unit(random)));  // metres per texel
        const float half = 8.0f * texel;                                      // a 16-texel viewport
        const glm::vec3 offset = texel * glm::vec3(unit(random), unit(random), unit(random));
        const glm::mat4 clipFromObject = glm::ortho(-half, half, -half, half, -4.0f * size, 4.0f * size) *
                                         glm::lookAt(center + offset - 2.0f * size * direction, center + offset, glm::vec3(0, 0, 1));
        const glm::vec4 viewport(37.0f, 5.0f, 16.0f, 16.0f);
        for (const Meshlet& meshlet : split.meshlets) {
            ++tested;
            if (!mc::meshletBetweenTexelCentres(clipFromObject, meshlet.osMin, meshlet.osMax, viewport)) continue;
            ++skipped;
            for (uint32_t t = meshlet.firstTriangle; t < meshlet.firstTriangle + meshlet.triangleCount; ++t) {
                glm::vec2 lo(1e30f), hi(-1e30f);
                for (int i = 0; i < 3; ++i) {
                    const glm::vec4 c = clipFromObject * glm::vec4(position(mesh, split.indices[t * 3 + i]), 1.0f);
                    const glm::vec2 window = glm::vec2(viewport) + (glm::vec2(c) / c.w * 0.5f + 0.5f) * glm::vec2(viewport.z, viewport.w);
                    const glm::vec2 snapped = glm::round(window * 256.0f) / 256.0f;
                    lo = glm::min(lo, snapped);
                    hi = glm::max(hi, snapped);
                }
                const bool centreAlongX = std::ceil(lo.x - 0.5f) <= std::floor(hi.x - 0.5f);
                const bool centreAlongY = std::ceil(lo.y - 0.5f) <= std::floor(hi.y - 0.5f);
                ASSERT_FALSE(centreAlongX && centreAlongY) << "a skipped triangle's bounds hold a texel centre";
            }
        }
    }
    std::printf("%zu of %zu meshlets between texel centres\n", skipped, tested);
    EXPECT_GT(skipped, tested / 10);
    EXPECT_LT(skipped, tested);
}

TEST(MeshletCulling, ObjectEyeIsTheInverseTransformOfTheWorldEye) {
    const glm::mat4 worldFromObject = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3, -2, 5)), 0.7f,
                                                             glm::normalize(glm::vec3(1, 2, 3))),
                                                 glm::vec3(2.0f, 0.5f, 1.5f));
    const glm::vec3 osEye(0.3f, -1.2f, 2.5f);
    const glm::vec3 wsEye = glm::vec3(worldFromObject * glm::vec4(osEye, 1.0f));
    const glm::vec3 back = mc::meshletObjectEye(worldFromObject, wsEye);
    EXPECT_NEAR(glm::distance(back, osEye), 0.0f, 1e-4f);
}

// Shadow levels of detail (addShadowLods): each level keeps at most kLodKeepAtMost of the triangles of
// the one before, its error grows level by level, its meshlets hold exactly its triangles after the full
// mesh's, and the full mesh's part is what buildMeshlets made.
TEST(ShadowLods, EachLevelHasFewerTrianglesAndALargerErrorThanTheOneBefore) {
    for (const Mesh& mesh : {makeSphereMesh(1.0f, 0, 96, 48), makeCylinderMesh(0.5f, 2.0f, 0, 64), engineMesh()}) {
        const MeshletMesh full = buildMeshlets(mesh, kMaxTriangles);
        MeshletMesh split = full;
        addShadowLods(mesh, kMaxTriangles, 4, split);
        ASSERT_FALSE(split.lods.empty());
        EXPECT_EQ(split.fullIndexCount, mesh.indices.size());
        EXPECT_TRUE(std::equal(full.indices.begin(), full.indices.end(), split.indices.begin()));
        size_t previous = mesh.indices.size() / 3;
        float previousError = 0.0f;
        uint32_t nextMeshlet = uint32_t(full.meshlets.size()), nextTriangle = split.fullIndexCount / 3;
        for (const MeshletLod& lod : split.lods) {
            EXPECT_LE(float(lod.triangleCount), kLodKeepAtMost * float(previous));
            EXPECT_GT(lod.osError, previousError);
            EXPECT_EQ(lod.firstMeshlet, nextMeshlet);
            uint32_t triangles = 0;
            for (uint32_t m = lod.firstMeshlet; m < lod.firstMeshlet + lod.meshletCount; ++m) {
                EXPECT_EQ(split.meshlets[m].firstTriangle, nextTriangle);
                nextTriangle += split.meshlets[m].triangleCount;
                triangles += split.meshlets[m].triangleCount;
            }
            EXPECT_EQ(triangles, lod.triangleCount);
            nextMeshlet += lod.meshletCount;
            previous = lod.triangleCount;
            previousError = lod.osError;
        }
        EXPECT_EQ(nextMeshlet, split.meshlets.size());
        EXPECT_EQ(size_t(nextTriangle) * 3, split.indices.size());
        for (uint32_t index : split.indices) ASSERT_LT(index, mesh.vertices.size());
    }
}

// The error is what the shadow rasterizer trusts to pick a level: every vertex of the full sphere lies
// within it of the level's surface.
TEST(ShadowLods, TheFullMeshLiesWithinEachLevelsErrorOfItsSurface) {
    const Mesh mesh = makeSphereMesh(1.0f, 0, 96, 48);
    MeshletMesh split = buildMeshlets(mesh, kMaxTriangles);
    addShadowLods(mesh, kMaxTriangles, 4, split);
    auto pointTriangle = [](glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {  // distance, Ericson 5.1.5
        const glm::vec3 ab = b - a, ac = c - a, n = glm::cross(ab, ac);
        const float area2 = glm::dot(n, n);
        if (area2 > 0.0f) {
            const glm::vec3 q = p - glm::dot(p - a, n) / area2 * n;  // p projected onto the plane
            const float u = glm::dot(glm::cross(c - b, q - b), n), v = glm::dot(glm::cross(a - c, q - c), n),
                        w = glm::dot(glm::cross(b - a, q - a), n);
            if (u >= 0.0f && v >= 0.0f && w >= 0.0f) return glm::distance(p, q);
        }
        auto segment = [&](glm::vec3 s, glm::vec3 e) {
            const float t = glm::clamp(glm::dot(p - s, e - s) / std::max(glm::dot(e - s, e - s), 1e-20f), 0.0f, 1.0f);
            return glm::distance(p, s + t * (e - s));
        };
        return std::min({segment(a, b), segment(b, c), segment(c, a)});
    };
    for (const MeshletLod& lod : split.lods) {
        const uint32_t first = split.meshlets[lod.firstMeshlet].firstTriangle;
        float farthest = 0.0f;
        for (const Vertex& vertex : mesh.vertices) {
            float nearest = 1e30f;
            for (uint32_t t = first; t < first + lod.triangleCount; ++t)
                nearest = std::min(nearest, pointTriangle(vertex.osPosition, position(mesh, split.indices[t * 3]),
                                                          position(mesh, split.indices[t * 3 + 1]),
                                                          position(mesh, split.indices[t * 3 + 2])));
            farthest = std::max(farthest, nearest);
        }
        std::printf("level of %u triangles: error %.4f, farthest vertex %.4f\n", lod.triangleCount, lod.osError, farthest);
        EXPECT_LE(farthest, lod.osError * 1.01f + 1e-5f);
    }
}

TEST(ShadowLods, AMeshOfOneMeshletHasNone) {
    const Mesh box = makeBoxMesh(glm::vec3(1.0f), 0);
    MeshletMesh split = buildMeshlets(box, kMaxTriangles);
    addShadowLods(box, kMaxTriangles, 4, split);
    EXPECT_TRUE(split.lods.empty());
    EXPECT_EQ(split.indices.size(), box.indices.size());
}
