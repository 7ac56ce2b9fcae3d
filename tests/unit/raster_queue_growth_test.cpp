// The compute rasterizer's queues (render/compute_raster_pass.h, queueCapacityFor): a queue that holds what
// a frame asked for stays as it is, one that is too small grows to twice the ask, and none passes its
// limit. A moving camera's needs rise a little on many frames; growth by the ask alone remade a queue on
// every new maximum (47 buffers in 150 orbit frames of a GPU benchmark).
#include <gtest/gtest.h>

#include "render/compute_raster_pass.h"

using penumbra::ComputeRasterPass;

TEST(RasterQueueGrowth, AQueueThatHoldsTheAskKeepsItsSize) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 1000, 1u << 20), 1000u);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 0, 1u << 20), 1000u);
}

TEST(RasterQueueGrowth, AQueueTooSmallGrowsToTwiceTheAsk) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 1001, 1u << 20), 2002u);
}

TEST(RasterQueueGrowth, SlowlyRisingAsksGrowAQueueLogarithmicallyOften) {
    uint32_t capacity = 1000, growths = 0;
    for (uint32_t ask = 1000; ask < 100000; ask += 100) {
        const uint32_t next = ComputeRasterPass::queueCapacityFor(capacity, ask, 1u << 20);
        growths += next != capacity;
        capacity = next;
    }
    EXPECT_LE(growths, 7u);  // 1000 -> 100000 is under 2^7
    EXPECT_GE(capacity, 99900u);
}

TEST(RasterQueueGrowth, NoQueuePassesItsLimit) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 900000, 1u << 19), 1u << 19);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1u << 19, 1u << 20, 1u << 19), 1u << 19);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(0xF0000000u, 0xF0000001u, 0xFFFFFFFFu), 0xFFFFFFFFu);
}
