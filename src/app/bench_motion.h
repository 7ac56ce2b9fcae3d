#pragma once
// `penumbra bench --light-motion DEGREES` and `--move-objects FRACTION`: a scene that changes every
// frame, through the public Renderer::setLight and Renderer::setInstanceTransform, so that the bench
// measures the steady state of a moving scene (shadow tiles drawn again every frame) and not only
// that of a still one, where every cached tile is reused.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/renderer.h"
#include "penumbra/scene.h"

namespace penumbra {

// The instances --move-objects moves: ceil(fraction * count) of them (none for 0, all for 1), spread
// evenly over the scene's order: j-th of m is instance floor(j * count / m).
std::vector<uint32_t> movingInstances(uint32_t instanceCount, double fraction);

// `direction` turned by `degrees` about the world's up axis, +Y (glTF is Y-up).
glm::vec3 turnedAboutUp(const glm::vec3& direction, double degrees);

// How far a moving instance travels from its place along world x: 5% of its own bounds' largest
// side, at most 1% of the scene's bounds diagonal (a ground plane stays nearly put); 1% of the
// scene's diagonal for an instance without a size.
float moveAmplitude(const Aabb& instanceBounds, const Aabb& sceneBounds);

// The offset along world x of a moving instance at frame `frame`: amplitude * sin(0.1 * frame).
float moveOffset(float amplitude, uint64_t frame);

class BenchMotion {
public:
    // Takes the scene's directional lights and the moving instances' transforms as they are now;
    // every frame is set relative to them. 0 degrees and fraction 0 do nothing.
    BenchMotion(const Scene& scene, double lightDegreesPerFrame, double moveFraction);

    // Sets frame `frame`'s light directions (the original turned by frame * degrees) and instance
    // transforms, before the frame is submitted. Allocates nothing (the renderer's calls aside).
    void apply(Renderer& renderer, uint64_t frame);

    uint32_t turnedLights() const { return uint32_t(lights_.size()); }
    uint32_t movedInstances() const { return uint32_t(instances_.size()); }

private:
    struct TurnedLight {
        uint32_t index = 0;
        glm::vec3 direction{0.0f};  // the original
        Light light;                // the value set, kept to set again without a copy
    };
    struct MovedInstance {
        uint32_t index = 0;
        glm::mat4 worldFromObject{1.0f};  // the original
        float amplitude = 0.0f;
    };
    double degrees_ = 0.0;
    std::vector<TurnedLight> lights_;
    std::vector<MovedInstance> instances_;
};

}  // namespace penumbra
