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

std::string limitError(const GpuSceneTotals& totals, uint64_t maxStorageBufferRange = kLargeBufferRange) {
    return penumbra::testing::errorMessage([&] { checkGpuSceneLimits(totals, maxStorageBufferRange); });
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
