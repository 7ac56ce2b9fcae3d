// The frame graph's barrier derivation (frame_graph.h): per resource, the last write, the stages that
// read since, and the uses that write was made visible to.
#include "gpu/frame_graph.h"

#include "gpu/handle_pool.h"

#include <vulkan/vulkan_core.h>

#include "core/error.h"

namespace penumbra::gpu {

namespace {

struct UsageInfo {
    const char* name;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 access;
    VkImageLayout layout;  // textures
    bool write;
};

UsageInfo info(Usage usage) {
    constexpr VkAccessFlags2 storageReadWrite = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    switch (usage) {
        case Usage::IndirectArguments:
            return {"indirect arguments", VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Usage::IndexBuffer:
            return {"index buffer", VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Usage::GraphicsRead:
            return {"graphics read", VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Usage::ComputeRead:
            return {"compute read", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                    VK_IMAGE_LAYOUT_UNDEFINED, false};
        case Usage::ComputeWrite:
            return {"compute write", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, storageReadWrite, VK_IMAGE_LAYOUT_GENERAL, true};
        case Usage::ComputeSampled:
            return {"compute sampled", VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
        case Usage::FragmentSampled:
            return {"fragment sampled", VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
        case Usage::ColorTarget:
            return {"colour target", VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true};
        case Usage::DepthTarget:
            return {"depth target", VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true};
        case Usage::TransferRead:
            return {"transfer read", VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false};
        case Usage::TransferWrite:
            return {"transfer write", VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true};
        case Usage::HostRead:
            return {"host read", VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false};
    }
    throw Error("internal: unknown frame graph usage");
}

constexpr uint32_t bit(Usage usage) { return 1u << uint32_t(usage); }

uint32_t slotOf(ResourceKey resource) { return resource.id & HandlePool<int>::kIndexMask; }

}  // namespace

const char* usageName(Usage usage) { return info(usage).name; }
bool isWrite(Usage usage) { return info(usage).write; }

FrameGraph::State& FrameGraph::state(ResourceKey resource) {
    std::vector<State>& states = resource.texture ? textures_ : buffers_;
    const uint32_t slot = slotOf(resource);
    if (slot >= states.size()) states.resize(slot + 1);
    State& s = states[slot];
    if (s.id != resource.id) s = State{.id = resource.id};
    return s;
}

std::span<const Barrier> FrameGraph::declare(std::string_view pass, std::span<const ResourceUse> uses) {
    // One entry per resource; mergedUsages_ holds the Usage bits of each.
    merged_.clear();
    mergedUsages_.clear();
    for (const ResourceUse& u : uses) {
        PENUMBRA_ASSERT(u.resource.id != 0);
        size_t i = 0;
        while (i < merged_.size() && !(merged_[i].resource == u.resource)) ++i;
        if (i == merged_.size()) {
            merged_.push_back(u);
            mergedUsages_.push_back(0);
        } else if (u.resource.texture && info(u.usage).layout != info(merged_[i].usage).layout) {
            throw Error("internal: pass " + std::string(pass) + " uses " + name(u.resource) + " in two layouts");
        }
        merged_[i].discard = merged_[i].discard || u.discard;
        mergedUsages_[i] |= bit(u.usage);
    }

    barriers_.clear();
    for (size_t i = 0; i < merged_.size(); ++i) {
        const ResourceUse& u = merged_[i];
        const uint32_t usages = mergedUsages_[i];
        VkPipelineStageFlags2 stages = 0;
        VkAccessFlags2 access = 0;
        bool write = false;
        for (uint32_t b = 0; b < kUsageCount; ++b) {
            if (!(usages & (1u << b))) continue;
            const UsageInfo ui = info(Usage(b));
            stages |= ui.stages;
            access |= ui.access;
            write = write || ui.write;
        }
        const uint32_t layout = u.resource.texture ? uint32_t(info(u.usage).layout) : 0u;
        State& s = state(u.resource);
        const bool layoutChange = layout != s.layout;
        Barrier barrier{u.resource, 0, 0, stages, access, s.layout, layout};
        if (write || layoutChange) {
            // Write after write or read (or a layout transition, itself a write): after every earlier access.
            barrier.srcStages = s.writeStages | s.readStages;
            barrier.srcAccess = s.writeAccess;
            if (u.discard) barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            if (barrier.srcStages != 0 || layoutChange) barriers_.push_back(barrier);
            if (write) {
                s.writeStages = stages;
                s.writeAccess = access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
                s.readStages = 0;
                s.visibleTo = 0;
            } else {
                // A read after a layout transition: later barriers chain on the transition's stages.
                s.writeStages = stages;
                s.writeAccess = 0;
                s.readStages = stages;
                s.visibleTo = usages;
            }
            s.layout = layout;
        } else {
            // Read after write: once per use that has not seen the write yet; reads after reads need none.
            if (s.writeStages != 0 && (s.visibleTo & usages) != usages) {
                barrier.srcStages = s.writeStages;
                barrier.srcAccess = s.writeAccess;
                barriers_.push_back(barrier);
                s.visibleTo |= usages;
            }
            s.readStages |= stages;
        }
    }
    if (recordPasses) passes_.push_back({std::string(pass), merged_, barriers_});
    return barriers_;
}

void FrameGraph::forget(ResourceKey resource) {
    state(resource) = State{.id = resource.id};
    forgotten_.push_back(resource);
}

void FrameGraph::assumeWritten(ResourceKey resource, Usage usage) {
    const UsageInfo ui = info(usage);
    State& s = state(resource);
    s.writeStages = ui.stages;
    s.writeAccess = ui.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
    s.readStages = 0;
    s.visibleTo = 0;
    s.layout = resource.texture ? uint32_t(ui.layout) : 0u;
}

void FrameGraph::setName(ResourceKey resource, const std::string& name) {
    auto& names = resource.texture ? textureNames_ : bufferNames_;
    const uint32_t slot = slotOf(resource);
    if (slot >= names.size()) names.resize(slot + 1);
    names[slot] = {resource.id, name};
}

std::string FrameGraph::name(ResourceKey resource) const {
    const auto& names = resource.texture ? textureNames_ : bufferNames_;
    const uint32_t slot = slotOf(resource);
    if (slot < names.size() && names[slot].first == resource.id) return names[slot].second;
    return std::string(resource.texture ? "texture " : "buffer ") + std::to_string(resource.id);
}

uint32_t FrameGraph::layout(TextureHandle texture) const {
    const uint32_t slot = slotOf({texture.id, true});
    return slot < textures_.size() && textures_[slot].id == texture.id ? textures_[slot].layout : 0u;
}

void FrameGraph::beginFrame() {
    savedBuffers_ = buffers_;
    savedTextures_ = textures_;
    forgotten_.clear();
    passes_.clear();
}

void FrameGraph::abandonFrame() {
    buffers_ = savedBuffers_;
    textures_ = savedTextures_;
    for (ResourceKey resource : forgotten_) state(resource) = State{.id = resource.id};
    forgotten_.clear();
}

}  // namespace penumbra::gpu
