#include "viewer/reference_view.h"

#include <algorithm>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/settings_keys.h"

namespace penumbra::viewer {

ReferenceKey referenceKeyOf(const CameraView& view, uint32_t light, const Settings& settings) {
    return ReferenceKey{view.viewFromWorld, view.clipFromView, view.width, view.height, light, settingsToJson(settings)};
}

ReferenceComparison::~ReferenceComparison() { clear(); }

void ReferenceComparison::clear() {
    cancel_ = true;
    if (worker_.joinable()) worker_.join();
    state_ = State::None;
    diff_ = Image{};
    metrics_ = CompareMetrics{};
    error_.clear();
}

void ReferenceComparison::start(ReferenceJob job, const ReferenceKey& key) {
    clear();
    key_ = key;
    cancel_ = false;
    done_ = false;
    rowsDone_ = 0;
    rows_ = std::max(job.view.height, 1u);
    state_ = State::Tracing;
    worker_ = std::thread([this, job = std::move(job)]() mutable { run(std::move(job)); });
}

void ReferenceComparison::run(ReferenceJob job) {
    Image diff;
    CompareMetrics metrics;
    std::string error;
    try {
        job.options.rowsDone = &rowsDone_;
        job.options.cancel = &cancel_;
        const ReferenceImages reference = traceReferenceShadow(job.scene, job.view, job.light, false, job.options);
        if (!cancel_) {
            metrics = compareShadowImages(job.oursShadow, reference.shadow, reference.validMask);
            diff = makeDiffImage(job.colour, job.oursShadow, reference.shadow, reference.validMask);
        }
    } catch (const Error& e) {
        error = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    workerDiff_ = std::move(diff);
    workerMetrics_ = metrics;
    workerError_ = std::move(error);
    done_ = true;
}

void ReferenceComparison::finish() {
    worker_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    diff_ = std::move(workerDiff_);
    metrics_ = workerMetrics_;
    error_ = std::move(workerError_);
    state_ = error_.empty() ? State::Ready : State::Failed;
}

ReferenceComparison::State ReferenceComparison::state() {
    if (state_ == State::Tracing && done_) finish();
    return state_;
}

ReferenceComparison::State ReferenceComparison::wait() {
    if (state_ == State::Tracing) finish();
    return state_;
}

float ReferenceComparison::progress() const {
    if (state_ == State::Ready || state_ == State::Failed) return 1.0f;
    return std::min(float(rowsDone_.load()) / float(rows_), 1.0f);
}

void ReferenceComparison::keepOnlyFor(const ReferenceKey& key) {
    if (state_ != State::None && !(key == key_)) clear();
}

}  // namespace penumbra::viewer
