#pragma once
// Storage that several directional lights' virtual shadow maps (render/virtual_shadow_map.h) share, so
// that a lit pass binds one pool texture and one page table for all of them.
//
// Layout of a set of mapCount maps of one configuration (VirtualPageStorageSet):
// - the pool texture: 16-bit depth codes (virtual_page_structs.h, "The pool's texels"; R16_UNORM, or
//   R32_SFLOAT on devices without storage images of it: virtualPoolFormat), poolSide = poolPagesPerSide *
//   pageSize texels wide and mapCount * poolSide rows high; map i's pool is the poolSide^2 texels from row i * poolSide, its physical page p
//   at texels (p % poolPagesPerSide, p / poolPagesPerSide) * pageSize from there;
// - the entry buffer: map i's levelCount * pagesPerSide^2 VirtualPageEntry records start at record
//   i * entryStride, entryStride that count padded so that every map's first byte is 256-aligned (the
//   largest minStorageBufferOffsetAlignment Vulkan allows: the table pass binds its own range).
// Each map's passes write only their own square and range (virtual_page_copy.comp at row poolOriginY, the
// page table's descriptors at firstEntry); the lookup finds them through VirtualShadowLookupData's
// poolOriginY and firstEntry (penumbra/shadows/virtual_shadow_lookup.glsl).
//
// The set owns the texture and the buffer and starts them as empty maps (every texel far, no entry
// resident), so a map's passes neither initialize nor destroy them: destroy the set after its maps.
#include <cstdint>
#include <string>

#include "gpu/device.h"
#include "shadows/virtual_clipmap.h"

namespace penumbra {

// The pool textures' format on `device`: R16_UNORM where it has shaderStorageImageExtendedFormats (2 bytes
// a texel), else R32_SFLOAT holding the same values (4).
gpu::Format virtualPoolFormat(const gpu::Device& device);
// The bytes of a texel of a pool texture of `format` (R16Unorm 2, R32Float 4: shadows/virtual_page_depth.h
// virtualPoolTexelBytes).
inline uint32_t virtualPoolBytesPerTexel(gpu::Format format) { return format == gpu::Format::R16Unorm ? 2u : 4u; }
// The pool texture of `rows` rows of poolSide texels in `format` (virtualPoolFormat), sampled and written
// as storage, plus `extraUsage`.
gpu::TextureDesc virtualPoolTextureDesc(gpu::Format format, uint32_t poolSide, uint32_t rows, uint32_t extraUsage,
                                        std::string debugName);
// Every texel of a pool texture (virtualPoolTextureDesc with transfer destination) to far: nothing cast
// (one submission, waited for).
void fillVirtualPoolTextureFar(gpu::Device& device, gpu::TextureHandle texture);

// Where one map lives in storage that several maps share.
struct VirtualPageStorage {
    gpu::TextureHandle poolTexture;  // virtualPoolTextureDesc; this map's pool is the (poolPagesPerSide*pageSize)^2 square at (0, poolOriginY)
    uint32_t poolOriginY = 0;        // texels
    gpu::BufferHandle entries;       // VirtualPageEntry records
    uint32_t firstEntry = 0;         // this map's levelCount * pagesPerSide^2 entries start here
};

// Byte alignment of a map's first entry in a shared entry buffer: the one every bound range keeps.
inline constexpr uint64_t kVirtualPageEntryAlignment = gpu::kPortableBufferOffsetAlignment;

// The pool texture and entry buffer of mapCount maps of clipmap `clipmap` with pools of poolPagesPerSide^2
// pages, initialized on creation (one submission, waited for).
class VirtualPageStorageSet {
public:
    // Throws Error when mapCount is 0 or the texture would exceed the device's image size.
    VirtualPageStorageSet(gpu::Device& device, const VirtualClipmapConfig& clipmap, uint32_t poolPagesPerSide,
                          uint32_t mapCount);
    ~VirtualPageStorageSet();
    VirtualPageStorageSet(const VirtualPageStorageSet&) = delete;
    VirtualPageStorageSet& operator=(const VirtualPageStorageSet&) = delete;

    // Map `map`'s place (map < mapCount()).
    VirtualPageStorage storageFor(uint32_t map) const;

    gpu::TextureHandle poolTexture() const { return poolTexture_; }  // virtualPoolTextureDesc(poolSide(), mapCount() * poolSide())
    gpu::BufferHandle entries() const { return entries_; }          // entryCount() VirtualPageEntry records
    uint32_t mapCount() const { return mapCount_; }
    uint32_t poolSide() const { return poolSide_; }                 // texels along a map's pool's side
    uint32_t entriesPerMap() const { return entriesPerMap_; }       // levelCount * pagesPerSide^2
    uint32_t entryStride() const { return entryStride_; }           // records from one map's first entry to the next's
    uint32_t entryCount() const { return entryStride_ * mapCount_; }  // records in entries()

private:
    void release();
    gpu::Device& device_;
    uint32_t mapCount_ = 0, poolSide_ = 0, entriesPerMap_ = 0, entryStride_ = 0;
    gpu::TextureHandle poolTexture_;
    gpu::BufferHandle entries_;
};

}  // namespace penumbra
