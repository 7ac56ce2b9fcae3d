#include "render/frame_targets.h"

#include <algorithm>

#include "core/error.h"

namespace penumbra {

FrameTargets::~FrameTargets() {
    for (gpu::TextureHandle t : {directionalAtlas, otherAtlas, colorSrgb_, colorUnorm_, depth}) device_.destroy(t);
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
    const uint32_t depthUsage = gpu::kTextureDepthTarget | gpu::kTextureSampled;
    if (!made_ || sizes.directionalAtlas != sizes_.directionalAtlas) {
        replace(directionalAtlas,
                {sizes.directionalAtlas, sizes.directionalAtlas, gpu::Format::D32Float, depthUsage, 1, "directional atlas"});
        ++directionalGeneration;
        device_.destroy(directionalReadback_);
        directionalReadback_ = {};
    }
    if (!made_ || sizes.otherAtlas != sizes_.otherAtlas) {
        replace(otherAtlas, {sizes.otherAtlas, sizes.otherAtlas, gpu::Format::D32Float, depthUsage, 1, "spot/point atlas"});
        ++otherGeneration;
        device_.destroy(otherReadback_);
        otherReadback_ = {};
    }
    auto rasterDepth = [&](gpu::BufferHandle& buffer, uint32_t size, uint32_t madeSize, uint64_t& generation,
                           const char* name) {
        if (!sizes.computeRaster || size != madeSize || !(made_ && sizes_.computeRaster)) {
            if (buffer) ++generation;
            device_.destroy(buffer);
            buffer = {};
        }
        if (sizes.computeRaster && !buffer) {
            buffer = device_.createBuffer(uint64_t(size) * size * 4, gpu::kBufferStorage, gpu::MemoryKind::DeviceLocal,
                                          nullptr, name);
            ++generation;
        }
    };
    rasterDepth(directionalRasterDepth, sizes.directionalAtlas, made_ ? sizes_.directionalAtlas : 0, directionalGeneration,
                "directional raster depth");
    rasterDepth(otherRasterDepth, sizes.otherAtlas, made_ ? sizes_.otherAtlas : 0, otherGeneration, "spot/point raster depth");
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
