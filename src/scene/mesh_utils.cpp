#include "scene/mesh_utils.h"

#include "core/error.h"

namespace penumbra {

Aabb computeBounds(const std::vector<Vertex>& vertices) {
    Aabb bounds;
    for (const Vertex& v : vertices) bounds.extend(v.osPosition);
    return bounds;
}

void generateFlatNormals(Mesh& mesh) {
    std::vector<Vertex> unwelded;
    unwelded.reserve(mesh.indices.size());
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        Vertex a = mesh.vertices[mesh.indices[t]];
        Vertex b = mesh.vertices[mesh.indices[t + 1]];
        Vertex c = mesh.vertices[mesh.indices[t + 2]];
        // CCW triangles face the viewer (glTF), so the cross product follows the winding.
        const glm::vec3 n = glm::cross(b.osPosition - a.osPosition, c.osPosition - a.osPosition);
        const float len = glm::length(n);
        const glm::vec3 normal = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
        a.osNormal = b.osNormal = c.osNormal = normal;
        unwelded.push_back(a);
        unwelded.push_back(b);
        unwelded.push_back(c);
    }
    mesh.vertices = std::move(unwelded);
    mesh.indices.resize(mesh.vertices.size());
    for (size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = uint32_t(i);
}

void computeWorldBounds(Scene& scene) {
    scene.wsBounds = Aabb{};
    for (Instance& instance : scene.instances) {
        PENUMBRA_ASSERT(instance.meshIndex < scene.meshes.size());
        instance.wsBounds = scene.meshes[instance.meshIndex].osBounds.transformed(instance.worldFromObject);
        scene.wsBounds.extend(instance.wsBounds);
    }
}

}  // namespace penumbra
