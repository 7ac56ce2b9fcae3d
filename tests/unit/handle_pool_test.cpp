// The Device's object slots (gpu/handle_pool.h): freed ids are reused, so slots do not grow.
#include <gtest/gtest.h>

#include "gpu/handle_pool.h"

namespace penumbra::gpu {
namespace {

TEST(HandlePool, IdZeroIsNeverHandedOut) {
    HandlePool<int> pool;
    EXPECT_NE(pool.insert(7), 0u);
    EXPECT_FALSE(pool.contains(0));
}

TEST(HandlePool, RemovedSlotIsReusedByTheNextInsert) {
    HandlePool<int> pool;
    const uint32_t a = pool.insert(1);
    pool.insert(2);
    EXPECT_EQ(pool.remove(a), 1);
    EXPECT_EQ(pool.insert(3), a);
    EXPECT_EQ(pool.at(a), 3);
}

TEST(HandlePool, MakingAndFreeingFrameAfterFrameKeepsTheSlotCountFlat) {
    HandlePool<int> pool;
    for (int frame = 0; frame < 1000; ++frame) {
        const uint32_t a = pool.insert(frame), b = pool.insert(frame);
        pool.remove(a);
        pool.remove(b);
    }
    EXPECT_EQ(pool.slotCount(), 2u);
    EXPECT_EQ(pool.liveCount(), 0u);
}

TEST(HandlePool, AccessToARemovedHandleThrows) {
    HandlePool<int> pool;
    const uint32_t a = pool.insert(1);
    pool.remove(a);
    EXPECT_FALSE(pool.contains(a));
    EXPECT_THROW(pool.at(a), Error);
}

TEST(HandlePool, ForEachLiveVisitsOnlyLiveSlots) {
    HandlePool<int> pool;
    pool.insert(1);
    const uint32_t b = pool.insert(2);
    pool.insert(3);
    pool.remove(b);
    int sum = 0;
    pool.forEachLive([&](uint32_t, int& value) { sum += value; });
    EXPECT_EQ(sum, 4);
}

}  // namespace
}  // namespace penumbra::gpu
