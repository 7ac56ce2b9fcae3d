// penumbra/scene_loading.h: addGroundPlane.
#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "penumbra/camera.h"
#include "penumbra/scene_builder.h"
#include "penumbra/scene_loading.h"
#include "scene/mesh_utils.h"

namespace penumbra {

namespace {

constexpr float kGroundScale = 4.0f;       // the plane's side over the scene's larger horizontal extent
constexpr float kGroundDrop = 1e-4f;       // how far below the bounds, over the same extent
constexpr float kGroundBaseColor = 0.5f;   // neutral grey

// The larger horizontal extent; a scene flat in both (a vertical line) falls back to its height,
// then to 1 (a single point).
float horizontalExtent(const Aabb& bounds) {
    const glm::vec3 extent = bounds.extent();
    const float horizontal = std::max(extent.x, extent.z);
    if (horizontal > 0.0f) return horizontal;
    return extent.y > 0.0f ? extent.y : 1.0f;
}

}  // namespace

void addGroundPlane(Scene& scene) {
    if (!scene.wsBounds.valid()) throw Error("cannot put a ground plane under a scene without geometry");
    if (!scene.camera) scene.camera = autoFramingCamera(scene.wsBounds);

    const float extent = horizontalExtent(scene.wsBounds);
    const glm::vec3 centre = scene.wsBounds.center();
    const glm::vec3 wsOrigin(centre.x, scene.wsBounds.min.y - kGroundDrop * extent, centre.z);

    Material grey;
    grey.name = "ground";
    grey.baseColorFactor = glm::vec4(glm::vec3(kGroundBaseColor), 1.0f);
    grey.metallic = 0.0f;
    grey.roughness = 1.0f;
    scene.materials.push_back(grey);

    Mesh plane = makePlaneMesh(glm::vec2(kGroundScale * extent), uint32_t(scene.materials.size() - 1));
    plane.name = "ground";
    plane.osBounds = computeBounds(plane.vertices);
    scene.meshes.push_back(std::move(plane));

    Instance ground;
    ground.meshIndex = uint32_t(scene.meshes.size() - 1);
    ground.worldFromObject = glm::translate(glm::mat4(1.0f), wsOrigin);
    ground.castShadows = false;
    ground.wsBounds = scene.meshes.back().osBounds.transformed(ground.worldFromObject);
    ground.nodeName = "ground";
    scene.wsBounds.extend(ground.wsBounds);
    scene.instances.push_back(std::move(ground));
}

}  // namespace penumbra
