// glTF primitives to Meshes: triangle lists with positions, normals and UVs.
#include <cmath>

#include "scene/gltf_internal.h"
#include "scene/mesh_utils.h"
#include "scene/scene_validation.h"

namespace penumbra::gltf {
namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

int findAttribute(const tinygltf::Primitive& primitive, const char* name) {
    const auto it = primitive.attributes.find(name);
    return it == primitive.attributes.end() ? -1 : it->second;
}

// The element count an accessor states, before it is read (0 for one that reading refuses anyway, with
// a better reason than a budget: a bad index, no bufferView).
uint64_t statedCount(const LoadContext& ctx, int accessorIndex) {
    if (accessorIndex < 0 || size_t(accessorIndex) >= ctx.model.accessors.size()) return 0;
    const tinygltf::Accessor& accessor = ctx.model.accessors[size_t(accessorIndex)];
    return accessor.bufferView < 0 ? 0 : accessor.count;
}

}  // namespace

std::optional<Mesh> convertPrimitive(const LoadContext& ctx, size_t meshIndex, size_t primitiveIndex,
                                     uint32_t defaultMaterialIndex) {
    const tinygltf::Mesh& source = ctx.model.meshes[meshIndex];
    const tinygltf::Primitive& primitive = source.primitives[primitiveIndex];
    const std::string what = describe("mesh", meshIndex, source.name) + " primitive " + std::to_string(primitiveIndex);
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        ctx.warn(what + ": mode " + std::to_string(primitive.mode) + " is not TRIANGLES, skipped");
        return std::nullopt;
    }
    const int positionAccessor = findAttribute(primitive, "POSITION");
    if (positionAccessor < 0) {
        ctx.warn(what + ": no POSITION attribute, skipped");
        return std::nullopt;
    }
    // The budgets first, from the counts the accessors state: nothing is allocated for a refused mesh.
    const uint64_t vertexCount = statedCount(ctx, positionAccessor);
    ctx.budget.charge(vertexCount, &SceneLimits::maxVertices, what);
    ctx.budget.charge(primitive.indices >= 0 ? statedCount(ctx, primitive.indices) : vertexCount, &SceneLimits::maxIndices, what);
    Mesh mesh;
    mesh.name = source.primitives.size() > 1 ? source.name + "#" + std::to_string(primitiveIndex) : source.name;
    const std::vector<glm::vec3> positions = readVec3(ctx, positionAccessor, what + " POSITION");
    mesh.vertices.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        if (!isFinite(positions[i])) ctx.fail(what + " POSITION: vertex " + std::to_string(i) + " is not finite");
        if (glm::any(glm::greaterThan(glm::abs(positions[i]), glm::vec3(kMaxWorldCoordinate))))
            ctx.fail(what + " POSITION: vertex " + std::to_string(i) + " lies beyond 1e10 (too large for float math)");
        mesh.vertices[i].osPosition = positions[i];
    }
    const int normalAccessor = findAttribute(primitive, "NORMAL");
    if (normalAccessor >= 0) {
        const std::vector<glm::vec3> normals = readVec3(ctx, normalAccessor, what + " NORMAL");
        if (normals.size() != positions.size()) ctx.fail(what + ": NORMAL and POSITION have different counts");
        size_t replaced = 0;
        for (size_t i = 0; i < normals.size(); ++i) {
            const float len = glm::length(normals[i]);
            const bool usable = std::isfinite(len) && len > 0.0f;
            // A zero or non-finite normal would poison shading; fall back to +Y like a generated one.
            mesh.vertices[i].osNormal = usable ? normals[i] / len : glm::vec3(0, 1, 0);
            replaced += !usable;
        }
        if (replaced > 0)
            ctx.warn(what + " NORMAL: " + std::to_string(replaced) + " zero or non-finite normals replaced by +Y");
    }
    const int uvAccessor = findAttribute(primitive, "TEXCOORD_0");
    if (uvAccessor >= 0) {
        const std::vector<glm::vec2> uvs = readVec2(ctx, uvAccessor, what + " TEXCOORD_0");
        if (uvs.size() != positions.size()) ctx.fail(what + ": TEXCOORD_0 and POSITION have different counts");
        for (size_t i = 0; i < uvs.size(); ++i) {
            if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y))
                ctx.fail(what + " TEXCOORD_0: vertex " + std::to_string(i) + " is not finite");
            mesh.vertices[i].uv = uvs[i];
        }
    }
    if (primitive.indices >= 0) {
        mesh.indices = readIndices(ctx, primitive.indices, what + " indices");
        for (size_t i = 0; i < mesh.indices.size(); ++i)
            if (mesh.indices[i] >= mesh.vertices.size())
                ctx.fail(what + ": index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                         ", not below the vertex count " + std::to_string(mesh.vertices.size()));
    } else {
        mesh.indices.resize(mesh.vertices.size());
        for (size_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = uint32_t(i);
    }
    mesh.indices.resize(mesh.indices.size() - mesh.indices.size() % 3);  // drop an incomplete last triangle
    if (normalAccessor < 0) generateFlatNormals(mesh);
    if (primitive.material >= 0) {
        if (size_t(primitive.material) >= ctx.model.materials.size())
            ctx.fail(what + ": material " + std::to_string(primitive.material) + " is out of range (the file has " +
                     std::to_string(ctx.model.materials.size()) + ")");
        mesh.materialIndex = uint32_t(primitive.material);
    } else {
        mesh.materialIndex = defaultMaterialIndex;
    }
    mesh.osBounds = computeBounds(mesh.vertices);
    return mesh;
}

}  // namespace penumbra::gltf
