#include "render/virtual_page_storage.h"

#include <string>
#include <vector>

#include "core/error.h"
#include "shadows/virtual_page_depth.h"
#include "virtual_page_structs.h"

namespace penumbra {

namespace {

// The records of `count` padded up to the next multiple whose bytes are kVirtualPageEntryAlignment-aligned.
uint32_t paddedEntries(uint32_t count) {
    constexpr uint64_t bytes = sizeof(gpu_data::VirtualPageEntry);
    uint32_t padded = count;
    while (padded * bytes % kVirtualPageEntryAlignment != 0) ++padded;
    return padded;
}

}  // namespace

gpu::Format virtualPoolFormat(const gpu::Device& device) {
    return device.hasStorageImageExtendedFormats() ? gpu::Format::R16Unorm : gpu::Format::R32Float;
}

gpu::TextureDesc virtualPoolTextureDesc(gpu::Format format, uint32_t poolSide, uint32_t rows, uint32_t extraUsage,
                                        std::string debugName) {
    PENUMBRA_ASSERT(format == gpu::Format::R16Unorm || format == gpu::Format::R32Float);
    gpu::TextureDesc texture;
    texture.width = poolSide;
    texture.height = rows;
    texture.format = format;
    texture.usage = gpu::kTextureSampled | gpu::kTextureStorage | extraUsage;
    texture.debugName = std::move(debugName);
    return texture;
}

void fillVirtualPoolTextureFar(gpu::Device& device, gpu::TextureHandle texture) {
    const gpu::TextureDesc& desc = device.textureDesc(texture);
    // Once, at creation: every texel the far code.
    const std::vector<uint16_t> far(size_t(desc.width) * desc.height, uint16_t(gpu_data::kVirtualPageDepthCodeFar));
    const std::vector<uint8_t> bytes = virtualPoolTexelBytes(far, virtualPoolBytesPerTexel(desc.format));
    const gpu::BufferHandle staging = device.createBuffer(bytes.size(), gpu::kBufferTransferSrc, gpu::MemoryKind::HostVisible,
                                                          bytes.data(), "virtual page pool upload");
    try {
        gpu::CommandList commands = device.beginCommands();
        commands.pass("virtualPool/init", {gpu::use(staging, gpu::Usage::TransferRead), gpu::discard(texture, gpu::Usage::TransferWrite)});
        commands.copyBufferToTexture(staging, texture);
        device.submitAndWait(commands);
    } catch (...) {
        device.destroy(staging);
        throw;
    }
    device.destroy(staging);
}

VirtualPageStorageSet::VirtualPageStorageSet(gpu::Device& device, const VirtualClipmapConfig& clipmap,
                                             uint32_t poolPagesPerSide, uint32_t mapCount)
    : device_(device), mapCount_(mapCount) {
    const uint64_t side = uint64_t(poolPagesPerSide) * clipmap.pageSize;
    const uint32_t levelSide = pagesPerSide(clipmap);
    entriesPerMap_ = clipmap.levelCount * levelSide * levelSide;
    entryStride_ = paddedEntries(entriesPerMap_);
    if (mapCount == 0 || side == 0 || entriesPerMap_ == 0)
        throw Error("virtual page storage: " + std::to_string(mapCount) + " maps of " + std::to_string(side) +
                    " texels and " + std::to_string(entriesPerMap_) + " entries");
    if (side * mapCount > device.maxImageSize())
        throw Error("virtual page storage: " + std::to_string(mapCount) + " pools of " + std::to_string(side) +
                    " texels do not fit an image of " + std::to_string(device.maxImageSize()) + " texels");
    const uint64_t entryBytes = uint64_t(entryStride_) * mapCount * sizeof(gpu_data::VirtualPageEntry);
    if (entryBytes > device.maxStorageBufferRange())
        throw Error("virtual page storage: " + std::to_string(mapCount) + " page tables of " +
                    std::to_string(entriesPerMap_) + " entries exceed the storage buffer range");
    poolSide_ = uint32_t(side);
    try {
        // Empty maps: no entry resident (as virtual_page_reset.comp leaves a table), every texel far.
        const gpu_data::VirtualPageEntry none{gpu_data::kVirtualPageNone, 0u, 0, 0, 0u, 0.0f, 0.0f, 0u};
        const std::vector<gpu_data::VirtualPageEntry> entries(size_t(entryStride_) * mapCount, none);
        entries_ = device.createBuffer(entryBytes, gpu::kBufferStorage | gpu::kBufferTransferSrc, gpu::MemoryKind::DeviceLocal,
                                       entries.data(), "virtual page tables (shared)");
        poolTexture_ = device.createTexture(virtualPoolTextureDesc(virtualPoolFormat(device), poolSide_, poolSide_ * mapCount,
                                                                   gpu::kTextureTransferDst | gpu::kTextureTransferSrc,
                                                                   "virtual page pools (shared)"));
        fillVirtualPoolTextureFar(device, poolTexture_);
    } catch (...) {
        release();  // the destructor does not run
        throw;
    }
}

VirtualPageStorageSet::~VirtualPageStorageSet() { release(); }

void VirtualPageStorageSet::release() {
    device_.destroy(entries_);
    device_.destroy(poolTexture_);
}

VirtualPageStorage VirtualPageStorageSet::storageFor(uint32_t map) const {
    PENUMBRA_ASSERT(map < mapCount_);
    return {poolTexture_, map * poolSide_, entries_, map * entryStride_};
}

}  // namespace penumbra
