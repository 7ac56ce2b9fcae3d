#include "reference/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "core/error.h"
#include "reference/material_alpha.h"

namespace penumbra {
namespace {

// One instance's triangles in world space with what the filter functions need to decide a hit.
struct GeometryData {
    uint32_t instanceIndex = 0;
    const Material* material = nullptr;
    const Texture* texture = nullptr;
    bool castsShadows = true;
    std::vector<glm::vec3> wsPositions;
    std::vector<glm::vec3> wsNormals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;  // counter-clockwise = front in world space

    glm::uvec3 triangle(uint32_t prim) const {
        return {indices[3 * prim], indices[3 * prim + 1], indices[3 * prim + 2]};
    }
    // Embree's barycentrics: u weights vertex 1, v weights vertex 2.
    template <typename T>
    T interpolate(const std::vector<T>& values, uint32_t prim, float u, float v) const {
        const glm::uvec3 tri = triangle(prim);
        return (1.0f - u - v) * values[tri.x] + u * values[tri.y] + v * values[tri.z];
    }
    glm::vec3 frontNormal(uint32_t prim) const {  // unnormalized, counter-clockwise side
        const glm::uvec3 tri = triangle(prim);
        return glm::cross(wsPositions[tri.y] - wsPositions[tri.x], wsPositions[tri.z] - wsPositions[tri.x]);
    }
    float alpha(uint32_t prim, float u, float v) const {
        return baseColorAlpha(*material, texture, interpolate(uvs, prim, u, v));
    }
};

std::string deviceErrorName(RTCError error) {
    switch (error) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_UNKNOWN: return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "error " + std::to_string(int(error));
}

void checkDevice(RTCDevice device, const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + " failed: " + deviceErrorName(error));
}

bool visibleToCamera(const GeometryData& g, uint32_t prim, float u, float v, const glm::vec3& wsRayDirection) {
    const Material& m = *g.material;
    if (m.alphaMode == AlphaMode::Blend) return false;
    if (!m.doubleSided && glm::dot(g.frontNormal(prim), wsRayDirection) >= 0.0f) return false;
    if (m.alphaMode == AlphaMode::Mask && g.alpha(prim, u, v) < m.alphaCutoff) return false;
    return true;
}

bool blocksShadowRay(const GeometryData& g, uint32_t prim, float u, float v) {
    if (!g.castsShadows) return false;
    const Material& m = *g.material;
    switch (m.shadows) {
        case MaterialShadowMode::On: return true;
        case MaterialShadowMode::Clip: return g.alpha(prim, u, v) >= m.alphaCutoff;
        case MaterialShadowMode::Dither:
            return ditherValue(g.interpolate(g.wsPositions, prim, u, v)) < g.alpha(prim, u, v);
        case MaterialShadowMode::Off: return false;
    }
    return true;
}

// Embree calls the intersect filter for rtcIntersect1 (camera rays only) and the occluded filter
// for rtcOccluded1 (shadow rays only); setting valid[i] = 0 rejects the candidate hit.
void cameraFilter(const RTCFilterFunctionNArguments* args) {
    const auto& g = *static_cast<const GeometryData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                            RTCRayN_dir_z(args->ray, args->N, i));
        const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        if (!visibleToCamera(g, prim, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i), dir))
            args->valid[i] = 0;
    }
}

void shadowFilter(const RTCFilterFunctionNArguments* args) {
    const auto& g = *static_cast<const GeometryData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        if (!blocksShadowRay(g, prim, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

// Filters cost a call per candidate hit: skip them where every hit counts.
bool needsCameraFilter(const Material& m) { return m.alphaMode != AlphaMode::Opaque || !m.doubleSided; }
bool needsShadowFilter(const GeometryData& g) {
    return !g.castsShadows || g.material->shadows != MaterialShadowMode::On;
}

// `materials` and `textures` are the EmbreeScene's own copies, which the geometry points into.
std::unique_ptr<GeometryData> makeGeometryData(const Scene& scene, uint32_t instanceIndex,
                                               const std::vector<Material>& materials,
                                               const std::vector<Texture>& textures) {
    const Instance& instance = scene.instances[instanceIndex];
    if (instance.meshIndex >= scene.meshes.size())
        throw Error("scene: instance " + std::to_string(instanceIndex) + " uses mesh " +
                    std::to_string(instance.meshIndex) + ", which does not exist");
    const Mesh& mesh = scene.meshes[instance.meshIndex];
    if (mesh.materialIndex >= scene.materials.size())
        throw Error("scene: mesh '" + mesh.name + "' uses material " + std::to_string(mesh.materialIndex) +
                    ", which does not exist");
    auto g = std::make_unique<GeometryData>();
    g->instanceIndex = instanceIndex;
    g->material = &materials[mesh.materialIndex];
    const int textureIndex = g->material->baseColorTexture;
    if (textureIndex >= 0 && size_t(textureIndex) < textures.size()) g->texture = &textures[textureIndex];
    g->castsShadows = instance.castShadows;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.worldFromObject)));
    for (const Vertex& vertex : mesh.vertices) {
        g->wsPositions.push_back(glm::vec3(instance.worldFromObject * glm::vec4(vertex.osPosition, 1.0f)));
        g->wsNormals.push_back(normalMatrix * vertex.osNormal);
        g->uvs.push_back(vertex.uv);
    }
    // A mirroring transform turns counter-clockwise into clockwise; glTF says the front stays the
    // front, so swap two corners to keep "counter-clockwise in world space = front".
    const bool mirrored = glm::determinant(glm::mat3(instance.worldFromObject)) < 0.0f;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        if (std::max({a, b, c}) >= mesh.vertices.size())
            throw Error("scene: mesh '" + mesh.name + "' has an index past its " +
                        std::to_string(mesh.vertices.size()) + " vertices");
        g->indices.insert(g->indices.end(), {a, mirrored ? c : b, mirrored ? b : c});
    }
    return g;
}

}  // namespace

struct EmbreeScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<std::unique_ptr<GeometryData>> geometries;  // indexed by geomID = instance index
    // Copies, so that the EmbreeScene doesn't depend on the Scene's lifetime.
    std::vector<Material> materials;
    std::vector<Texture> textures;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
    void attach(std::unique_ptr<GeometryData> g);
};

void EmbreeScene::Impl::attach(std::unique_ptr<GeometryData> g) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    checkDevice(device, "rtcNewGeometry");
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), g->wsPositions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), g->indices.size() / 3));
    if (vertices == nullptr || indices == nullptr) {
        rtcReleaseGeometry(geometry);
        checkDevice(device, "rtcSetNewGeometryBuffer");
        throw Error("Embree: rtcSetNewGeometryBuffer returned no buffer");
    }
    for (size_t i = 0; i < g->wsPositions.size(); ++i) {
        vertices[3 * i] = g->wsPositions[i].x;
        vertices[3 * i + 1] = g->wsPositions[i].y;
        vertices[3 * i + 2] = g->wsPositions[i].z;
    }
    std::copy(g->indices.begin(), g->indices.end(), indices);
    rtcSetGeometryUserData(geometry, g.get());
    if (needsCameraFilter(*g->material)) rtcSetGeometryIntersectFilterFunction(geometry, cameraFilter);
    if (needsShadowFilter(*g)) rtcSetGeometryOccludedFilterFunction(geometry, shadowFilter);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, g->instanceIndex);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    checkDevice(device, "building a triangle geometry");
    if (geometries.size() <= g->instanceIndex) geometries.resize(g->instanceIndex + 1);
    geometries[g->instanceIndex] = std::move(g);
}

EmbreeScene::EmbreeScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    if (impl_->device == nullptr) throw Error("Embree: rtcNewDevice failed: " + deviceErrorName(rtcGetDeviceError(nullptr)));
    impl_->scene = rtcNewScene(impl_->device);
    checkDevice(impl_->device, "rtcNewScene");
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    impl_->materials = scene.materials;
    impl_->textures = scene.textures;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        auto g = makeGeometryData(scene, i, impl_->materials, impl_->textures);
        if (g->indices.empty()) continue;
        for (const glm::vec3& p : g->wsPositions) wsBounds_.extend(p);
        triangleCount_ += uint32_t(g->indices.size() / 3);
        impl_->attach(std::move(g));
    }
    rtcCommitScene(impl_->scene);
    checkDevice(impl_->device, "rtcCommitScene");
}

EmbreeScene::~EmbreeScene() = default;

float EmbreeScene::sceneScale() const {
    if (!wsBounds_.valid()) return 1e-6f;
    const glm::vec3 e = wsBounds_.extent();
    return std::max({e.x, e.y, e.z, 1e-6f});
}

std::optional<SurfaceHit> EmbreeScene::intersectCamera(const glm::vec3& wsOrigin, const glm::vec3& wsDirection,
                                                       float tNear, float tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayHit{};
    rayHit.ray.org_x = wsOrigin.x, rayHit.ray.org_y = wsOrigin.y, rayHit.ray.org_z = wsOrigin.z;
    rayHit.ray.dir_x = wsDirection.x, rayHit.ray.dir_y = wsDirection.y, rayHit.ray.dir_z = wsDirection.z;
    rayHit.ray.tnear = tNear;
    rayHit.ray.tfar = tFar;
    rayHit.ray.mask = 0xffffffffu;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    const GeometryData& g = *impl_->geometries[rayHit.hit.geomID];
    const uint32_t prim = rayHit.hit.primID;
    const float u = rayHit.hit.u, v = rayHit.hit.v;
    SurfaceHit hit;
    hit.instanceIndex = g.instanceIndex;
    hit.triangleIndex = prim;
    hit.t = rayHit.ray.tfar;
    hit.wsPosition = g.interpolate(g.wsPositions, prim, u, v);
    hit.wsGeometricNormal = glm::normalize(g.frontNormal(prim));
    const glm::vec3 shading = g.interpolate(g.wsNormals, prim, u, v);
    const float shadingLength = glm::length(shading);
    hit.wsShadingNormal = shadingLength > 1e-20f && std::isfinite(shadingLength) ? shading / shadingLength
                                                                                 : hit.wsGeometricNormal;
    hit.frontFacing = glm::dot(hit.wsGeometricNormal, wsDirection) < 0.0f;
    hit.material = g.material;
    return hit;
}

bool EmbreeScene::occluded(const glm::vec3& wsOrigin, const glm::vec3& wsDirection, float tNear, float tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = wsOrigin.x, ray.org_y = wsOrigin.y, ray.org_z = wsOrigin.z;
    ray.dir_x = wsDirection.x, ray.dir_y = wsDirection.y, ray.dir_z = wsDirection.z;
    ray.tnear = tNear;
    ray.tfar = tFar;
    ray.mask = 0xffffffffu;
    rtcOccluded1(impl_->scene, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();  // Embree's "occluded" marker
}

}  // namespace penumbra
