// The virtual shadow maps' physical page pool (src/shadows/virtual_page_pool.h): allocation on request,
// caching across frames, keep-alive of unrequested pages, least-recently-requested eviction, overflow,
// and invalidation by light and by caster bounds.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "shadows/virtual_page_pool.h"

namespace penumbra {
namespace {

VirtualPageKey page(int32_t x, int32_t y = 0, uint32_t map = 0) { return {map, {x, y}}; }

// Requests the pages, then draws every page that needs it (as the renderer would).
VirtualPageFrame frameWith(VirtualPagePool& pool, const std::vector<VirtualPageKey>& requests) {
    const VirtualPageFrame frame = pool.update(requests);
    for (const VirtualPageKey& key : requests)
        if (pool.needsDraw(key)) pool.markDrawn(key);
    return frame;
}

TEST(VirtualPagePool, ARequestedPageIsAllocatedAndMustBeDrawn) {
    VirtualPagePool pool(4, 2);
    const VirtualPageFrame frame = pool.update(std::vector{page(3)});
    EXPECT_EQ(frame.allocated, 1u);
    EXPECT_EQ(frame.toDraw, 1u);
    EXPECT_TRUE(pool.needsDraw(page(3)));
    EXPECT_EQ(pool.physicalPage(page(3)), 0u);
}

TEST(VirtualPagePool, ADrawnPageRequestedAgainIsCachedAndNotDrawnAgain) {
    VirtualPagePool pool(4, 2);
    frameWith(pool, {page(1), page(2)});
    const VirtualPageFrame second = frameWith(pool, {page(1), page(2)});
    EXPECT_EQ(second.cached, 2u);
    EXPECT_EQ(second.allocated, 0u);
    EXPECT_EQ(second.toDraw, 0u);
}

TEST(VirtualPagePool, DuplicateRequestsCountOnce) {
    VirtualPagePool pool(4, 2);
    const VirtualPageFrame frame = pool.update(std::vector{page(1), page(1), page(1)});
    EXPECT_EQ(frame.requested, 1u);
    EXPECT_EQ(pool.residentCount(), 1u);
}

TEST(VirtualPagePool, UnrequestedPagesAreKeptForKeepFramesThenFreed) {
    VirtualPagePool pool(4, 2);
    frameWith(pool, {page(1)});
    frameWith(pool, {});
    frameWith(pool, {});
    EXPECT_TRUE(pool.resident(page(1))) << "kept for 2 frames without a request";
    const VirtualPageFrame freed = frameWith(pool, {});
    EXPECT_FALSE(pool.resident(page(1)));
    EXPECT_EQ(freed.evicted, 1u);
    const VirtualPageFrame again = frameWith(pool, {page(1)});
    EXPECT_EQ(again.allocated, 1u) << "a freed page is drawn again when it is requested again";
}

TEST(VirtualPagePool, APageRequestedAgainAfterExactlyKeepFramesIdleFramesIsStillCached) {
    VirtualPagePool pool(4, 2);
    frameWith(pool, {page(1)});
    frameWith(pool, {});
    frameWith(pool, {});
    const VirtualPageFrame again = frameWith(pool, {page(1)});
    EXPECT_EQ(again.cached, 1u);
    EXPECT_EQ(again.evicted, 0u);
    EXPECT_EQ(again.toDraw, 0u);
}

TEST(VirtualPagePool, AFullPoolGivesTheLeastRecentlyRequestedPageToANewOne) {
    VirtualPagePool pool(2, 10);
    frameWith(pool, {page(1)});
    frameWith(pool, {page(2)});
    const uint32_t physicalOfOldest = *pool.physicalPage(page(1));
    const VirtualPageFrame frame = frameWith(pool, {page(3)});
    EXPECT_EQ(frame.evicted, 1u);
    EXPECT_FALSE(pool.resident(page(1)));
    EXPECT_TRUE(pool.resident(page(2)));
    EXPECT_EQ(pool.physicalPage(page(3)), physicalOfOldest);
}

TEST(VirtualPagePool, PagesRequestedThisFrameAreNeverTakenAndTheRestOverflows) {
    VirtualPagePool pool(2, 10);
    frameWith(pool, {page(1), page(2)});
    // The new page comes first in the list; the resident ones are still kept.
    const VirtualPageFrame frame = frameWith(pool, {page(3), page(1), page(2)});
    EXPECT_EQ(frame.overflowed, 1u);
    EXPECT_EQ(frame.cached, 2u);
    EXPECT_FALSE(pool.resident(page(3)));
    EXPECT_TRUE(pool.resident(page(1)) && pool.resident(page(2)));
}

TEST(VirtualPagePool, ResidentPagesHoldDistinctPhysicalPages) {
    VirtualPagePool pool(16, 1);
    for (int32_t f = 0; f < 20; ++f) {
        std::vector<VirtualPageKey> requests;
        for (int32_t i = 0; i < 12; ++i) requests.push_back(page(f + i, i % 3, uint32_t(i % 2)));
        frameWith(pool, requests);
        std::set<uint32_t> physical;
        for (const VirtualPageKey& key : requests)
            if (const auto p = pool.physicalPage(key)) {
                EXPECT_LT(*p, 16u);
                EXPECT_TRUE(physical.insert(*p).second) << "frame " << f;
            }
    }
}

TEST(VirtualPagePool, AChangedLightRedrawsEveryPageOfItsMapsOnly) {
    VirtualPagePool pool(8, 2);
    frameWith(pool, {page(1, 0, 0), page(2, 0, 0), page(1, 0, 1)});
    pool.invalidateMap(0);
    EXPECT_TRUE(pool.needsDraw(page(1, 0, 0)));
    EXPECT_TRUE(pool.needsDraw(page(2, 0, 0)));
    EXPECT_FALSE(pool.needsDraw(page(1, 0, 1)));
    EXPECT_EQ(pool.update(std::vector{page(1, 0, 0), page(2, 0, 0), page(1, 0, 1)}).toDraw, 2u);
}

TEST(VirtualPagePool, AMovedCasterRedrawsOnlyThePagesItsBoundsTouch) {
    VirtualPagePool pool(16, 2);
    std::vector<VirtualPageKey> grid;
    for (int32_t y = 0; y < 3; ++y)
        for (int32_t x = 0; x < 3; ++x) grid.push_back(page(x, y));
    frameWith(pool, grid);
    pool.invalidatePages(0, PageRect{{1, 1}, {2, 1}});  // old bounds
    pool.invalidatePages(0, PageRect{{0, 2}, {0, 2}});  // new bounds
    pool.invalidatePages(1, PageRect{{0, 0}, {2, 2}});  // another map's pages: none resident
    std::set<std::pair<int32_t, int32_t>> dirty;
    for (const VirtualPageKey& key : grid)
        if (pool.needsDraw(key)) dirty.insert({key.page.x, key.page.y});
    EXPECT_EQ(dirty, (std::set<std::pair<int32_t, int32_t>>{{1, 1}, {2, 1}, {0, 2}}));
}

TEST(VirtualPagePool, ReleaseOutsideFreesOnlyThatMapsPagesOutsideTheWindow) {
    VirtualPagePool pool(8, 10);
    frameWith(pool, {page(0, 0, 0), page(3, 0, 0), page(4, 1, 0), page(4, 1, 1)});
    EXPECT_EQ(pool.releaseOutside(0, PageRect{{1, 0}, {4, 3}}), 1u);
    EXPECT_FALSE(pool.resident(page(0, 0, 0)));
    EXPECT_TRUE(pool.resident(page(3, 0, 0)));
    EXPECT_TRUE(pool.resident(page(4, 1, 0)));
    EXPECT_TRUE(pool.resident(page(4, 1, 1))) << "another map's page";
}

TEST(VirtualPagePool, PagesReleasedOutsideTheWindowCountAsEvictedInTheNextUpdate) {
    VirtualPagePool pool(8, 10);
    frameWith(pool, {page(0), page(1), page(2)});
    pool.releaseOutside(0, PageRect{{2, 0}, {5, 0}});
    const VirtualPageFrame frame = frameWith(pool, {page(2)});
    EXPECT_EQ(frame.evicted, 2u);
    EXPECT_EQ(frameWith(pool, {page(2)}).evicted, 0u) << "counted once";
}

TEST(VirtualPagePool, ReleasedPhysicalPagesServeNewRequestsWithoutEviction) {
    VirtualPagePool pool(2, 10);
    frameWith(pool, {page(0), page(1)});
    pool.releaseOutside(0, PageRect{{1, 0}, {2, 0}});
    const VirtualPageFrame frame = frameWith(pool, {page(1), page(2)});
    EXPECT_EQ(frame.allocated, 1u);
    EXPECT_EQ(frame.overflowed, 0u);
    EXPECT_EQ(frame.evicted, 1u) << "page 0, released; page 1 is kept";
    EXPECT_TRUE(pool.resident(page(1)));
}

TEST(VirtualPagePool, TheFrameReportsTheResidentPagesAfterIt) {
    VirtualPagePool pool(4, 0);
    EXPECT_EQ(frameWith(pool, {page(0), page(1), page(2)}).resident, 3u);
    EXPECT_EQ(frameWith(pool, {page(1)}).resident, 1u) << "keepFrames 0 frees the unrequested ones at once";
    std::vector<VirtualPageKey> resident = pool.residentPages();
    ASSERT_EQ(resident.size(), 1u);
    EXPECT_EQ(resident[0], page(1));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(VirtualPoolPressure, AnOverflowingFrameGoesOneStepCoarserUpToTheLimit) {
    const VirtualPoolLoad overflowing{3000, 975, 2025};
    EXPECT_EQ(nextPoolPressureSteps(0, overflowing), 1u);
    EXPECT_EQ(nextPoolPressureSteps(1, overflowing), 2u);
    EXPECT_EQ(nextPoolPressureSteps(kMaxPoolPressureSteps, overflowing), kMaxPoolPressureSteps);
}

TEST(VirtualPoolPressure, AStepFinerOnlyWhenFourTimesThePagesFillAtMostHalfThePool) {
    EXPECT_EQ(nextPoolPressureSteps(1, {821, 0, 2025}), 1u);  // 3284 pages a step finer: more than the pool
    EXPECT_EQ(nextPoolPressureSteps(1, {300, 0, 2025}), 1u);  // 1200 > half the pool: stays (hysteresis)
    EXPECT_EQ(nextPoolPressureSteps(1, {253, 0, 2025}), 0u);  // 1012 <= 1012
    EXPECT_EQ(nextPoolPressureSteps(2, {100, 0, 2025}), 1u);  // one step a frame
}

TEST(VirtualPoolPressure, AFittingPoolAtTheSettingStaysThere) {
    EXPECT_EQ(nextPoolPressureSteps(0, {0, 0, 2025}), 0u);
    EXPECT_EQ(nextPoolPressureSteps(0, {2025, 0, 2025}), 0u);
}

}  // namespace
}  // namespace penumbra
