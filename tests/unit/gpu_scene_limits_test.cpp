// checkGpuSceneLimits: a scene too large for the GPU layout is an Error naming what overflows, not a
// wrapped 32-bit index or offset (e.g. index counts over 2^32).
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "error_message.h"
#include "render/gpu_scene.h"

using namespace penumbra;

namespace {

constexpr uint64_t kLargeBufferRange = 1ull << 40;

std::string limitError(const GpuSceneTotals& totals, uint64_t maxStorageBufferRange = kLargeBufferRange,
                       uint32_t visibleListBuffers = gpu_data::kVisibleListBuffers) {
    return penumbra::testing::errorMessage(
        [&] { checkGpuSceneLimits(totals, maxStorageBufferRange, visibleListBuffers); });
}

}  // namespace

TEST(GpuSceneLimits, SceneWithinEveryLimitPasses) {
    EXPECT_EQ(limitError({1000, 3000, 10, 2}), "");
}

TEST(GpuSceneLimits, MoreThanTwoToTheThirtyTwoIndicesIsAnError) {
    EXPECT_EQ(limitError({3, 0xFFFFFFFFull, 1, 1}), "");
    EXPECT_NE(limitError({3, 0x100000000ull, 1, 1}).find("4294967296 triangle indices, more than the 2^32 - 1"),
              std::string::npos);
}

TEST(GpuSceneLimits, MoreThanTwoToTheThirtyOneVerticesIsAnError) {
    EXPECT_NE(limitError({0x80000000ull, 3, 1, 1}).find("2147483648 vertices"), std::string::npos);
}

TEST(GpuSceneLimits, ABufferOverTheDeviceStorageRangeIsAnError) {
    // 2^22 vertices of 32 bytes = 128 MiB, over a 64 MiB maxStorageBufferRange.
    EXPECT_NE(limitError({1u << 22, 3, 1, 1}, 64ull << 20).find("its vertices take 128 MiB"), std::string::npos)
        << limitError({1u << 22, 3, 1, 1}, 64ull << 20);
}

namespace {

constexpr uint64_t kVulkanMinimumStorageRange = 128ull << 20;  // maxStorageBufferRange every Vulkan 1.3 device has
constexpr uint64_t kMillionBoxes = 1000001;                     // gen:boxes:1000000: the boxes and the ground

GpuSceneTotals instances(uint64_t count) { return {24, 36, count, 5}; }

}  // namespace

TEST(GpuSceneLimits, AMillionInstancesFitEveryVulkanDevice) {
    // 144-byte records took 137 MiB; the culling lists, 130 MiB in one buffer, split over two.
    EXPECT_EQ(limitError(instances(kMillionBoxes), kVulkanMinimumStorageRange), "");
}

TEST(GpuSceneLimits, CullingListsOfAMillionInstancesNeedMoreThanOneBuffer) {
    EXPECT_NE(limitError(instances(kMillionBoxes), kVulkanMinimumStorageRange, 1)
                  .find("its 1000001 instances need 34 culling lists of 4 MiB, more than 1 of the device's largest"),
              std::string::npos)
        << limitError(instances(kMillionBoxes), kVulkanMinimumStorageRange, 1);
}

TEST(GpuSceneLimits, InstancesFitUntilTheirRecordsFillTheStorageRange) {
    // 64-byte records: 2^21 of them fill 128 MiB exactly.
    EXPECT_EQ(limitError(instances(1u << 21), kVulkanMinimumStorageRange), "");
    EXPECT_NE(limitError(instances((1u << 21) + 1), kVulkanMinimumStorageRange).find("its instances take 129 MiB"),
              std::string::npos)
        << limitError(instances((1u << 21) + 1), kVulkanMinimumStorageRange);
}

TEST(GpuSceneLimits, VisibleListsSplitIntoWholeListsPerBuffer) {
    const VisibleListSplit split = splitVisibleLists(kMillionBoxes, gpu_data::kCullListCount, kVulkanMinimumStorageRange,
                                                     gpu_data::kVisibleListBuffers);
    EXPECT_EQ(split.listsPerBuffer, 33u);  // 33 x 4000004 bytes <= 128 MiB < 34 x 4000004
    EXPECT_EQ(split.bufferCount, 2u);
}
