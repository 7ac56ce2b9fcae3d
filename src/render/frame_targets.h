#pragma once
// The textures a frame renders into (both shadow atlases, colour, depth) and the host buffers it
// reads back through. They live across frames; ensure() re-makes only those whose size or format
// changed (the old ones are destroyed once no frame in flight uses them).
#include "gpu/device.h"

namespace penumbra {

struct FrameTargetSizes {
    uint32_t directionalAtlas = 1;  // 1 when no directional light is reserved
    uint32_t otherAtlas = 1;        // 1 when no spot/point light is reserved
    uint32_t width = 1, height = 1;
    gpu::Format colorFormat = gpu::Format::RGBA8Srgb;
    bool computeRaster = false;     // the compute rasterizer's depth buffers
    bool hardwareRaster = true;     // the hardware rasterizer's depth targets (shadows.raster hw or auto)
    bool operator==(const FrameTargetSizes&) const = default;
};

class FrameTargets {
public:
    explicit FrameTargets(gpu::Device& device) : device_(device) {}
    ~FrameTargets();
    FrameTargets(const FrameTargets&) = delete;
    FrameTargets& operator=(const FrameTargets&) = delete;

    void ensure(const FrameTargetSizes& sizes);
    // Host-visible buffers the size of the colour target / the atlases (made on first use).
    gpu::BufferHandle colorReadback();
    gpu::BufferHandle directionalReadback();
    gpu::BufferHandle otherReadback();

    const FrameTargetSizes& sizes() const { return sizes_; }
    // The atlases are R32F (sampled, written by compute passes); color: the one of sizes().colorFormat.
    gpu::TextureHandle directionalAtlas, otherAtlas, color, depth;
    // sizes().hardwareRaster: the hardware rasterizer's D32 depth target of each atlas, copied into it.
    gpu::TextureHandle directionalHardwareDepth, otherHardwareDepth;
    // sizes().computeRaster: the compute rasterizer's depth (uint per texel) of each atlas. Neither
    // rasterizer's depth holds the cached tiles for the lit pass: the atlas does (drawn rects are copied).
    gpu::BufferHandle directionalRasterDepth, otherRasterDepth;
    // Bumped whenever the atlas is re-made: its cached tiles are gone.
    uint64_t directionalGeneration = 0, otherGeneration = 0;

private:
    gpu::BufferHandle readbackBuffer(gpu::BufferHandle& buffer, uint64_t size, const char* name);
    void replace(gpu::TextureHandle& texture, const gpu::TextureDesc& desc);

    gpu::Device& device_;
    FrameTargetSizes sizes_;
    bool made_ = false;
    gpu::BufferHandle colorReadback_, directionalReadback_, otherReadback_;
    // One colour target per format, so frames that alternate colour and AOV outputs re-make nothing.
    gpu::TextureHandle colorSrgb_, colorUnorm_;
};

}  // namespace penumbra
