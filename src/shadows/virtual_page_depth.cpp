#include "shadows/virtual_page_depth.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace penumbra {

using gpu_data::kVirtualPageDepthCodeFar;
using gpu_data::kVirtualPageDepthCodeMax;

VirtualPageDepthRange virtualPageDepthRange(std::span<const float> depths) {
    float nearest = 1.0f, farthest = -1.0f;
    for (float depth : depths) {
        depth = std::max(depth, 0.0f);
        if (!(depth < 1.0f)) continue;
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    VirtualPageDepthRange range;
    range.depthMin = nearest;
    range.depthStep = farthest > nearest ? (farthest - nearest) / float(kVirtualPageDepthCodeMax) : 0.0f;
    return range;
}

uint32_t virtualPageDepthCode(float depth, const VirtualPageDepthRange& range) {
    depth = std::max(depth, 0.0f);
    if (!(depth < 1.0f)) return kVirtualPageDepthCodeFar;
    if (!(range.depthStep > 0.0f)) return 0u;
    const float steps = std::ceil((depth - range.depthMin) / range.depthStep);
    uint32_t code = uint32_t(std::clamp(steps, 0.0f, float(kVirtualPageDepthCodeMax)));
    // One more where the division's rounding left it a hair short: it never decodes nearer than drawn.
    if (code < kVirtualPageDepthCodeMax && gpu_data::virtualPageDecodeDepth(code, range.depthMin, range.depthStep) < depth) ++code;
    return code;
}

VirtualPoolCodes encodeVirtualPool(std::span<const float> texels, uint32_t poolSide, uint32_t pageSize) {
    PENUMBRA_ASSERT(pageSize > 0 && poolSide % pageSize == 0 && texels.size() % poolSide == 0);
    const uint32_t rows = uint32_t(texels.size() / poolSide), columns = poolSide / pageSize, squareRows = rows / pageSize;
    VirtualPoolCodes pool;
    pool.poolSide = poolSide;
    pool.pageSize = pageSize;
    pool.codes.assign(size_t(rows) * poolSide, uint16_t(kVirtualPageDepthCodeFar));
    pool.squareRanges.resize(size_t(columns) * squareRows);
    std::vector<float> page(size_t(pageSize) * pageSize);
    for (uint32_t square = 0; square < pool.squareRanges.size(); ++square) {
        const uint32_t x0 = square % columns * pageSize, y0 = square / columns * pageSize;
        for (uint32_t y = 0; y < pageSize; ++y)
            std::copy_n(texels.begin() + std::ptrdiff_t(size_t(y0 + y) * poolSide + x0), pageSize, page.begin() + std::ptrdiff_t(y * pageSize));
        const VirtualPageDepthRange range = virtualPageDepthRange(page);
        pool.squareRanges[square] = range;
        for (uint32_t y = 0; y < pageSize; ++y)
            for (uint32_t x = 0; x < pageSize; ++x)
                pool.codes[size_t(y0 + y) * poolSide + x0 + x] = uint16_t(virtualPageDepthCode(page[y * pageSize + x], range));
    }
    return pool;
}

void setVirtualPageRanges(std::span<gpu_data::VirtualPageEntry> entries, const VirtualPoolCodes& pool,
                          uint32_t poolPagesPerSide, uint32_t poolOriginY) {
    const uint32_t columns = pool.poolSide / pool.pageSize, firstSquare = poolOriginY / pool.pageSize * columns;
    for (gpu_data::VirtualPageEntry& entry : entries) {
        if (entry.physicalPage >= poolPagesPerSide * poolPagesPerSide) continue;
        const uint32_t square = firstSquare + entry.physicalPage / poolPagesPerSide * columns + entry.physicalPage % poolPagesPerSide;
        PENUMBRA_ASSERT(square < pool.squareRanges.size());
        entry.depthMin = pool.squareRanges[square].depthMin;
        entry.depthStep = pool.squareRanges[square].depthStep;
    }
}

std::vector<uint8_t> virtualPoolTexelBytes(std::span<const uint16_t> codes, uint32_t bytesPerTexel) {
    PENUMBRA_ASSERT(bytesPerTexel == 2 || bytesPerTexel == 4);
    std::vector<uint8_t> bytes(codes.size() * bytesPerTexel);
    for (size_t i = 0; i < codes.size(); ++i) {
        if (bytesPerTexel == 2) {
            std::memcpy(bytes.data() + i * 2, &codes[i], 2);
            continue;
        }
        const float value = gpu_data::virtualPageTexelOfCode(codes[i]);
        std::memcpy(bytes.data() + i * 4, &value, 4);
    }
    return bytes;
}

std::vector<uint16_t> virtualPoolCodesOfBytes(std::span<const uint8_t> bytes, uint32_t bytesPerTexel) {
    PENUMBRA_ASSERT((bytesPerTexel == 2 || bytesPerTexel == 4) && bytes.size() % bytesPerTexel == 0);
    std::vector<uint16_t> codes(bytes.size() / bytesPerTexel);
    for (size_t i = 0; i < codes.size(); ++i) {
        if (bytesPerTexel == 2) {
            std::memcpy(&codes[i], bytes.data() + i * 2, 2);
            continue;
        }
        float value;
        std::memcpy(&value, bytes.data() + i * 4, 4);
        codes[i] = uint16_t(gpu_data::virtualPageCodeOfTexel(value));
    }
    return codes;
}

float virtualPoolDepth(std::span<const uint16_t> codes, uint32_t codesPerRow, uint32_t x, uint32_t y,
                       const VirtualPageDepthRange& range) {
    const size_t index = size_t(y) * codesPerRow + x;
    PENUMBRA_ASSERT(x < codesPerRow && index < codes.size());
    return gpu_data::virtualPageDecodeDepth(codes[index], range.depthMin, range.depthStep);
}

}  // namespace penumbra
