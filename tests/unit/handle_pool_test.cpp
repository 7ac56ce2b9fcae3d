// The Device's object slots (gpu/handle_pool.h): freed slots are reused, so slots do not grow, and
// every id carries its slot's generation, so a handle kept past its object's destruction is caught.
#include <gtest/gtest.h>

#include "gpu/handle_pool.h"

namespace penumbra::gpu {
namespace {

using Pool = HandlePool<int>;

uint32_t slotOf(uint32_t id) { return id & Pool::kIndexMask; }

// Using a dead id: an assertion failure where PENUMBRA_ASSERT is on (core/error.h: no NDEBUG, or
// PENUMBRA_ENABLE_ASSERTS), a penumbra::Error elsewhere.
#if !defined(NDEBUG) || defined(PENUMBRA_ENABLE_ASSERTS)
#define PENUMBRA_ASSERTS_ACTIVE 1
#else
#define PENUMBRA_ASSERTS_ACTIVE 0
#endif
#if PENUMBRA_ASSERTS_ACTIVE
#define EXPECT_DEAD_HANDLE(statement) EXPECT_DEATH(statement, "internal assertion failed")
#else
#define EXPECT_DEAD_HANDLE(statement) EXPECT_THROW(statement, Error)
#endif

TEST(HandlePool, IdZeroIsNeverHandedOut) {
    Pool pool;
    EXPECT_NE(pool.insert(7), 0u);
    EXPECT_FALSE(pool.contains(0));
}

TEST(HandlePool, IdZeroIsNotAnObject) {
    Pool pool;
    pool.insert(7);
    EXPECT_DEAD_HANDLE(pool.at(0));
}

TEST(HandlePool, RemovedSlotIsReusedByTheNextInsert) {
    Pool pool;
    const uint32_t a = pool.insert(1);
    pool.insert(2);
    EXPECT_EQ(pool.remove(a), 1);
    const uint32_t c = pool.insert(3);
    EXPECT_EQ(slotOf(c), slotOf(a));
    EXPECT_EQ(pool.at(c), 3);
}

TEST(HandlePool, ReusedSlotGetsANewId) {
    Pool pool;
    const uint32_t a = pool.insert(1);
    pool.remove(a);
    EXPECT_NE(pool.insert(2), a);
}

TEST(HandlePool, MakingAndFreeingFrameAfterFrameKeepsTheSlotCountFlat) {
    Pool pool;
    for (int frame = 0; frame < 1000; ++frame) {
        const uint32_t a = pool.insert(frame), b = pool.insert(frame);
        pool.remove(a);
        pool.remove(b);
    }
    EXPECT_EQ(pool.slotCount(), 2u);
    EXPECT_EQ(pool.liveCount(), 0u);
}

TEST(HandlePool, AccessToARemovedHandleIsCaught) {
    Pool pool;
    const uint32_t a = pool.insert(1);
    pool.remove(a);
    EXPECT_FALSE(pool.contains(a));
    EXPECT_DEAD_HANDLE(pool.at(a));
}

TEST(HandlePool, StaleHandleDoesNotNameTheObjectNowInItsSlot) {
    Pool pool;
    const uint32_t stale = pool.insert(1);
    pool.remove(stale);
    const uint32_t fresh = pool.insert(2);
    ASSERT_EQ(slotOf(fresh), slotOf(stale));
    EXPECT_FALSE(pool.contains(stale));
    EXPECT_DEAD_HANDLE(pool.at(stale));
    EXPECT_EQ(pool.at(fresh), 2);
}

TEST(HandlePool, RemovingAStaleHandleIsCaughtAndLeavesTheNewObjectAlive) {
    Pool pool;
    const uint32_t stale = pool.insert(1);
    pool.remove(stale);
    const uint32_t fresh = pool.insert(2);
    EXPECT_DEAD_HANDLE(pool.remove(stale));
    EXPECT_TRUE(pool.contains(fresh));
    EXPECT_EQ(pool.liveCount(), 1u);
}

#if !PENUMBRA_ASSERTS_ACTIVE
TEST(HandlePool, StaleHandleErrorSaysTheHandleIsStale) {
    Pool pool;
    const uint32_t stale = pool.insert(1);
    pool.remove(stale);
    pool.insert(2);
    try {
        pool.at(stale);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("stale"), std::string::npos) << e.what();
    }
}
#endif

TEST(HandlePool, GenerationWrapsWithoutEverHandingOutIdZero) {
    Pool pool;
    uint32_t previous = pool.insert(0);
    for (uint32_t reuse = 1; reuse <= Pool::kGenerations + 1; ++reuse) {
        pool.remove(previous);
        const uint32_t id = pool.insert(int(reuse));
        ASSERT_NE(id, 0u);
        ASSERT_EQ(slotOf(id), slotOf(previous));
        ASSERT_FALSE(pool.contains(previous)) << "reuse " << reuse;
        ASSERT_EQ(pool.at(id), int(reuse));
        previous = id;
    }
    EXPECT_EQ(pool.slotCount(), 1u);
}

TEST(HandlePool, ForEachLiveVisitsOnlyLiveSlotsWithTheirIds) {
    Pool pool;
    const uint32_t a = pool.insert(1);
    const uint32_t b = pool.insert(2);
    pool.remove(b);
    const uint32_t c = pool.insert(3);
    int sum = 0;
    pool.forEachLive([&](uint32_t id, int& value) {
        EXPECT_EQ(pool.at(id), value);
        sum += value;
    });
    EXPECT_EQ(sum, 4);
    EXPECT_TRUE(pool.contains(a) && pool.contains(c));
}

}  // namespace
}  // namespace penumbra::gpu
