// The compute rasterizer's queues (render/compute_raster_pass.h, queueCapacityFor): a queue that holds
// twice what a frame asked for stays as it is; one more than half full doubles (or grows to twice the ask)
// before a frame overflows it; none passes its limit. A moving camera's needs rise a little on many
// frames: growth to twice each new maximum remade a queue on every one (47 buffers in 150 orbit frames of a
// GPU benchmark).
#include <gtest/gtest.h>

#include "render/compute_raster_pass.h"

using penumbra::ComputeRasterPass;

TEST(RasterQueueGrowth, AQueueThatHoldsTwiceTheAskKeepsItsSize) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 500, 1u << 20), 1000u);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 0, 1u << 20), 1000u);
}

TEST(RasterQueueGrowth, AQueueMoreThanHalfFullDoublesBeforeItOverflows) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 501, 1u << 20), 2000u);
}

TEST(RasterQueueGrowth, AnOverflowedQueueGrowsToTwiceTheAsk) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 3000, 1u << 20), 6000u);
}

TEST(RasterQueueGrowth, SlowlyRisingAsksGrowAQueueLogarithmicallyOften) {
    uint32_t capacity = 1000, growths = 0;
    for (uint32_t ask = 400; ask < 100000; ask += 100) {
        const uint32_t next = ComputeRasterPass::queueCapacityFor(capacity, ask, 1u << 20);
        growths += next != capacity;
        EXPECT_GE(next, ask) << "the ask " << ask << " overflowed";
        capacity = next;
    }
    EXPECT_LE(growths, 8u);  // 1000 -> 200000 is under 2^8
}

TEST(RasterQueueGrowth, NoQueuePassesItsLimit) {
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1000, 900000, 1u << 19), 1u << 19);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(1u << 19, 1u << 20, 1u << 19), 1u << 19);
    EXPECT_EQ(ComputeRasterPass::queueCapacityFor(0xF0000000u, 0xF0000001u, 0xFFFFFFFFu), 0xFFFFFFFFu);
}
