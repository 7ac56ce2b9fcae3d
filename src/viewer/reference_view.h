#pragma once
// The reference view's comparison, without a window: on request the ray-traced shadow term of one
// light for the current camera (src/reference/reference_tracer.h) is traced on a worker thread with
// its progress, then compared with our shadow AOV and drawn as penumbra compare --diff draws it
// (false shadow red, false lit cyan, over the colour image dimmed). It is of one camera, window size,
// light and settings (a ReferenceKey): another key drops it, cancelling a trace still running.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include <glm/glm.hpp>

#include "penumbra/camera.h"
#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "penumbra/shadow_compare.h"
#include "penumbra/reference.h"

namespace penumbra::viewer {

// What a comparison is of.
struct ReferenceKey {
    glm::mat4 viewFromWorld{1.0f}, clipFromView{1.0f};
    uint32_t width = 0, height = 0, light = 0;
    std::string settingsJson;
    bool operator==(const ReferenceKey&) const = default;
};
ReferenceKey referenceKeyOf(const CameraView& view, uint32_t light, const Settings& settings);

// The inputs of one comparison, gathered on the main thread (the renderer's images of the view).
struct ReferenceJob {
    Scene scene;  // a copy: the worker traces it
    CameraView view;
    uint32_t light = 0;
    ReferenceOptions options;  // referenceOptionsFor(settings, view, 0)
    Image oursShadow;          // our shadow AOV of `view` (channel 0 is read)
    Image colour;              // our colour image of `view`: the picture's dimmed base
};

class ReferenceComparison {
public:
    enum class State { None, Tracing, Ready, Failed };

    ReferenceComparison() = default;
    ~ReferenceComparison();  // cancels a trace and waits for its thread
    ReferenceComparison(const ReferenceComparison&) = delete;
    ReferenceComparison& operator=(const ReferenceComparison&) = delete;

    // Starts tracing `job` on a worker thread (dropping the comparison before it).
    void start(ReferenceJob job, const ReferenceKey& key);
    // Tracing until the worker is done, then Ready (diff(), metrics()) or Failed (error()).
    State state();
    float progress() const;  // the share of rows traced, 0..1
    // Blocks until a trace running ends; returns state().
    State wait();
    // Drops the comparison (cancelling its trace) unless it is of `key`: the camera moved, the window's
    // size, the light or the settings changed.
    void keepOnlyFor(const ReferenceKey& key);
    void clear();
    const ReferenceKey& key() const { return key_; }
    const Image& diff() const { return diff_; }
    const CompareMetrics& metrics() const { return metrics_; }
    const std::string& error() const { return error_; }

private:
    void run(ReferenceJob job);
    void finish();

    State state_ = State::None;
    ReferenceKey key_;
    std::thread worker_;
    std::atomic<bool> cancel_{false}, done_{false};
    std::atomic<uint32_t> rowsDone_{0};
    uint32_t rows_ = 1;
    std::mutex mutex_;  // the worker's results until finish() takes them
    Image workerDiff_, diff_;
    CompareMetrics workerMetrics_, metrics_;
    std::string workerError_, error_;
};

}  // namespace penumbra::viewer
