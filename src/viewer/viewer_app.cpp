#include "viewer/viewer_app.h"

#include <cstdio>
#include <utility>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "penumbra/files.h"
#include "penumbra/error.h"
#include "penumbra/scene_loading.h"
#include "penumbra/vulkan.h"
#include "viewer/atlas_overlay.h"
#include "viewer/image_overlay.h"
#include "viewer/cascade_frusta.h"
#include "viewer/imgui_layer.h"
#include "viewer/panels.h"
#include "viewer/presenter.h"
#include "viewer/swapchain.h"
#include "viewer/vulkan_context.h"

namespace penumbra::viewer {

namespace {

constexpr size_t kStatsHistory = 240;

ViewerApp& appOf(GLFWwindow* window) { return *static_cast<ViewerApp*>(glfwGetWindowUserPointer(window)); }

// File > Save scene's field starts at the document's default.
void setSceneSavePath(ViewerState& state, const SceneDocument& document) {
    std::snprintf(state.sceneSavePath, sizeof state.sceneSavePath, "%s", document.defaultSavePath().c_str());
}

void installCallbacks(GLFWwindow* window) {
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) {
        if (!ImGui::GetCurrentContext() || !ImGui::GetIO().WantCaptureMouse) appOf(w).onScroll(y);
    });
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
        if (count > 0) appOf(w).onDrop(paths[0]);
    });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        if (!ImGui::GetCurrentContext() || !ImGui::GetIO().WantCaptureKeyboard) appOf(w).onKey(key, action, mods);
    });
}

void applyDefaultsWithWarnings(Settings& settings, const Scene& scene, const CameraView& view) {
    for (const std::string& warning : applySceneDefaults(settings, scene, view))
        std::fprintf(stderr, "penumbra-viewer: warning: %s\n", warning.c_str());
}

// The split screen's right half: the settings file alone (no --set), validated like the left's.
std::optional<Settings> loadCompareSettings(const ViewerOptions& options) {
    if (options.compareSettingsPath.empty()) return std::nullopt;
    Settings settings = loadSettingsFile(options.compareSettingsPath);
    validateSettings(settings);
    return settings;
}

// The views the split screen applies to: the ones the renderer draws whole.
bool splitsView(ViewMode view) { return view == ViewMode::Final || view == ViewMode::Shadow || view == ViewMode::Cascades; }

Settings loadUserSettings(const ViewerOptions& options) {
    Settings settings = options.settingsPath.empty() ? Settings{} : loadSettingsFile(options.settingsPath);
    for (const std::string& assignment : options.overrides) {
        if (assignment.find('=') == std::string::npos)
            throw Error("settings: --set expects key=value, got '" + assignment + "'");
        applySettingOverride(settings, assignment);
    }
    validateSettings(settings);
    return settings;
}

// One line on stdout per scene opened or reloaded and per screenshot saved, for scripts and tests
// that follow the viewer.
void announce(const std::string& message) {
    std::printf("penumbra-viewer: %s\n", message.c_str());
    std::fflush(stdout);
}

std::unique_ptr<Renderer> makeRenderer(Device& device, Scene scene) {
    RendererOptions options;
    // On a GPU a setting change never stalls a frame: every variant it can reach is built ahead on the
    // worker thread. A CPU device (lavapipe) builds on demand: its frames wait for their own variant
    // anyway (see PipelineWarmup), and a background build would take the cores that draw.
    options.warmup = device.info().isCpu ? PipelineWarmup::OnDemand : PipelineWarmup::Background;
    return std::make_unique<Renderer>(device, std::move(scene), options);
}

OutputMode outputOf(ViewMode view) {
    if (view == ViewMode::Shadow) return OutputMode::ShadowAov;
    if (view == ViewMode::Cascades) return OutputMode::CascadesAov;
    return OutputMode::Color;
}

}  // namespace

ViewerApp::ViewerApp(const ViewerOptions& options)
    : options_(options), document_(options.scenePath, options.watchPollMs,
                SceneSourceOptions{.addGround = options.ground, .assetRoot = options.assetRoot, .limits = options.limits}) {
    // Bad input first, so it is one line before any window opens.
    userSettings_ = loadUserSettings(options);
    compareSettings_ = loadCompareSettings(options);
    Scene scene = document_.loadFirst();
    const bool oneLight = options.view == ViewMode::Shadow || options.view == ViewMode::Cascades || options.view == ViewMode::Reference;
    if (oneLight && options.light >= scene.lights.size())
        throw Error("--light " + std::to_string(options.light) + ": the scene has " + std::to_string(scene.lights.size()) +
                    " lights");
    if (!options.cameraPath.empty()) {
        playback_ = loadCameraPath(options.cameraPath);
        playing_ = true;
    }
    if (!options.recordCameraPath.empty()) {
        checkWritable(options.recordCameraPath);
        recordingFile_ = options.recordCameraPath;
        recordingOn_ = true;
    }
    state_.view = options.view;
    state_.light = options.light;
    state_.showPanels = options.screenshotPath.empty() || options.panels;

    if (!glfwInit()) throw Error("cannot open a window: GLFW found no display (set DISPLAY, or run under xvfb-run)");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(int(options.width), int(options.height), "penumbra-viewer", nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw Error("cannot open a window of " + std::to_string(options.width) + "x" + std::to_string(options.height));
    }
    glfwSetWindowUserPointer(window_, this);
    installCallbacks(window_);
    context_ = std::make_unique<VulkanContext>(window_, options.device, options.validation);
    const VkPresentModeKHR present = options.present == "mailbox" ? VK_PRESENT_MODE_MAILBOX_KHR : VK_PRESENT_MODE_FIFO_KHR;
    swapchain_ = std::make_unique<Swapchain>(*context_, present);
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    swapchain_->recreate(uint32_t(width), uint32_t(height));
    presenter_ = std::make_unique<Presenter>(*context_, *swapchain_);
    imgui_ = std::make_unique<ImGuiLayer>(*context_, window_, *swapchain_, presenter_->commandPool());
    atlas_ = std::make_unique<ImageOverlay>(*context_, ImageOverlay::Placement::BottomLeft);
    referenceOverlay_ = std::make_unique<ImageOverlay>(*context_, ImageOverlay::Placement::Window);
    splitOverlay_ = std::make_unique<ImageOverlay>(*context_, ImageOverlay::Placement::RightHalf);
    DeviceOptions deviceOptions;
    deviceOptions.framesInFlight = Presenter::kFramesInFlight;
    device_ = std::make_unique<Device>(externalVulkanDevice(context_->instance, context_->physicalDevice, context_->device,
                                                            context_->queue, context_->queueFamily, context_->bufferInt64Atomics),
                                       deviceOptions);
    renderer_ = makeRenderer(*device_, std::move(scene));
    camera_ = std::make_unique<CameraController>(startCamera(renderer_->scene()), renderer_->scene().wsBounds);
    settings_ = userSettings_;
    const CameraView view = makeCameraView(camera_->camera(), swapchain_->extent().width, swapchain_->extent().height);
    applyDefaultsWithWarnings(settings_, renderer_->scene(), view);
    if (compareSettings_) applyDefaultsWithWarnings(*compareSettings_, renderer_->scene(), view);
    setSceneSavePath(state_, document_);
    announce("opened " + document_.label());
}

ViewerApp::~ViewerApp() {
    if (renderer_) renderer_->waitIdle();
    renderer_.reset();
    device_.reset();
    reference_.clear();
    atlas_.reset();
    referenceOverlay_.reset();
    splitOverlay_.reset();
    imgui_.reset();
    presenter_.reset();
    swapchain_.reset();
    context_.reset();
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

// The renderer's part of opening a scene: a renderer is made for it (before the old one goes, so a
// scene the GPU cannot take leaves the old one too). The old renderer goes first: its queued pipeline
// builds are dropped, where next to a new renderer's builds each of its pipelines would wait for one
// (30 s on lavapipe). A copy of its scene (the inspector's edits included) rebuilds it if the GPU
// cannot take the new scene; the error goes on to SceneDocument, which keeps the old source.
void ViewerApp::installScene(Scene&& scene) {
    Scene previous = renderer_->scene();
    renderer_->waitIdle();
    VIEWER_VK(vkDeviceWaitIdle(context_->device));
    renderer_.reset();
    try {
        renderer_ = makeRenderer(*device_, std::move(scene));
    } catch (const Error&) {
        renderer_ = makeRenderer(*device_, std::move(previous));
        throw;
    }
}

// Between frames: what the File menu, R and a dropped file asked of the document, and the watched
// file's changes. Another scene starts at its own camera; the settings and the view stay.
void ViewerApp::handleSceneFiles() {
    const std::optional<SceneEvent> event = document_.update(FileWatcher::Clock::now(), renderer_->scene(),
                                                             [this](Scene&& scene) { installScene(std::move(scene)); });
    if (!event) return;
    state_.status = event->message;
    if (!event->opened) return;
    if (event->camera) {
        camera_ = std::make_unique<CameraController>(*event->camera, renderer_->scene().wsBounds);
        state_.sceneCamera = -1;
        setSceneSavePath(state_, document_);
        if (shownView_ == ViewMode::Frusta) shownView_ = ViewMode::Final;  // switchView observes the new camera
    }
    if (state_.light >= renderer_->scene().lights.size()) state_.light = 0;
    reference_.clear();  // of the old scene
    announce(event->message);
}

void ViewerApp::onKey(int key, int action, int mods) {
    (void)mods;
    if (action != GLFW_PRESS) return;
    const uint32_t lights = uint32_t(renderer_->scene().lights.size());
    switch (key) {
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
        case GLFW_KEY_TAB: state_.showPanels = !state_.showPanels; break;
        case GLFW_KEY_1: state_.view = ViewMode::Final; break;
        case GLFW_KEY_2: state_.view = ViewMode::Shadow; break;
        case GLFW_KEY_3: state_.view = ViewMode::Cascades; break;
        case GLFW_KEY_4: state_.view = ViewMode::Atlas; break;
        case GLFW_KEY_5: state_.view = ViewMode::Frusta; break;
        case GLFW_KEY_6: state_.view = ViewMode::Reference; break;
        case GLFW_KEY_T:
            state_.view = ViewMode::Reference;
            referenceRequested_ = true;
            break;
        case GLFW_KEY_LEFT_BRACKET: if (lights) state_.light = (state_.light + lights - 1) % lights; break;
        case GLFW_KEY_RIGHT_BRACKET: if (lights) state_.light = (state_.light + 1) % lights; break;
        case GLFW_KEY_O:
            camera_->setMode(camera_->mode() == CameraMode::Orbit ? CameraMode::Fly : CameraMode::Orbit);
            break;
        case GLFW_KEY_F: camera_->frameScene(); break;
        case GLFW_KEY_C: nextSceneCamera(); break;
        case GLFW_KEY_F12: screenshotRequested_ = true; break;
        case GLFW_KEY_P: toggleRecording(); break;
        case GLFW_KEY_R: document_.requestReload(); break;
        default: break;
    }
}

// C: the scene's camera, then each glTF camera in node order, then the scene's camera again.
void ViewerApp::nextSceneCamera() {
    const int cameras = int(renderer_->scene().cameras.size());
    selectSceneCamera(state_, *camera_, renderer_->scene(), state_.sceneCamera + 1 < cameras ? state_.sceneCamera + 1 : -1);
}

// P: starts a new recording, or stops the one running and writes it.
void ViewerApp::toggleRecording() {
    recordingOn_ = !recordingOn_;
    if (recordingOn_) {
        recording_.keyframes.clear();
        recordingClock_ = 0.0f;
        state_.status = "recording the camera path";
        return;
    }
    try {
        saveCameraPath(recording_, recordingFile_);
        state_.status = "saved the camera path (" + std::to_string(recording_.keyframes.size()) + " keyframes) to " +
                        recordingFile_;
    } catch (const Error& error) {
        state_.status = error.what();
        std::fprintf(stderr, "penumbra-viewer: %s\n", error.what());
    }
}

// The camera of this frame: the played path's (scripted: by frame index, so the screenshot is its end)
// or the user's; then the recording takes it as a keyframe (scripted: 1/60 s per frame).
void ViewerApp::moveCamera(float seconds) {
    const CameraInput input = pollCameraInput();
    const bool scripted = !options_.screenshotPath.empty();
    if (playing_) {
        playbackClock_ += seconds;
        const float time = scripted ? scriptedPathTime(playback_, framesDone_, options_.frames)
                                    : playback_.keyframes.front().time + playbackClock_;
        camera_->reset(cameraOnPath(playback_, time, camera_->camera()));
        playing_ = scripted || time < playback_.keyframes.back().time;  // then the user flies on from its end
    } else {
        camera_->update(input, seconds);
    }
    if (recordingOn_) {
        recordingClock_ = scripted ? float(recording_.keyframes.size()) / 60.0f : recordingClock_ + seconds;
        if (recording_.keyframes.empty() || recordingClock_ > recording_.keyframes.back().time)
            recording_.keyframes.push_back(keyframeOf(camera_->camera(), recordingClock_));
    }
}

CameraInput ViewerApp::pollCameraInput() {
    CameraInput input;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    input.cursorDelta = glm::vec2(float(x - lastCursorX_), float(y - lastCursorY_));
    lastCursorX_ = x;
    lastCursorY_ = y;
    input.wheel = wheel_;
    wheel_ = 0.0f;
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureMouse) {
        input.rotating = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        input.panning = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    }
    if (!io.WantCaptureKeyboard) {
        auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS; };
        input.forward = down(GLFW_KEY_W);
        input.back = down(GLFW_KEY_S);
        input.left = down(GLFW_KEY_A);
        input.right = down(GLFW_KEY_D);
        input.down = down(GLFW_KEY_Q);
        input.up = down(GLFW_KEY_E);
        input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    }
    return input;
}

void ViewerApp::collectStats() {
    for (FrameStats& stats : renderer_->takeCompletedFrames()) {
        state_.history.push_back(std::move(stats));
        if (state_.history.size() > kStatsHistory) state_.history.pop_front();
    }
}

// One frame: false when the swapchain must be re-made before it can be drawn.
bool ViewerApp::renderFrame(float seconds, Image* screenshot) {
    if (!presenter_->beginFrame()) return false;
    switchView();
    moveCamera(seconds);
    const VkExtent2D extent = swapchain_->extent();
    const CameraView view = makeCameraView(camera_->camera(), extent.width, extent.height);
    RenderRequest request;
    request.width = extent.width;
    request.height = extent.height;
    request.output = outputOf(state_.view);
    request.aovLight = state_.light;
    std::vector<AtlasTileLabel> labels;
    if (state_.view == ViewMode::Atlas) {
        RenderRequest atlasRequest = request;
        atlasRequest.captureAtlas = true;
        atlasRequest.readback = false;
        const RenderResult atlas = renderer_->render(atlasRequest, settings_, view);
        atlas_->update(atlas.atlas, swapchain_->format());
        labels = atlasTileLabels(atlas.stats.shadows, renderer_->scene());
    }
    const std::vector<WorldLine> lines = state_.view == ViewMode::Frusta ? observedCascades(request) : std::vector<WorldLine>();
    const bool reference = state_.view == ViewMode::Reference && updateReference(view, screenshot != nullptr);
    const bool split = compareSettings_ && splitsView(state_.view);
    if (split) renderRightHalf(request, view);
    const ExternalImage target = presenter_->sceneTarget(request.output != OutputMode::Color);
    renderer_->submitFrame(request, settings_, view, &target);
    collectStats();

    imgui_->newFrame();
    PanelContext panels{state_, settings_, *renderer_, *camera_, context_->deviceName, document_};
    if (state_.view == ViewMode::Atlas && atlas_->ready()) drawAtlasLabels(labels, atlas_->windowRect(extent),
                                                                            glm::vec2(atlas_->width(), atlas_->height()));
    if (!lines.empty()) drawWorldLines(lines, view);
    if (state_.showPanels) drawPanels(panels);
    if (split && state_.showPanels) drawSplitLabels(options_.compareSettingsPath);
    if (state_.view == ViewMode::Reference) referenceRequested_ |= drawReferencePanel(reference_, state_.showPanels);
    if (!document_.error().empty()) drawErrorLine(document_.error());
    const bool overlay = state_.view == ViewMode::Atlas;
    const bool presented = presenter_->endFrame(
        *imgui_,
        [&](VkCommandBuffer commands, VkImage image, VkExtent2D size) {
            if (overlay) atlas_->record(commands, image, size);
            if (reference) referenceOverlay_->record(commands, image, size);
            if (split) splitOverlay_->record(commands, image, size);
        },
        screenshot);
    if (!presented) recreateSwapchain();
    return true;
}

// The reference view, each frame: a comparison of another camera (or window size, light, settings) is
// dropped; T starts one, and so does a screenshot, which waits for it (a scripted run fails with the
// tracer's message, e.g. a light without shadows). True when the finished picture is to be shown.
bool ViewerApp::updateReference(const CameraView& view, bool beforeScreenshot) {
    const ReferenceKey key = referenceKeyOf(view, state_.light, settings_);
    reference_.keepOnlyFor(key);
    const ReferenceComparison::State state = reference_.state();
    const bool idle = state == ReferenceComparison::State::None || state == ReferenceComparison::State::Failed;
    const bool requested = std::exchange(referenceRequested_, false);  // again when shown: after scene edits
    if ((requested && state != ReferenceComparison::State::Tracing) || (beforeScreenshot && idle)) startReference(view, key);
    if (beforeScreenshot && reference_.wait() == ReferenceComparison::State::Failed && !options_.screenshotPath.empty())
        throw Error("reference view: " + reference_.error());
    if (reference_.state() != ReferenceComparison::State::Ready) {
        referenceUploaded_ = false;
        return false;
    }
    if (!referenceUploaded_) referenceOverlay_->update(reference_.diff(), swapchain_->format());
    referenceUploaded_ = true;
    return true;
}

// Our side of the comparison, rendered now for `view` (the shadow AOV and the colour image, as
// penumbra compare renders them); the reference is traced on the comparison's worker.
void ViewerApp::startReference(const CameraView& view, const ReferenceKey& key) {
    ReferenceJob job{renderer_->scene(), view, state_.light, referenceOptionsFor(settings_, view, 0), {}, {}};
    RenderRequest request;
    request.width = view.width;
    request.height = view.height;
    request.aovLight = state_.light;
    try {
        request.output = OutputMode::ShadowAov;
        job.oursShadow = renderer_->render(request, settings_, view).image;
        request.output = OutputMode::Color;
        job.colour = renderer_->render(request, settings_, view).image;
    } catch (const Error& error) {
        state_.status = error.what();
        std::fprintf(stderr, "penumbra-viewer: %s\n", error.what());
        return;
    }
    reference_.start(std::move(job), key);
}

// The split screen's right half: this frame rendered with the second settings and read back (a debug
// view: a synchronous frame more per frame), shown over the right half of the window.
void ViewerApp::renderRightHalf(const RenderRequest& request, const CameraView& view) {
    RenderRequest right = request;
    right.readback = true;
    splitOverlay_->update(renderer_->render(right, *compareSettings_, view).image, swapchain_->format());
}

// Into the frusta view the camera is kept as the observed one and the fly camera moves outside; out of
// it the camera comes back.
void ViewerApp::switchView() {
    if (state_.view == shownView_) return;
    if (state_.view == ViewMode::Frusta) {
        observed_ = camera_->camera();
        const float distance = std::min(settings_.shadows.maxDistance, observed_.zFar);
        camera_->reset(outsideCamera(observed_, distance));
    } else if (shownView_ == ViewMode::Frusta) {
        camera_->reset(observed_);
    }
    shownView_ = state_.view;
}

// The observed camera's cascades: a frame planned (and drawn, not shown) from it, for its shadow plan.
std::vector<WorldLine> ViewerApp::observedCascades(const RenderRequest& request) {
    RenderRequest planned = request;
    planned.readback = false;
    const CameraView observed = makeCameraView(observed_, request.width, request.height);
    const RenderResult result = renderer_->render(planned, settings_, observed);
    return cascadeLines(cascadeGeometry(result.stats.shadows), observed);
}

void ViewerApp::recreateSwapchain() {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    swapchain_->recreate(uint32_t(width), uint32_t(height));
    imgui_->swapchainRecreated(*swapchain_);
}

void ViewerApp::saveScreenshot(const Image& image, const std::string& path) {
    writePng(image, path);
    state_.status = "saved " + path;
    announce(state_.status);
}

int ViewerApp::run() {
    auto last = std::chrono::steady_clock::now();
    glfwGetCursorPos(window_, &lastCursorX_, &lastCursorY_);
    const bool scripted = !options_.screenshotPath.empty();
    while (!glfwWindowShouldClose(window_)) {
        glfwPollEvents();
        int width = 0, height = 0;
        glfwGetFramebufferSize(window_, &width, &height);
        if (width == 0 || height == 0) {  // minimized: nothing to draw into
            glfwWaitEvents();
            continue;
        }
        if (uint32_t(width) != swapchain_->extent().width || uint32_t(height) != swapchain_->extent().height)
            recreateSwapchain();
        handleSceneFiles();
        const auto now = std::chrono::steady_clock::now();
        const float seconds = std::chrono::duration<float>(now - last).count();
        last = now;
        const bool lastScripted = scripted && framesDone_ + 1 == options_.frames;
        const bool capture = lastScripted || screenshotRequested_;
        Image shot;
        if (!renderFrame(seconds, capture ? &shot : nullptr)) {
            recreateSwapchain();
            continue;
        }
        ++framesDone_;
        if (capture && !lastScripted) {
            screenshotRequested_ = false;
            saveScreenshot(shot, "penumbra-viewer-" + std::to_string(screenshotCount_++) + ".png");
        }
        if (lastScripted) {
            saveScreenshot(shot, options_.screenshotPath);
            break;
        }
    }
    if (recordingOn_) saveCameraPath(recording_, recordingFile_);  // a recording still running at exit
    renderer_->waitIdle();
    VIEWER_VK(vkDeviceWaitIdle(context_->device));
    if (options_.validation && context_->validationMessages() > 0)
        throw Error(std::to_string(context_->validationMessages()) + " Vulkan validation messages (see above)");
    return 0;
}

}  // namespace penumbra::viewer
