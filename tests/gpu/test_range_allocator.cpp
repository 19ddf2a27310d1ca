// The bookkeeping of Penumbra's default device memory allocator: aligned first-fit ranges
// in a block, padding kept free, and freed ranges merged back into one.
#include <gtest/gtest.h>

#include "gpu/range_allocator.hpp"

namespace penumbra::gpu {
namespace {

TEST(RangeAllocator, PlacesAlignedRangesAndKeepsThePaddingFree) {
    RangeAllocator ranges(1024);
    EXPECT_EQ(ranges.allocate(10, 1), 0u);
    EXPECT_EQ(ranges.allocate(100, 64), 64u);  // 10..64 stays free
    EXPECT_EQ(ranges.allocate(54, 2), 10u);    // and is found first
    EXPECT_EQ(ranges.free_bytes(), 1024u - 10 - 100 - 54);
    EXPECT_EQ(ranges.allocate(860, 1), 164u);  // exactly the rest
    EXPECT_EQ(ranges.allocate(1, 1), std::nullopt);
    EXPECT_EQ(ranges.free_bytes(), 0u);
}

TEST(RangeAllocator, FreedRangesMergeWithTheirNeighbours) {
    RangeAllocator ranges(4096);
    const auto a = ranges.allocate(1000, 256);
    const auto b = ranges.allocate(1000, 256);
    const auto c = ranges.allocate(1000, 256);
    ASSERT_TRUE(a && b && c);
    EXPECT_TRUE(ranges.free(*a));
    EXPECT_TRUE(ranges.free(*c));
    EXPECT_FALSE(ranges.empty());
    EXPECT_EQ(ranges.free_ranges(), 2u);  // [0, 1024) and from c's start on; b between
    EXPECT_TRUE(ranges.free(*b));
    EXPECT_TRUE(ranges.empty());
    EXPECT_EQ(ranges.free_ranges(), 1u);
    EXPECT_EQ(ranges.free_bytes(), 4096u);
    EXPECT_EQ(ranges.allocate(4096, 4096), 0u) << "the whole block again";
}

TEST(RangeAllocator, RefusesWhatCannotBePlaced) {
    RangeAllocator ranges(1000);
    EXPECT_EQ(ranges.allocate(0, 1), std::nullopt);
    EXPECT_EQ(ranges.allocate(8, 3), std::nullopt) << "alignment not a power of two";
    EXPECT_EQ(ranges.allocate(8, 0), std::nullopt);
    EXPECT_EQ(ranges.allocate(1001, 1), std::nullopt);
    EXPECT_EQ(ranges.allocate(8, 1), 0u);
    EXPECT_EQ(ranges.allocate(600, 512), std::nullopt) << "the only aligned start left, 512, leaves 488 bytes";
    EXPECT_EQ(ranges.allocate(400, 512), 512u);
    EXPECT_FALSE(ranges.free(3)) << "not an offset it returned";
    EXPECT_TRUE(ranges.free(512));
    EXPECT_FALSE(ranges.free(512)) << "freed twice";
    EXPECT_EQ(ranges.free_bytes(), 992u);
}

}  // namespace
}  // namespace penumbra::gpu
