// The simple shapes of scene_builder.h. Triangles are oriented counter-clockwise seen from the side
// their vertex normals point to (glTF's front face).
#include <cmath>

#include "penumbra/scene_builder.h"

namespace penumbra {
namespace {

constexpr float kPi = 3.14159265358979f;

uint32_t addVertex(Mesh& mesh, glm::vec3 osPosition, glm::vec3 osNormal, glm::vec2 uv) {
    mesh.vertices.push_back({osPosition, osNormal, uv});
    return uint32_t(mesh.vertices.size() - 1);
}

// Adds (a, b, c) wound so that its face normal agrees with the vertex normals; skips degenerate ones.
void addTriangle(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
    const Vertex& va = mesh.vertices[a];
    const Vertex& vb = mesh.vertices[b];
    const Vertex& vc = mesh.vertices[c];
    const glm::vec3 faceNormal = glm::cross(vb.osPosition - va.osPosition, vc.osPosition - va.osPosition);
    if (glm::dot(faceNormal, faceNormal) == 0.0f) return;
    const bool flip = glm::dot(faceNormal, va.osNormal + vb.osNormal + vc.osNormal) < 0.0f;
    mesh.indices.insert(mesh.indices.end(), {a, flip ? c : b, flip ? b : c});
}

// A flat quad: corners in order around the rectangle, uv (0,0) at corner 3.
void addQuad(Mesh& mesh, const glm::vec3 corners[4], glm::vec3 normal, float uvScale = 1.0f) {
    const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    uint32_t ids[4];
    for (int i = 0; i < 4; ++i) ids[i] = addVertex(mesh, corners[i], normal, uvs[i] * uvScale);
    addTriangle(mesh, ids[0], ids[1], ids[2]);
    addTriangle(mesh, ids[0], ids[2], ids[3]);
}

}  // namespace

Mesh makeBoxMesh(glm::vec3 halfExtents, uint32_t materialIndex) {
    Mesh mesh;
    mesh.name = "box";
    mesh.materialIndex = materialIndex;
    // (normal, u, v) with u x v = normal, so (-u,-v) (+u,-v) (+u,+v) (-u,+v) runs counter-clockwise.
    const glm::vec3 faces[6][3] = {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                   {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                                   {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
    for (const auto& face : faces) {
        const glm::vec3 n = face[0] * halfExtents, u = face[1] * halfExtents, v = face[2] * halfExtents;
        const glm::vec3 corners[4] = {n - u - v, n + u - v, n + u + v, n - u + v};
        addQuad(mesh, corners, face[0]);
    }
    return mesh;
}

Mesh makeSphereMesh(float radius, uint32_t materialIndex, int segments, int rings) {
    Mesh mesh;
    mesh.name = "sphere";
    mesh.materialIndex = materialIndex;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi * float(r) / float(rings);  // 0 at the top (+Y)
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * float(s) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            addVertex(mesh, n * radius, n, {float(s) / float(segments), float(r) / float(rings)});
        }
    }
    const uint32_t columns = uint32_t(segments + 1);
    for (uint32_t r = 0; r < uint32_t(rings); ++r)
        for (uint32_t s = 0; s < uint32_t(segments); ++s) {
            const uint32_t a = r * columns + s, b = a + 1, c = a + columns, d = c + 1;
            addTriangle(mesh, a, c, d);  // degenerate at the poles: skipped
            addTriangle(mesh, a, d, b);
        }
    return mesh;
}

Mesh makePlaneMesh(glm::vec2 size, uint32_t materialIndex, float uvScale) {
    Mesh mesh;
    mesh.name = "plane";
    mesh.materialIndex = materialIndex;
    const glm::vec2 h = 0.5f * size;
    // uv (0,0) at the -X, -Z corner; u along +X, v along +Z.
    const glm::vec3 corners[4] = {{-h.x, 0, h.y}, {h.x, 0, h.y}, {h.x, 0, -h.y}, {-h.x, 0, -h.y}};
    addQuad(mesh, corners, {0, 1, 0}, uvScale);
    return mesh;
}

Mesh makeQuadMesh(glm::vec2 size, uint32_t materialIndex) {
    Mesh mesh;
    mesh.name = "quad";
    mesh.materialIndex = materialIndex;
    const glm::vec2 h = 0.5f * size;
    const glm::vec3 corners[4] = {{-h.x, -h.y, 0}, {h.x, -h.y, 0}, {h.x, h.y, 0}, {-h.x, h.y, 0}};
    addQuad(mesh, corners, {0, 0, 1});
    return mesh;
}

Mesh makeCylinderMesh(float radius, float height, uint32_t materialIndex, int segments) {
    Mesh mesh;
    mesh.name = "cylinder";
    mesh.materialIndex = materialIndex;
    for (int s = 0; s <= segments; ++s) {  // side: smooth normals, a seam column duplicated for the UVs
        const float phi = 2.0f * kPi * float(s) / float(segments);
        const glm::vec3 n(std::cos(phi), 0.0f, -std::sin(phi));
        const float u = float(s) / float(segments);
        addVertex(mesh, n * radius, n, {u, 1.0f});
        addVertex(mesh, n * radius + glm::vec3(0, height, 0), n, {u, 0.0f});
    }
    for (uint32_t s = 0; s < uint32_t(segments); ++s) {
        const uint32_t a = 2 * s, b = a + 1, c = a + 2, d = a + 3;
        addTriangle(mesh, a, c, d);
        addTriangle(mesh, a, d, b);
    }
    for (const float y : {0.0f, height}) {  // caps: fans around a centre vertex
        const glm::vec3 n(0.0f, y > 0.0f ? 1.0f : -1.0f, 0.0f);
        const uint32_t centre = addVertex(mesh, {0, y, 0}, n, {0.5f, 0.5f});
        const uint32_t first = uint32_t(mesh.vertices.size());
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * float(s) / float(segments);
            const glm::vec2 c(std::cos(phi), -std::sin(phi));
            addVertex(mesh, {c.x * radius, y, c.y * radius}, n, 0.5f + 0.5f * glm::vec2(c.x, c.y));
        }
        for (uint32_t s = 0; s < uint32_t(segments); ++s) addTriangle(mesh, centre, first + s, first + s + 1);
    }
    return mesh;
}

}  // namespace penumbra
