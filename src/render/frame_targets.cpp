#include "render/frame_targets.h"

#include <algorithm>

#include "core/error.h"

namespace penumbra {

FrameTargets::~FrameTargets() {
    for (gpu::TextureHandle t : {directionalAtlas, otherAtlas, colorSrgb_, colorUnorm_, depth}) device_.destroy(t);
    for (gpu::BufferHandle b : {colorReadback_, directionalReadback_, otherReadback_, rasterDepth}) device_.destroy(b);
}

void FrameTargets::replace(gpu::TextureHandle& texture, const gpu::TextureDesc& desc) {
    device_.destroy(texture);
    texture = device_.createTexture(desc);
}

void FrameTargets::ensure(const FrameTargetSizes& sizes) {
    PENUMBRA_ASSERT(sizes.colorFormat == gpu::Format::RGBA8Srgb || sizes.colorFormat == gpu::Format::RGBA8Unorm);
    if (made_ && sizes == sizes_) return;
    const uint32_t depthUsage = gpu::kTextureDepthTarget | gpu::kTextureSampled;
    if (!made_ || sizes.directionalAtlas != sizes_.directionalAtlas) {
        replace(directionalAtlas,
                {sizes.directionalAtlas, sizes.directionalAtlas, gpu::Format::D32Float, depthUsage, 1, "directional atlas"});
        device_.destroy(directionalReadback_);
        directionalReadback_ = {};
    }
    if (!made_ || sizes.otherAtlas != sizes_.otherAtlas) {
        replace(otherAtlas, {sizes.otherAtlas, sizes.otherAtlas, gpu::Format::D32Float, depthUsage, 1, "spot/point atlas"});
        device_.destroy(otherReadback_);
        otherReadback_ = {};
    }
    const uint32_t rasterSize = std::max(sizes.directionalAtlas, sizes.otherAtlas);
    const uint32_t madeRasterSize = made_ && sizes_.computeRaster ? std::max(sizes_.directionalAtlas, sizes_.otherAtlas) : 0;
    if (!sizes.computeRaster || rasterSize != madeRasterSize) {
        device_.destroy(rasterDepth);
        rasterDepth = {};
    }
    if (sizes.computeRaster && !rasterDepth)
        rasterDepth = device_.createBuffer(uint64_t(rasterSize) * rasterSize * 4, gpu::kBufferStorage,
                                           gpu::MemoryKind::DeviceLocal, nullptr, "shadow raster depth");
    const bool resized = !made_ || sizes.width != sizes_.width || sizes.height != sizes_.height;
    if (resized) {
        device_.destroy(colorSrgb_);
        device_.destroy(colorUnorm_);
        colorSrgb_ = colorUnorm_ = {};
        replace(depth, {sizes.width, sizes.height, gpu::Format::D32Float, gpu::kTextureDepthTarget, 1, "depth"});
        device_.destroy(colorReadback_);
        colorReadback_ = {};
    }
    gpu::TextureHandle& colorOfFormat = sizes.colorFormat == gpu::Format::RGBA8Srgb ? colorSrgb_ : colorUnorm_;
    if (!colorOfFormat)
        colorOfFormat = device_.createTexture({sizes.width, sizes.height, sizes.colorFormat,
                                               gpu::kTextureColorTarget | gpu::kTextureTransferSrc, 1, "color"});
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
