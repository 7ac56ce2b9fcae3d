#pragma once
// Penumbra's shadow planner as a library, for engines that draw shadow maps with their own passes: from
// a scene, a camera and the shadow settings, the lights that get shadows, the cascade splits and
// culling spheres, each shadow map's light matrices and place in its atlas (texel-snapped, pancaked),
// and the casters each map must draw. Pure CPU: no device. The same planner plans every Penumbra frame
// (Renderer, ShadowSystem), so a map drawn from this plan is the one <penumbra/shadows.glsl> expects,
// given its DirectionalShadowData / OtherShadowData (which ShadowSystem fills). docs/engine-integration.md,
// "The planner alone".
//
// Conventions of every map (the depth conventions of <penumbra/shadows/shadow_structs.h>): Vulkan clip
// space (x right, y down, depth in [0, 1]); standard depth, 0 at the near plane (toward the light);
// clear to 1, draw casters with depth test LESS and no depth bias; maps with depthClamp drawn with
// depthClampEnable (shadow pancaking: casters in front of the near plane flatten onto it).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <penumbra/camera.h>
#include <penumbra/scene.h>
#include <penumbra/shadow_settings.h>

namespace penumbra {

// One shadow map: a directional light's cascade, a spot light's map or one face of a point light's cube.
struct PlannedShadowMap {
    uint32_t sceneLight = 0;  // index into Scene::lights
    uint32_t cascade = 0;     // directional: the cascade; point light: the cube face (+X, -X, +Y, -Y, +Z, -Z); spot: 0
    uint32_t atlasX = 0, atlasY = 0, size = 0;  // its viewport in the atlas, pixels (top-left origin)
    uint32_t scissorInset = 0;                  // the scissor is the viewport shrunk by this much per side
    glm::mat4 lightFromWorld{1.0f};
    glm::mat4 clipFromWorld{1.0f};   // what the caster pass's vertex shader multiplies by
    glm::mat4 atlasFromWorld{1.0f};  // world -> (atlas u, v in [0, 1], depth)
    float wsTexelSize = 0.0f;        // world size of a texel (perspective maps: at distance 1)
    bool perspective = false;        // spot or point (else an orthographic cascade)
    bool depthClamp = true;          // draw with depthClampEnable (pancaking)
    std::vector<uint32_t> casterInstances;  // Scene::instances to draw into it, scene order
};

struct PlannedCascade {
    float vsNear = 0.0f, vsFar = 0.0f;  // the view-depth slice it serves, metres
    glm::vec3 wsCenter{0.0f};           // its culling sphere (Unity's cullingSphere)
    float radius = 0.0f;
};

struct ShadowPlan {
    // The directional lights' atlas (0 when no directional light has shadows) and its maps: the reserved
    // lights' cascades, light by light (map i = reservation slot * cascades + cascade).
    uint32_t directionalAtlasSize = 0;
    std::vector<PlannedCascade> cascades;  // shared by every directional light
    std::vector<PlannedShadowMap> directionalMaps;
    // The spot and point lights' atlas and maps (a spot light takes one, a point light six).
    uint32_t otherAtlasSize = 0;
    std::vector<PlannedShadowMap> otherMaps;
    std::vector<uint32_t> droppedLights;  // Scene::lights that wanted shadows but found no room
    std::vector<std::string> warnings;    // one line each
};

// The plan of one frame. With shadows.directional.fit = tight the cascades fit the surfaces the camera
// sees, which needs the view's depth; this function has none and fits the culling spheres (the `sphere`
// fit). Virtual shadow map modes plan no atlas maps for the lights they serve. Throws penumbra::Error
// for invalid settings (validateSettings' message).
ShadowPlan planShadows(const Scene& scene, const CameraView& view, const ShadowSettings& settings);

}  // namespace penumbra
