#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/recycling_queue.h"

using namespace penumbra;

TEST(RecyclingQueue, GivesElementsBackInTheOrderTheyWerePushed) {
    RecyclingQueue<int> queue;
    for (int i = 0; i < 3; ++i) queue.pushBack() = i;
    EXPECT_EQ(queue.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(queue.front(), i);
        queue.popFront();
    }
    EXPECT_TRUE(queue.empty());
}

TEST(RecyclingQueue, ARecycledSlotKeepsItsElementsStorage) {
    RecyclingQueue<std::vector<int>> queue;
    queue.pushBack().assign(100, 7);
    const int* storage = queue.front().data();
    queue.popFront();
    std::vector<int>& again = queue.pushBack();
    EXPECT_EQ(again.data(), storage);
    EXPECT_GE(again.capacity(), 100u);
}

TEST(RecyclingQueue, GrowingWhileWrappedKeepsTheOrder) {
    RecyclingQueue<std::string> queue;
    queue.pushBack() = "a";
    queue.pushBack() = "b";
    queue.popFront();         // the slot of "a" is free, "b" is second
    queue.pushBack() = "c";   // wraps into the first slot
    queue.pushBack() = "d";   // full: grows
    ASSERT_EQ(queue.size(), 3u);
    EXPECT_EQ(queue[0], "b");
    EXPECT_EQ(queue[1], "c");
    EXPECT_EQ(queue[2], "d");
    EXPECT_EQ(queue.back(), "d");
}

TEST(RecyclingQueue, EraseKeepsTheOtherElementsInOrder) {
    RecyclingQueue<int> queue;
    for (int i = 0; i < 4; ++i) queue.pushBack() = i;
    queue.erase(1);
    ASSERT_EQ(queue.size(), 3u);
    EXPECT_EQ(queue[0], 0);
    EXPECT_EQ(queue[1], 2);
    EXPECT_EQ(queue[2], 3);
}

TEST(RecyclingQueue, PopBackDropsTheNewestElement) {
    RecyclingQueue<int> queue;
    queue.pushBack() = 1;
    queue.pushBack() = 2;
    queue.popBack();
    ASSERT_EQ(queue.size(), 1u);
    EXPECT_EQ(queue.back(), 1);
}
