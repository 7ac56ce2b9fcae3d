#pragma once
// The viewer's camera: a fly camera (WASD + mouse look, Q/E down/up, Shift faster, the wheel sets the
// speed) and an orbit camera around a target (F frames the scene). Pure CPU, no window: the app turns
// GLFW input into CameraInput once per frame.
#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/scene.h"

namespace penumbra::viewer {

struct CameraInput {
    bool forward = false, back = false, left = false, right = false, down = false, up = false;
    bool fast = false;        // Shift
    bool rotating = false;    // right mouse button held: look (fly) or orbit (orbit)
    bool panning = false;     // middle mouse button held (orbit)
    glm::vec2 cursorDelta{0.0f};  // pixels since the last frame
    float wheel = 0.0f;       // scroll ticks since the last frame
};

enum class CameraMode { Fly, Orbit };

class CameraController {
public:
    // Starts at `start` (the scene's camera), exactly: the first frames show what penumbra render shows.
    CameraController(const Camera& start, const Aabb& wsSceneBounds);

    void update(const CameraInput& input, float seconds);
    void setMode(CameraMode mode);
    CameraMode mode() const { return mode_; }
    // Orbit mode around the scene's bounds, at a distance that shows all of them.
    void frameScene();
    void reset(const Camera& start);

    float speed() const { return speed_; }  // metres per second of the fly camera
    const Camera& camera() const { return camera_; }
    glm::vec3 wsPosition() const { return glm::vec3(camera_.worldFromView[3]); }

private:
    void lookFromAngles();
    void orbitToMatrix();

    Camera camera_;
    Aabb bounds_;
    CameraMode mode_ = CameraMode::Fly;
    float yaw_ = 0.0f, pitch_ = 0.0f;  // radians; yaw about +Y from -Z, pitch up from the horizon
    float speed_ = 1.0f;
    glm::vec3 wsOrbitTarget{0.0f};
    float orbitDistance_ = 1.0f;
};

}  // namespace penumbra::viewer
