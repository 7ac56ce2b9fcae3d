// TriangleGrid (scene/surface_distance.h): the nearest triangle's distance through the grid equals a
// search of every triangle, for points on, near and far from a mesh; and the closest-point function
// against points whose nearest feature (face, edge, vertex) is known.
#include <random>

#include <gtest/gtest.h>

#include "penumbra/scene_builder.h"
#include "scene/surface_distance.h"

using namespace penumbra;

namespace {

std::vector<glm::vec3> positionsOf(const Mesh& mesh) {
    std::vector<glm::vec3> positions;
    for (const Vertex& v : mesh.vertices) positions.push_back(v.osPosition);
    return positions;
}

}  // namespace

TEST(SurfaceDistance, PointTriangleDistanceToTheFaceAnEdgeAndAVertex) {
    const glm::vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    EXPECT_FLOAT_EQ(pointTriangleDistance({0.5f, 0.5f, 3.0f}, a, b, c), 3.0f);   // above the face
    EXPECT_FLOAT_EQ(pointTriangleDistance({1.0f, -2.0f, 0.0f}, a, b, c), 2.0f);  // beside edge ab
    EXPECT_FLOAT_EQ(pointTriangleDistance({-3.0f, -4.0f, 0.0f}, a, b, c), 5.0f); // beyond vertex a
    EXPECT_NEAR(pointTriangleDistance({2.0f, 2.0f, 0.0f}, a, b, c), std::sqrt(2.0f), 1e-6f);  // beside edge bc
}

TEST(SurfaceDistance, TheGridFindsTheNearestTriangleOfEverySearch) {
    const Mesh mesh = makeSphereMesh(1.0f, 0, 40, 20);
    const std::vector<glm::vec3> positions = positionsOf(mesh);
    const TriangleGrid grid(positions, mesh.indices);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 p(coordinate(random), coordinate(random), coordinate(random));
        float nearest = INFINITY;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            nearest = std::min(nearest, pointTriangleDistance(p, positions[mesh.indices[t]], positions[mesh.indices[t + 1]],
                                                              positions[mesh.indices[t + 2]]));
        ASSERT_NEAR(grid.distance(p), nearest, 1e-5f) << "point " << i;
    }
    EXPECT_NEAR(grid.distance(positions[5]), 0.0f, 1e-6f);
}
