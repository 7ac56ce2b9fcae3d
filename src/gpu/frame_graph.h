#pragma once
// The frame graph's synchronisation. Every pass declares the buffers and textures it uses and how
// (CommandList::pass); the barriers before it follow from those declarations and from what the
// earlier passes declared: pipeline stages and access masks as narrow as the uses, image layouts
// tracked, and a barrier only where a hazard is (read after write, write after write, write after
// read; reads after reads need none). The state of every resource carries over from frame to frame
// (one queue: a barrier orders against everything submitted before it), so a pass that is skipped
// (a cached shadow atlas, a conditional pass) simply declares nothing.
//
// Pure bookkeeping, no Vulkan calls: CommandList::pass records the barriers this returns, and the
// unit tests check them on the CPU. docs/architecture.md describes it.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/types.h"

namespace penumbra::gpu {

// How a pass uses a resource: the pipeline stages, the memory accesses and, for a texture, its layout.
enum class Usage : uint8_t {
    IndirectArguments,  // buffer: draw or dispatch parameters (vkCmd*Indirect*)
    IndexBuffer,        // buffer: vkCmdBindIndexBuffer
    GraphicsRead,       // buffer: storage buffer read by the vertex and fragment shaders
    ComputeRead,        // buffer: storage buffer read by a compute shader
    ComputeWrite,       // buffer: storage buffer written (and maybe read, atomics) by a compute shader
    ComputeSampled,     // texture: sampled by a compute shader
    FragmentSampled,    // texture: sampled by a fragment shader
    ColorTarget,        // texture: colour attachment (loaded or cleared, stored)
    DepthTarget,        // texture: depth attachment (tested and written)
    TransferRead,       // copy source
    TransferWrite,      // copy destination or fill
    HostRead,           // buffer: mapped and read by the CPU once the submission's fence has signalled
};
constexpr uint32_t kUsageCount = uint32_t(Usage::HostRead) + 1;
const char* usageName(Usage usage);
bool isWrite(Usage usage);

struct ResourceKey {
    uint32_t id = 0;  // the handle's id: slot and generation (gpu/handle_pool.h)
    bool texture = false;
    bool operator==(const ResourceKey&) const = default;
};

// One resource used by a pass. discard (textures): the previous contents are not needed, so the
// layout transition starts from VK_IMAGE_LAYOUT_UNDEFINED (a target cleared or fully rewritten).
struct ResourceUse {
    ResourceKey resource;
    Usage usage = Usage::ComputeRead;
    bool discard = false;
};
inline ResourceUse use(BufferHandle buffer, Usage usage) { return {{buffer.id, false}, usage, false}; }
inline ResourceUse use(TextureHandle texture, Usage usage) { return {{texture.id, true}, usage, false}; }
// A texture whose previous contents the pass does not need (cleared or fully overwritten).
inline ResourceUse discard(TextureHandle texture, Usage usage) { return {{texture.id, true}, usage, true}; }

// One barrier before a pass, as Vulkan values (VkPipelineStageFlags2, VkAccessFlags2, VkImageLayout).
// Buffers: a buffer barrier over the whole buffer; textures: an image barrier over every level.
struct Barrier {
    ResourceKey resource;
    uint64_t srcStages = 0, srcAccess = 0, dstStages = 0, dstAccess = 0;
    uint32_t oldLayout = 0, newLayout = 0;  // equal for buffers (0) and for textures kept in their layout
};

// A declared pass as the graph printers show it (recorded only while FrameGraph::recordPasses is on).
struct PassRecord {
    std::string name;
    std::vector<ResourceUse> uses;
    std::vector<Barrier> barriers;
};

class FrameGraph {
public:
    // The barriers needed before a pass with these uses (in the order of first use), after every
    // pass declared so far; the tracked states move past the pass. A resource used twice by one pass
    // (two bindings) counts once, with the union of its uses; a texture's uses must agree on a layout.
    std::span<const Barrier> declare(std::string_view pass, std::span<const ResourceUse> uses);

    // A destroyed handle: its slot may come back for a new resource, which starts unused.
    void forget(ResourceKey resource);
    // A resource that commands outside the graph (a caller's) last wrote as `usage`, leaving a texture in
    // that usage's layout.
    void assumeWritten(ResourceKey resource, Usage usage);
    // The slots tracked (states are kept per handle slot, not per id: an id carries a generation).
    size_t trackedSlots() const { return buffers_.size() + textures_.size(); }
    // Names shown by the printers (the debug names given at creation).
    void setName(ResourceKey resource, const std::string& name);
    std::string name(ResourceKey resource) const;
    // The layout a texture is in after the passes declared so far (VK_IMAGE_LAYOUT_UNDEFINED = 0
    // before its first use).
    uint32_t layout(TextureHandle texture) const;

    // A frame that is recorded but maybe never submitted: abandonFrame() puts every state back to
    // where beginFrame() found it.
    void beginFrame();
    void abandonFrame();

    // The passes declared since beginFrame, for the printers (off by default: frames record nothing).
    bool recordPasses = false;
    const std::vector<PassRecord>& passes() const { return passes_; }

private:
    struct State {
        uint64_t writeStages = 0, writeAccess = 0;  // the last write (or layout transition)
        uint64_t readStages = 0;                    // stages that read since then
        uint32_t visibleTo = 0;                     // Usage bits the last write was made visible to
        uint32_t layout = 0;
        uint32_t id = 0;  // the id (with its generation) these states belong to
    };
    // The state of the resource's slot; a slot last used by another generation starts unused.
    State& state(ResourceKey resource);

    std::vector<State> buffers_, textures_;
    std::vector<State> savedBuffers_, savedTextures_;
    std::vector<ResourceKey> forgotten_;  // during the frame: forgotten again after abandonFrame
    std::vector<std::pair<uint32_t, std::string>> bufferNames_, textureNames_;  // per slot: id, name
    std::vector<ResourceUse> merged_;
    std::vector<uint32_t> mergedUsages_;
    std::vector<Barrier> barriers_;
    std::vector<PassRecord> passes_;
};

// The recorded passes as a graph: one node per pass, an edge from the pass that last wrote a resource
// to each later pass that uses it (labelled with the resources). format: "mermaid" or "dot".
std::string printFrameGraph(const FrameGraph& graph, const std::string& format);

}  // namespace penumbra::gpu
