#pragma once
// penumbra-viewer's window and frame loop: input, camera, the renderer's frames into the swapchain,
// the views, the panels, screenshots, scene reload and drag-and-drop.
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "penumbra/device.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"
#include "viewer/camera_controller.h"
#include "viewer/camera_path.h"
#include "viewer/cascade_frusta.h"
#include "viewer/file_watcher.h"
#include "viewer/reference_view.h"
#include "viewer/scene_document.h"
#include "viewer/viewer_options.h"

struct GLFWwindow;

namespace penumbra::viewer {

class ImageOverlay;
class ImGuiLayer;
class Presenter;
class Swapchain;
class VulkanContext;

// What the panels show and change; owned by the app, drawn by panels.cpp.
struct ViewerState {
    ViewMode view = ViewMode::Final;
    uint32_t light = 0;
    int sceneCamera = -1;  // the camera last picked (C, the camera combo): -1 the scene's, else Scene::cameras
    bool showPanels = true;
    std::deque<FrameStats> history;  // the last frames the GPU finished, oldest first
    std::string status;              // the last reload error or saved file, shown in the panel
    char settingsSavePath[512] = "penumbra-settings.json";  // the inspector's text field
    // File menu: the paths of its Open and Save scene fields (what they ask goes to the SceneDocument,
    // acted on after the frame).
    char openPath[512] = "";
    char sceneSavePath[512] = "penumbra-scene.gltf";
};

class ViewerApp {
public:
    explicit ViewerApp(const ViewerOptions& options);
    ~ViewerApp();
    // The frame loop; returns the exit code (1 after a validation message with --validation).
    int run();

    // GLFW callbacks' targets.
    void onScroll(double ticks) { wheel_ += float(ticks); }
    void onDrop(const std::string& path) { document_.requestOpen(path); }
    void onKey(int key, int action, int mods);

private:
    void installScene(Scene&& scene);
    void handleSceneFiles();
    bool renderFrame(float seconds, Image* screenshot);
    CameraInput pollCameraInput();
    void moveCamera(float seconds);
    void toggleRecording();
    void collectStats();
    void recreateSwapchain();
    void switchView();
    std::vector<WorldLine> observedCascades(const RenderRequest& request);
    void nextSceneCamera();
    bool updateReference(const CameraView& view, bool beforeScreenshot);
    void startReference(const CameraView& view, const ReferenceKey& key);
    void renderRightHalf(const RenderRequest& request, const CameraView& view);
    void saveScreenshot(const Image& image, const std::string& path);

    ViewerOptions options_;
    SceneDocument document_;  // the scene file: open, reload, save, the last error
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<VulkanContext> context_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<Presenter> presenter_;
    std::unique_ptr<ImGuiLayer> imgui_;
    std::unique_ptr<ImageOverlay> atlas_, referenceOverlay_, splitOverlay_;
    std::unique_ptr<Device> device_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<CameraController> camera_;
    Settings userSettings_, settings_;
    std::optional<Settings> compareSettings_;  // --compare-settings: the split screen's right half
    ViewerState state_;
    float wheel_ = 0.0f;
    double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
    ViewMode shownView_ = ViewMode::Final;  // the view of the last frame (switchView acts on a change)
    Camera observed_;                       // the frusta view's observed camera
    uint32_t screenshotCount_ = 0;
    bool screenshotRequested_ = false;
    uint32_t framesDone_ = 0;
    // The reference view: the comparison (traced on its worker), T's request, and whether its finished
    // picture is in referenceOverlay_.
    ReferenceComparison reference_;
    bool referenceRequested_ = false, referenceUploaded_ = false;
    // Camera paths: one played from the first frame (until its end; scripted: by frame index), one
    // being recorded (P, or --record-camera-path from the first frame), with their clocks in seconds.
    CameraPath playback_, recording_;
    bool playing_ = false, recordingOn_ = false;
    float playbackClock_ = 0.0f, recordingClock_ = 0.0f;
    std::string recordingFile_ = "penumbra-camera-path.json";
};

}  // namespace penumbra::viewer
