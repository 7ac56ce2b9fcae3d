// The suballocator behind every GPU memory block (gpu/offset_allocator.h).
#include <gtest/gtest.h>

#include "gpu/offset_allocator.h"
#include "penumbra/error.h"

namespace penumbra::gpu {
namespace {

TEST(OffsetAllocator, FirstAllocationStartsAtZero) {
    OffsetAllocator allocator(1024);
    EXPECT_EQ(allocator.allocate(100, 1), 0u);
    EXPECT_EQ(allocator.usedBytes(), 100u);
}

TEST(OffsetAllocator, OffsetsHonourTheAlignment) {
    OffsetAllocator allocator(4096);
    ASSERT_EQ(allocator.allocate(10, 1), 0u);
    const auto aligned = allocator.allocate(64, 256);
    ASSERT_TRUE(aligned);
    EXPECT_EQ(*aligned % 256, 0u);
    EXPECT_EQ(*aligned, 256u);
}

TEST(OffsetAllocator, AllocationsNeverOverlap) {
    OffsetAllocator allocator(1 << 16);
    std::vector<std::pair<uint64_t, uint64_t>> ranges;
    for (uint64_t size : {100u, 3000u, 17u, 512u, 4096u, 1u, 999u}) {
        const auto offset = allocator.allocate(size, 16);
        ASSERT_TRUE(offset);
        for (const auto& [start, length] : ranges) EXPECT_TRUE(*offset >= start + length || *offset + size <= start);
        ranges.emplace_back(*offset, size);
    }
}

TEST(OffsetAllocator, FullRangeRefusesMore) {
    OffsetAllocator allocator(1000);
    ASSERT_TRUE(allocator.allocate(1000, 1));
    EXPECT_FALSE(allocator.allocate(1, 1));
}

TEST(OffsetAllocator, FreedRangeIsReused) {
    OffsetAllocator allocator(1000);
    const auto a = allocator.allocate(400, 1);
    ASSERT_TRUE(allocator.allocate(400, 1));
    allocator.free(*a);
    EXPECT_EQ(allocator.allocate(400, 1), a);
}

TEST(OffsetAllocator, NeighboursMergeOnFreeSoTheWholeRangeFitsAgain) {
    OffsetAllocator allocator(900);
    const auto a = allocator.allocate(300, 1), b = allocator.allocate(300, 1), c = allocator.allocate(300, 1);
    allocator.free(*a);
    allocator.free(*c);
    allocator.free(*b);  // merges with both neighbours
    EXPECT_EQ(allocator.freeRangeCount(), 1u);
    EXPECT_TRUE(allocator.empty());
    EXPECT_EQ(allocator.allocate(900, 1), 0u);
}

TEST(OffsetAllocator, AlignmentPaddingIsGivenBackOnFree) {
    OffsetAllocator allocator(1024);
    ASSERT_TRUE(allocator.allocate(1, 1));
    const auto padded = allocator.allocate(100, 512);
    ASSERT_EQ(padded, 512u);
    allocator.free(*padded);
    EXPECT_EQ(allocator.usedBytes(), 1u);
    EXPECT_EQ(allocator.allocate(1023, 1), 1u);
}

TEST(OffsetAllocator, FreeingAnUnknownOffsetThrows) {
    OffsetAllocator allocator(100);
    EXPECT_THROW(allocator.free(5), Error);
}

}  // namespace
}  // namespace penumbra::gpu
