#pragma once
// Tiny in-memory scenes for the reference tracer's tests: a ground quad, boxes, lights and a
// camera looking straight down. Local helpers so that these tests depend on nothing but scene.h.
#include <cmath>
#include <optional>
#include <utility>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/camera.h"
#include "penumbra/scene.h"

namespace penumbra::test {

// Appends a quad (a, b, c, d around its rim) as two triangles whose counter-clockwise side faces
// `wsOutward`, with uvs (0,0), (1,0), (1,1), (0,1) at a, b, c, d.
inline void addQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 wsOutward) {
    const auto base = uint32_t(mesh.vertices.size());
    const glm::vec3 n = glm::normalize(wsOutward);
    const glm::vec2 uvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const glm::vec3 corners[4] = {a, b, c, d};
    for (int i = 0; i < 4; ++i) {
        mesh.vertices.push_back({corners[i], n, uvs[i]});
        mesh.osBounds.extend(corners[i]);
    }
    const bool counterClockwise = glm::dot(glm::cross(b - a, c - a), n) > 0.0f;
    const uint32_t order[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i += 3) {
        mesh.indices.push_back(base + order[i]);
        mesh.indices.push_back(base + (counterClockwise ? order[i + 1] : order[i + 2]));
        mesh.indices.push_back(base + (counterClockwise ? order[i + 2] : order[i + 1]));
    }
}

// A horizontal quad at height y spanning [x0, x1] × [z0, z1], front side up, u along x, v along z.
inline Mesh horizontalQuad(float y, float x0, float x1, float z0, float z1, uint32_t materialIndex = 0) {
    Mesh mesh;
    mesh.name = "quad";
    mesh.materialIndex = materialIndex;
    addQuad(mesh, {x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}, {0, 1, 0});
    return mesh;
}

// An axis-aligned box with outward-facing (counter-clockwise) faces.
inline Mesh boxMesh(glm::vec3 lo, glm::vec3 hi, uint32_t materialIndex = 0) {
    Mesh mesh;
    mesh.name = "box";
    mesh.materialIndex = materialIndex;
    for (int axis = 0; axis < 3; ++axis) {
        const int b = (axis + 1) % 3, c = (axis + 2) % 3;
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 corner[4];
            const float pb[4] = {lo[b], hi[b], hi[b], lo[b]};
            const float pc[4] = {lo[c], lo[c], hi[c], hi[c]};
            for (int i = 0; i < 4; ++i) {
                corner[i][axis] = sign > 0.0f ? hi[axis] : lo[axis];
                corner[i][b] = pb[i];
                corner[i][c] = pc[i];
            }
            glm::vec3 outward(0.0f);
            outward[axis] = sign;
            addQuad(mesh, corner[0], corner[1], corner[2], corner[3], outward);
        }
    }
    return mesh;
}

inline uint32_t addMaterial(Scene& scene, const Material& material) {
    scene.materials.push_back(material);
    return uint32_t(scene.materials.size() - 1);
}

// Adds the mesh and one identity-transformed instance of it; returns the instance index.
inline uint32_t addObject(Scene& scene, Mesh mesh, bool castShadows = true) {
    scene.meshes.push_back(std::move(mesh));
    Instance instance;
    instance.meshIndex = uint32_t(scene.meshes.size() - 1);
    instance.castShadows = castShadows;
    instance.wsBounds = scene.meshes.back().osBounds;
    instance.nodeName = scene.meshes.back().name;
    scene.instances.push_back(instance);
    scene.wsBounds.extend(instance.wsBounds);
    return uint32_t(scene.instances.size() - 1);
}

inline Scene emptyScene() {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.materials.back().name = "default";
    return scene;
}

inline Light sunLight(glm::vec3 wsDirection, float strength = 1.0f) {
    Light light;
    light.name = "sun";
    light.type = LightType::Directional;
    light.wsDirection = glm::normalize(wsDirection);
    light.shadows = LightShadows::Hard;
    light.shadowStrength = strength;
    return light;
}

inline Light spotLight(glm::vec3 wsPosition, glm::vec3 wsDirection, float outerConeAngle) {
    Light light = sunLight(wsDirection);
    light.name = "spot";
    light.type = LightType::Spot;
    light.wsPosition = wsPosition;
    light.outerConeAngle = outerConeAngle;
    light.innerConeAngle = 0.5f * outerConeAngle;
    return light;
}

// A camera at `wsEye` looking straight down (-Y), with image up = world -Z.
inline Camera topDownCamera(glm::vec3 wsEye, float yfov) {
    Camera camera;
    camera.name = "top";
    camera.worldFromView = glm::inverse(glm::lookAt(wsEye, wsEye + glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)));
    camera.yfov = yfov;
    camera.zNear = 0.1f;
    return camera;
}

// The pixel whose centre is nearest to the projection of `wsPoint`.
inline glm::ivec2 pixelOf(const CameraView& view, glm::vec3 wsPoint) {
    const glm::vec4 clip = view.clipFromWorld * glm::vec4(wsPoint, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int(std::floor((ndc.x + 1.0f) * 0.5f * float(view.width))),
            int(std::floor((ndc.y + 1.0f) * 0.5f * float(view.height)))};
}

// Ray / axis-aligned box (slab test): the entry distance > 0 and the entry face's outward normal.
inline std::optional<std::pair<float, glm::vec3>> rayBox(glm::vec3 origin, glm::vec3 dir, glm::vec3 lo, glm::vec3 hi) {
    float tEnter = -INFINITY, tExit = INFINITY;
    glm::vec3 normal(0.0f);
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0f) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return std::nullopt;
            continue;
        }
        float t0 = (lo[a] - origin[a]) / dir[a], t1 = (hi[a] - origin[a]) / dir[a];
        float side = -1.0f;
        if (t0 > t1) std::swap(t0, t1), side = 1.0f;
        if (t0 > tEnter) {
            tEnter = t0;
            normal = glm::vec3(0.0f);
            normal[a] = side;
        }
        tExit = std::min(tExit, t1);
    }
    if (tEnter > tExit || tExit <= 0.0f) return std::nullopt;
    return std::make_pair(tEnter, normal);
}

}  // namespace penumbra::test
