// The ring of frames in flight: per slot a command pool, a fence, a timestamp range, an upload ring
// and the garbage destroyed while it was recorded. Also the one-off (load-time) submissions.
#include <algorithm>
#include <chrono>
#include <cstring>

#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

constexpr uint64_t kInitialUploadBytes = 1ull << 20;
constexpr uint32_t kNoQueries = ~0u;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// "frame 3 (passes shadows.directional, main)": what a submission held, for error messages.
std::string Device::Impl::SubmissionName::describe() const {
    if (!text.empty()) return std::string(text);
    std::string described = "frame " + std::to_string(frameIndex);
    if (passes.empty()) return described;
    described += " (passes ";
    for (size_t i = 0; i < passes.size(); ++i) described += (i ? ", " : "") + passes[i];
    return described + ")";
}

// ---- device loss

void Device::Impl::throwLost(const std::string& where, VkResult result) {
    if (!lost) {
        lost = true;
        lostAt = where;
        // Waits on a lost device end in finite time (Vulkan spec, "Lost Device"); after this one no
        // earlier submission can still use an object, so every object may be destroyed safely.
        vkDeviceWaitIdle(device);
    }
    throw Error(std::string("GPU device lost (") + vkResultName(result) + ") " + where +
                "; the device can't be used any more");
}

void Device::Impl::throwIfLost() const {
    if (lost) throw Error("GPU device lost earlier (" + lostAt + "); the device can't be used any more");
}

void Device::Impl::queueSubmit(const VkSubmitInfo2& submit, VkFence fence, const SubmissionName& what) {
    throwIfLost();
    ++submissionCalls;
    const uint64_t injected = options.faults.loseDeviceAtSubmit;
    const VkResult result = submissionCalls == injected ? VK_ERROR_DEVICE_LOST : vkQueueSubmit2(queue, 1, &submit, fence);
    if (result == VK_ERROR_DEVICE_LOST) throwLost("submitting " + what.describe(), result);
    if (result != VK_SUCCESS)
        throw Error("Vulkan call failed: vkQueueSubmit2 (" + what.describe() + ") returned " + vkResultName(result));
    ++submits;
}

namespace {

// One iteration of a polling loop: a hint to the core that it spins (x86 PAUSE), else nothing.
inline void spinPause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// DeviceOptions::spinWait: polls `ready` until it returns something other than VK_NOT_READY (or the
// timeout passes: VK_TIMEOUT).
template <typename Poll>
VkResult spinUntil(Poll ready, uint64_t timeoutNs) {
    const auto start = std::chrono::steady_clock::now();
    for (uint32_t round = 0;; ++round) {
        const VkResult result = ready();
        if (result != VK_NOT_READY) return result;
        if ((round & 1023u) == 0 && uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                 std::chrono::steady_clock::now() - start).count()) >= timeoutNs)
            return VK_TIMEOUT;
        spinPause();
    }
}

}  // namespace

void Device::Impl::waitForFence(VkFence fence, const SubmissionName& what) {
    throwIfLost();
    ++fenceWaits;
    const uint64_t injected = options.faults.loseDeviceAtWait;
    const auto poll = [&] {
        ++spinWaitPolls;
        return vkGetFenceStatus(device, fence);
    };
    const VkResult result = fenceWaits == injected ? VK_ERROR_DEVICE_LOST
                            : options.spinWait     ? spinUntil(poll, UINT64_MAX)
                                                   : vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
    if (result == VK_ERROR_DEVICE_LOST) throwLost("while the GPU ran " + what.describe(), result);
    if (result != VK_SUCCESS)
        throw Error("Vulkan call failed: vkWaitForFences (" + what.describe() + ") returned " + vkResultName(result));
}

void Device::Impl::waitForTimeline(uint64_t value, const SubmissionName& what) {
    throwIfLost();
    ++fenceWaits;
    // A generous bound: a frame's commands finish in well under this, so reaching it means the
    // caller never submitted the command buffer with its signal (a hang would help nobody).
    constexpr uint64_t kTimeoutNs = 60ull * 1000 * 1000 * 1000;
    VkSemaphoreWaitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    wait.semaphoreCount = 1;
    wait.pSemaphores = &externalTimeline;
    wait.pValues = &value;
    const auto poll = [&] {
        uint64_t reached = 0;
        ++spinWaitPolls;
        const VkResult counter = vkGetSemaphoreCounterValue(device, externalTimeline, &reached);
        return counter != VK_SUCCESS ? counter : reached >= value ? VK_SUCCESS : VK_NOT_READY;
    };
    const VkResult result = options.spinWait ? spinUntil(poll, kTimeoutNs) : vkWaitSemaphores(device, &wait, kTimeoutNs);
    if (result == VK_ERROR_DEVICE_LOST) throwLost("while the GPU ran " + what.describe(), result);
    if (result == VK_TIMEOUT)
        throw Error(what.describe() + " did not finish within 60 s: was its command buffer submitted with the "
                    "frame's completion semaphore signalled to its value?");
    if (result != VK_SUCCESS)
        throw Error("Vulkan call failed: vkWaitSemaphores (" + what.describe() + ") returned " + vkResultName(result));
}

void Device::Impl::createFrames(uint32_t count) {
    frames.resize(count);
    for (FrameContext& frame : frames) {
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = queueFamily;
        VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &frame.commandPool));
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = frame.commandPool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &frame.commandBuffer));
        setDebugName(VK_OBJECT_TYPE_COMMAND_BUFFER, uint64_t(frame.commandBuffer), "penumbra frame");
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &frame.fence));
    }
}

// The ring holds uniforms, storage data, copy sources and the frame's readbacks, and indirect dispatch
// sizes that the CPU writes (the atlases' culling and raster tile lists, cull_structs.h).
constexpr uint32_t kUploadRingUsage = kBufferUniform | kBufferStorage | kBufferTransferSrc | kBufferTransferDst | kBufferIndirect;

void Device::Impl::createUploadRings(Device& owner) {
    for (FrameContext& frame : frames) {
        frame.uploadBuffer = owner.createBuffer(kInitialUploadBytes,
                                                kUploadRingUsage,
                                                MemoryKind::HostVisible, nullptr, "frame upload ring");
        frame.uploadCapacity = kInitialUploadBytes;
    }
}

void Device::Impl::destroyFrames() {
    for (FrameContext& frame : frames) {
        retireOutgrownUploads(frame);  // a frame still recording when the device goes
        destroyGarbage(frame.garbage);
        if (frame.uploadBuffer) {
            BufferResource upload = buffers.remove(frame.uploadBuffer.id);
            destroyNow(upload);
        }
        if (frame.fence) vkDestroyFence(device, frame.fence, nullptr);
        if (frame.commandPool) vkDestroyCommandPool(device, frame.commandPool, nullptr);
    }
    frames.clear();
    if (externalTimeline) vkDestroySemaphore(device, externalTimeline, nullptr);
    externalTimeline = VK_NULL_HANDLE;
}

void Device::Impl::retireFrame(FrameContext& frame) {
    if (!frame.inFlight) return;
    if (lost) {
        // Nothing of a lost device is waited for (throwLost waited once for all): the frame is
        // dropped, its objects freed.
        frame.inFlight = false;
        frame.timerCount = 0;
        frame.readbackRanges.clear();
        destroyGarbage(frame.garbage);
        return;
    }
    try {
        const SubmissionName what{{}, frame.frameIndex, std::span(frame.timerNames.data(), frame.timerCount)};
        if (frame.external) waitForTimeline(frame.timelineValue, what);
        else waitForFence(frame.fence, what);
    } catch (const Error&) {
        // Lost now: drop it as above. (An external frame whose command buffer never came stays in flight:
        // each later wait for it fails the same way.)
        if (lost) retireFrame(frame);
        throw;
    }
    if (completedCount == completed.size()) completed.emplace_back();
    CompletedFrame& done = completed[completedCount++];  // reused: every field is set here
    done.frameIndex = frame.frameIndex;
    done.submitToFenceMilliseconds = millisecondsSince(frame.submitTime);
    done.gpuFrameMilliseconds = done.gpuEndMilliseconds = 0.0;
    done.timings.resize(timestampsSupported ? frame.timerCount : 0);
    if (timestampsSupported) {
        const uint32_t slot = uint32_t(&frame - frames.data());
        const double msPerTick = double(properties.limits.timestampPeriod) * 1e-6;
        const uint32_t queryCount = frame.timerCount * 2;
        std::vector<uint64_t>& ticks = scratchTicks;
        ticks.resize(std::max<size_t>({ticks.size(), queryCount, 1}));
        if (queryCount > 0)
            VK_CHECK(vkGetQueryPoolResults(device, timestampPool, slot * timestampsPerFrame, queryCount,
                                           queryCount * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        for (size_t i = 0; i < frame.timerCount; ++i) {
            done.timings[i].name.assign(frame.timerNames[i]);
            done.timings[i].milliseconds = double(ticks[2 * i + 1] - ticks[2 * i]) * msPerTick;
        }
        uint64_t whole[2] = {};
        VK_CHECK(vkGetQueryPoolResults(device, timestampPool, (slot + 1) * timestampsPerFrame - 2, 2, sizeof(whole),
                                       whole, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        done.gpuFrameMilliseconds = double(whole[1] - whole[0]) * msPerTick;
        done.gpuEndMilliseconds = double(whole[1]) * msPerTick;
    }
    const auto* ring = static_cast<const uint8_t*>(buffers.at(frame.uploadBuffer.id).mapped);
    done.readback.clear();
    for (const auto& [offset, size] : frame.readbackRanges)
        done.readback.insert(done.readback.end(), ring + offset, ring + offset + size);
    frame.readbackRanges.clear();
    frame.inFlight = false;
    frame.timerCount = 0;
    destroyGarbage(frame.garbage);
}

uint32_t Device::framesInFlight() const { return uint32_t(impl_->frames.size()); }
uint64_t Device::nextFrameIndex() const { return impl_->nextFrameIndex; }

CommandList Device::beginFrame() { return impl_->beginSlot(*this, VK_NULL_HANDLE); }

CommandList Device::beginExternalFrame(uint64_t vkCommandBuffer) {
    if (!impl_->timelineSemaphores)
        throw Error("recording into a caller's command buffer needs the timelineSemaphore feature (Vulkan 1.2) on " +
                    impl_->info.name + (impl_->ownsDevice ? "" : ": enable it and say so in ExternalVulkanDevice"));
    if (!vkCommandBuffer) throw Error("no command buffer to record the frame into");
    return impl_->beginSlot(*this, reinterpret_cast<VkCommandBuffer>(vkCommandBuffer));
}

// The next ring slot, its previous frame retired, recording into its own command buffer or `external`.
CommandList Device::Impl::beginSlot(Device& owner, VkCommandBuffer external) {
    Impl& d = *this;
    // Always checked: a frame left recording (not submitted, not abandoned) would be lost silently.
    if (d.recordingSlot >= 0) throw Error("internal: beginFrame while frame " +
                                          std::to_string(d.frames[d.recordingSlot].frameIndex) + " is still recording");
    d.throwIfLost();
    d.collectPipelineBuilds();
    const uint32_t slot = uint32_t(d.nextFrameIndex % d.frames.size());
    FrameContext& frame = d.frames[slot];
    d.retireFrame(frame);
    frame.external = external != VK_NULL_HANDLE;
    VkCommandBuffer commandBuffer = frame.external ? external : frame.commandBuffer;
    if (!frame.external) {
        // The pool keeps its memory (no RELEASE_RESOURCES): the next frame's recording reuses it rather
        // than the driver allocating it again.
        VK_CHECK(vkResetCommandPool(d.device, frame.commandPool, 0));
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        VK_CHECK(vkBeginCommandBuffer(frame.commandBuffer, &begin));
    }
    frame.frameIndex = d.nextFrameIndex++;
    frame.uploadUsed = 0;
    frame.readbackRanges.clear();
    d.recordingSlot = int32_t(slot);
    d.frameGraph.beginFrame();

    CommandList commands;
    commands.device = &owner;
    commands.nativeCommandBuffer = commandBuffer;
    commands.timerNames.swap(frame.timerNames);  // lent while it records (submitFrame gives them back)
    commands.openTimers.swap(frame.openTimers);
    commands.openTimers.clear();
    if (d.timestampsSupported) {
        // The slot's last two queries time the whole frame (submitFrame writes the end).
        commands.queryBase = slot * d.timestampsPerFrame;
        commands.queryCapacity = d.timestampsPerFrame - 2;
        vkCmdResetQueryPool(commandBuffer, d.timestampPool, commands.queryBase, d.timestampsPerFrame);
        vkCmdWriteTimestamp2(commandBuffer, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, d.timestampPool,
                             commands.queryBase + commands.queryCapacity);
    } else {
        commands.queryBase = kNoQueries;
    }
    return commands;
}

FrameAllocation Device::allocateFrameData(uint64_t size, uint64_t alignment) {
    Impl& d = *impl_;
    if (d.recordingSlot < 0) throw Error("internal: allocateFrameData outside beginFrame/submitFrame");
    FrameContext& frame = d.frames[d.recordingSlot];
    alignment = std::max<uint64_t>(alignment, kPortableBufferOffsetAlignment);  // a descriptor may bind it
    uint64_t offset = (frame.uploadUsed + alignment - 1) & ~(alignment - 1);
    if (!frame.uploadBuffer || offset + size > frame.uploadCapacity) {
        // Grow the ring (the old buffer stays alive until this frame is done): only when a frame needs
        // more than any frame before it, so the steady state allocates nothing.
        uint64_t capacity = std::max(kInitialUploadBytes, frame.uploadCapacity * 2);
        while (capacity < offset + size) capacity *= 2;
        if (!frame.readbackRanges.empty()) throw Error("internal: the upload ring grew after a frame readback");
        // Data written earlier in this frame lives in the old buffer, and slices of it may still be bound
        // or copied: it keeps its handle until the frame is closed and its memory until the frame is done.
        if (frame.uploadBuffer) frame.outgrownUploads.push_back(frame.uploadBuffer);
        frame.uploadBuffer = createBuffer(capacity, kUploadRingUsage,
                                          MemoryKind::HostVisible, nullptr, "frame upload ring");
        frame.uploadCapacity = capacity;
        offset = 0;
    }
    frame.uploadUsed = offset + size;
    FrameAllocation allocation;
    allocation.slice = {frame.uploadBuffer, offset, size};
    allocation.mapped = static_cast<uint8_t*>(d.buffers.at(frame.uploadBuffer.id).mapped) + offset;
    return allocation;
}

uint64_t Device::readBackAtFrameEnd(CommandList& commands, const BufferSlice& source) {
    Impl& d = *impl_;
    if (d.recordingSlot < 0) throw Error("internal: readBackAtFrameEnd outside beginFrame/submitFrame");
    const FrameAllocation target = allocateFrameData(source.size, 16);
    commands.pass("readback", {use(source.buffer, Usage::TransferRead), use(target.slice.buffer, Usage::TransferWrite)});
    commands.copyBuffer(source, target.slice.buffer, target.slice.offset);
    auto& ranges = d.frames[d.recordingSlot].readbackRanges;
    uint64_t start = 0;  // the completed frame's readback joins the ranges in this order
    for (const auto& range : ranges) start += range.second;
    ranges.emplace_back(target.slice.offset, source.size);
    return start;
}

// The frame's last commands: the host readback's barrier and the closing timestamp.
void Device::Impl::endSlotCommands(FrameContext& frame, CommandList& commands) {
    PENUMBRA_ASSERT(recordingSlot >= 0 && commands.openTimers.empty());
    // The host reads what readBackAtFrameEnd copied once the frame is done.
    if (!frame.readbackRanges.empty()) commands.pass("host readback", {use(frame.uploadBuffer, Usage::HostRead)});
    if (timestampsSupported)
        vkCmdWriteTimestamp2(static_cast<VkCommandBuffer>(commands.nativeCommandBuffer), VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT,
                             timestampPool, commands.queryBase + commands.queryCapacity + 1);
}

// The slot is in flight: it takes back its timers, and the objects destroyed since the last frame go
// when it is done (frames before it may still use them).
void Device::Impl::retireOutgrownUploads(FrameContext& frame) {
    for (BufferHandle outgrown : frame.outgrownUploads) frame.garbage.buffers.push_back(buffers.remove(outgrown.id));
    frame.outgrownUploads.clear();
}

void Device::Impl::closeSlot(FrameContext& frame, CommandList& commands) {
    retireOutgrownUploads(frame);
    frame.submitTime = std::chrono::steady_clock::now();
    frame.inFlight = true;
    frame.timerNames.swap(commands.timerNames);
    frame.timerCount = commands.timerCount;
    frame.openTimers.swap(commands.openTimers);
    commands.timerCount = 0;
    Garbage& garbage = frame.garbage;
    auto append = [](auto& to, auto& from) {
        to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
        from.clear();
    };
    append(garbage.buffers, pendingGarbage.buffers);
    append(garbage.textures, pendingGarbage.textures);
    append(garbage.pipelines, pendingGarbage.pipelines);
    append(garbage.samplers, pendingGarbage.samplers);
    append(garbage.tables, pendingGarbage.tables);
    recordingSlot = -1;
    commands.nativeCommandBuffer = nullptr;
}

uint64_t Device::submitFrame(CommandList& commands, const ExternalTarget* sync) {
    Impl& d = *impl_;
    if (d.recordingSlot < 0) throw Error("internal: submitFrame without beginFrame");
    FrameContext& frame = d.frames[d.recordingSlot];
    if (frame.external) throw Error("internal: submitFrame of a frame recorded into a caller's command buffer");
    d.endSlotCommands(frame, commands);
    VK_CHECK(vkEndCommandBuffer(frame.commandBuffer));
    VkCommandBufferSubmitInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    commandInfo.commandBuffer = frame.commandBuffer;
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &commandInfo;
    if (sync && sync->waitSemaphore) {
        wait.semaphore = reinterpret_cast<VkSemaphore>(sync->waitSemaphore);
        wait.stageMask = sync->waitStageMask ? VkPipelineStageFlags2(sync->waitStageMask) : VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        submit.waitSemaphoreInfoCount = 1;
        submit.pWaitSemaphoreInfos = &wait;
    }
    if (sync && sync->signalSemaphore) {
        signal.semaphore = reinterpret_cast<VkSemaphore>(sync->signalSemaphore);
        signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        submit.signalSemaphoreInfoCount = 1;
        submit.pSignalSemaphoreInfos = &signal;
    }
    VK_CHECK(vkResetFences(d.device, 1, &frame.fence));
    d.queueSubmit(submit, frame.fence, {{}, frame.frameIndex, std::span(commands.timerNames.data(), commands.timerCount)});
    d.closeSlot(frame, commands);
    return frame.frameIndex;
}

Device::ExternalFrameEnd Device::endExternalFrame(CommandList& commands) {
    Impl& d = *impl_;
    if (d.recordingSlot < 0) throw Error("internal: endExternalFrame without beginExternalFrame");
    FrameContext& frame = d.frames[d.recordingSlot];
    if (!frame.external) throw Error("internal: endExternalFrame of a frame recorded into Penumbra's command buffer");
    d.endSlotCommands(frame, commands);
    if (!d.externalTimeline) {
        VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        info.pNext = &type;
        VK_CHECK(vkCreateSemaphore(d.device, &info, nullptr, &d.externalTimeline));
        d.setDebugName(VK_OBJECT_TYPE_SEMAPHORE, uint64_t(d.externalTimeline), "penumbra external frames");
    }
    frame.timelineValue = ++d.externalTimelineValue;
    d.closeSlot(frame, commands);
    return {frame.frameIndex, reinterpret_cast<uint64_t>(d.externalTimeline), frame.timelineValue};
}

void Device::abandonFrame(CommandList& commands) {
    Impl& d = *impl_;
    if (d.recordingSlot < 0) return;
    FrameContext& frame = d.frames[d.recordingSlot];
    // Resetting the pool returns the command buffer to the initial state, recording or not (even
    // inside a render pass instance). A caller's command buffer is the caller's to reset.
    if (!frame.external) vkResetCommandPool(d.device, frame.commandPool, 0);
    d.frameGraph.abandonFrame();  // none of its barriers and transitions happened
    frame.readbackRanges.clear();
    d.retireOutgrownUploads(frame);
    Garbage& garbage = frame.garbage;
    auto append = [](auto& to, auto& from) {
        to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
        from.clear();
    };
    append(d.pendingGarbage.buffers, garbage.buffers);
    append(d.pendingGarbage.textures, garbage.textures);
    append(d.pendingGarbage.pipelines, garbage.pipelines);
    append(d.pendingGarbage.samplers, garbage.samplers);
    append(d.pendingGarbage.tables, garbage.tables);
    d.recordingSlot = -1;
    commands.nativeCommandBuffer = nullptr;
    frame.timerNames.swap(commands.timerNames);
    frame.timerCount = 0;
    frame.openTimers.swap(commands.openTimers);
    commands.timerCount = 0;
}

void Device::waitFrame(uint64_t frameIndex) {
    Impl& d = *impl_;
    for (FrameContext& frame : d.frames)
        if (frame.inFlight && frame.frameIndex <= frameIndex) d.retireFrame(frame);
}

void Device::waitIdle() {
    Impl& d = *impl_;
    // Oldest first, so completed frames stay in order.
    std::vector<FrameContext*>& inFlight = d.scratchInFlight;
    inFlight.clear();
    for (FrameContext& frame : d.frames)
        if (frame.inFlight) inFlight.push_back(&frame);
    std::sort(inFlight.begin(), inFlight.end(), [](auto* a, auto* b) { return a->frameIndex < b->frameIndex; });
    for (FrameContext* frame : inFlight) d.retireFrame(*frame);
    if (d.recordingSlot < 0) d.destroyGarbage(d.pendingGarbage);
}

void Device::trimMemory() { impl_->memory->releaseEmptyBlocks(); }

FrameGraph& Device::frameGraph() { return impl_->frameGraph; }

std::vector<CompletedFrame> Device::takeCompletedFrames() {
    const std::span<CompletedFrame> done = completedFrames();
    std::vector<CompletedFrame> frames(std::make_move_iterator(done.begin()), std::make_move_iterator(done.end()));
    releaseCompletedFrames();
    return frames;
}

std::span<CompletedFrame> Device::completedFrames() { return {impl_->completed.data(), impl_->completedCount}; }

void Device::releaseCompletedFrames() { impl_->completedCount = 0; }

void Device::Impl::destroyGarbage(Garbage& garbage) {
    for (auto& b : garbage.buffers) destroyNow(b);
    for (auto& t : garbage.textures) destroyNow(t);
    for (auto& p : garbage.pipelines) parkOrDestroy(p);
    for (VkSampler s : garbage.samplers) vkDestroySampler(device, s, nullptr);
    for (auto& t : garbage.tables) destroyNow(t);
    garbage = Garbage{};
}

// ---- one-off submissions

VkCommandBuffer Device::Impl::beginImmediate() {
    throwIfLost();
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = immediatePool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &commandBuffer));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(commandBuffer, &begin));
    return commandBuffer;
}

void Device::Impl::endImmediate(VkCommandBuffer commandBuffer) {
    struct FreeOnExit {  // also when the submission or the wait fails
        Impl& d;
        VkCommandBuffer commandBuffer;
        ~FreeOnExit() { vkFreeCommandBuffers(d.device, d.immediatePool, 1, &commandBuffer); }
    } freeOnExit{*this, commandBuffer};
    VK_CHECK(vkEndCommandBuffer(commandBuffer));
    VkCommandBufferSubmitInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    commandInfo.commandBuffer = commandBuffer;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &commandInfo;
    VK_CHECK(vkResetFences(device, 1, &immediateFence));
    queueSubmit(submit, immediateFence, {"a one-off submission (uploads or readback)"});
    ++deviceWaits;
    waitForFence(immediateFence, {"a one-off submission (uploads or readback)"});
}

CommandList Device::beginCommands() {
    // Its passes must join the frame graph in submission order: not between beginFrame and submitFrame.
    if (impl_->recordingSlot >= 0) throw Error("internal: beginCommands while a frame is recording");
    CommandList commands;
    commands.device = this;
    commands.nativeCommandBuffer = impl_->beginImmediate();
    commands.queryBase = kNoQueries;  // timers are per frame; a one-off list records none
    return commands;
}

void Device::submitAndWait(CommandList& commands) {
    PENUMBRA_ASSERT(commands.openTimers.empty());
    impl_->endImmediate(static_cast<VkCommandBuffer>(commands.nativeCommandBuffer));
    commands.nativeCommandBuffer = nullptr;
}

}  // namespace penumbra::gpu
