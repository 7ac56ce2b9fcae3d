#include "render/frame_targets.h"

#include <algorithm>

#include "core/error.h"

namespace penumbra {

FrameTargets::~FrameTargets() {
    for (gpu::TextureHandle t : {directionalAtlas, otherAtlas, directionalHardwareDepth, otherHardwareDepth, colorSrgb_,
                                 colorUnorm_, depth})
        device_.destroy(t);
    for (gpu::BufferHandle b : {colorReadback_, directionalReadback_, otherReadback_, directionalRasterDepth, otherRasterDepth})
        device_.destroy(b);
}

void FrameTargets::replace(gpu::TextureHandle& texture, const gpu::TextureDesc& desc) {
    device_.destroy(texture);
    texture = device_.createTexture(desc);
}

void FrameTargets::ensure(const FrameTargetSizes& sizes) {
    PENUMBRA_ASSERT(sizes.colorFormat == gpu::Format::RGBA8Srgb || sizes.colorFormat == gpu::Format::RGBA8Unorm);
    if (made_ && sizes == sizes_) return;
    // The atlases: R32F that compute passes write (AtlasCopyPass) and the lit pass gathers; copied out
    // when a test or the viewer captures them.
    const uint32_t atlasUsage = gpu::kTextureSampled | gpu::kTextureStorage | gpu::kTextureTransferSrc;
    if (!made_ || sizes.directionalAtlas != sizes_.directionalAtlas) {
        replace(directionalAtlas, {sizes.directionalAtlas, sizes.directionalAtlas, gpu::Format::R32Float, atlasUsage, 1,
                                   "directional atlas"});
        ++directionalGeneration;
        device_.destroy(directionalReadback_);
        directionalReadback_ = {};
    }
    if (!made_ || sizes.otherAtlas != sizes_.otherAtlas) {
        replace(otherAtlas, {sizes.otherAtlas, sizes.otherAtlas, gpu::Format::R32Float, atlasUsage, 1, "spot/point atlas"});
        ++otherGeneration;
        device_.destroy(otherReadback_);
        otherReadback_ = {};
    }
    // Each rasterizer's own depth (the compute one's buffer of float bits, the hardware one's D32 target),
    // kept across frames with the atlases and made only while that rasterizer may draw. Neither holds the
    // cached tiles for the lit pass (the atlas does: only drawn rects are copied into it), so making or
    // dropping one leaves the atlas's tiles valid (a switch of rasterizer redraws every tile anyway,
    // TileCache).
    // (handle: the texture or buffer; wanted, wasWanted: this and the last ensure's sizes ask for it.)
    auto keepStorage = [&](auto& handle, bool wanted, bool wasWanted, uint32_t size, uint32_t madeSize, auto make) {
        if (!wanted || size != madeSize || !(made_ && wasWanted)) {
            device_.destroy(handle);
            handle = {};
        }
        if (wanted && !handle) handle = make(size);
    };
    const uint32_t madeDirectional = made_ ? sizes_.directionalAtlas : 0, madeOther = made_ ? sizes_.otherAtlas : 0;
    auto hardwareDepth = [&](const char* name) {
        return [this, name](uint32_t size) {
            return device_.createTexture({size, size, gpu::Format::D32Float, gpu::kTextureDepthTarget | gpu::kTextureSampled, 1, name});
        };
    };
    auto rasterDepth = [&](const char* name) {
        return [this, name](uint32_t size) {
            return device_.createBuffer(uint64_t(size) * size * 4, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal, nullptr, name);
        };
    };
    keepStorage(directionalHardwareDepth, sizes.hardwareRaster, sizes_.hardwareRaster, sizes.directionalAtlas, madeDirectional,
                hardwareDepth("directional hardware depth"));
    keepStorage(otherHardwareDepth, sizes.hardwareRaster, sizes_.hardwareRaster, sizes.otherAtlas, madeOther,
                hardwareDepth("spot/point hardware depth"));
    keepStorage(directionalRasterDepth, sizes.computeRaster, sizes_.computeRaster, sizes.directionalAtlas, madeDirectional,
                rasterDepth("directional raster depth"));
    keepStorage(otherRasterDepth, sizes.computeRaster, sizes_.computeRaster, sizes.otherAtlas, madeOther,
                rasterDepth("spot/point raster depth"));
    const bool resized = !made_ || sizes.width != sizes_.width || sizes.height != sizes_.height;
    if (resized) {
        device_.destroy(colorSrgb_);
        device_.destroy(colorUnorm_);
        colorSrgb_ = colorUnorm_ = {};
        replace(depth, {sizes.width, sizes.height, gpu::Format::D32Float,
                        gpu::kTextureDepthTarget | gpu::kTextureSampled | gpu::kTextureTransferDst, 1, "depth"});
        device_.destroy(colorReadback_);
        colorReadback_ = {};
    }
    gpu::TextureHandle& colorOfFormat = sizes.colorFormat == gpu::Format::RGBA8Srgb ? colorSrgb_ : colorUnorm_;
    if (!colorOfFormat)
        colorOfFormat = device_.createTexture({sizes.width, sizes.height, sizes.colorFormat,
                                               gpu::kTextureColorTarget | gpu::kTextureTransferSrc | gpu::kTextureTransferDst, 1,
                                               "color"});
    color = colorOfFormat;
    sizes_ = sizes;
    made_ = true;
}

gpu::BufferHandle FrameTargets::readbackBuffer(gpu::BufferHandle& buffer, uint64_t size, const char* name) {
    if (!buffer) buffer = device_.createBuffer(size, gpu::kBufferTransferDst, gpu::MemoryKind::HostVisible, nullptr, name);
    return buffer;
}

gpu::BufferHandle FrameTargets::colorReadback() {
    return readbackBuffer(colorReadback_, uint64_t(sizes_.width) * sizes_.height * 4, "color readback");
}
gpu::BufferHandle FrameTargets::directionalReadback() {
    return readbackBuffer(directionalReadback_, uint64_t(sizes_.directionalAtlas) * sizes_.directionalAtlas * 4,
                          "directional atlas readback");
}
gpu::BufferHandle FrameTargets::otherReadback() {
    return readbackBuffer(otherReadback_, uint64_t(sizes_.otherAtlas) * sizes_.otherAtlas * 4, "spot/point atlas readback");
}

}  // namespace penumbra
