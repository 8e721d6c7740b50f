// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/handoff.h"

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "alloc_counter.h"

namespace hapticad {
namespace {

// Counts live instances and poisons itself when destroyed, so a use after free shows.
struct Table {
  static std::atomic<int> live;
  explicit Table(int v) : value(v), canary(0x5AFE) { ++live; }
  ~Table() {
    canary = 0xDEAD;
    --live;
  }
  int value;
  volatile int canary;
};
std::atomic<int> Table::live{0};

TEST(Handoff, TheServoSideTakesTheNewestAndTheOldOnesAreFreedOffIt) {
  {
    Handoff<const Table> handoff;
    EXPECT_EQ(handoff.Take(), nullptr);  // nothing published yet
    handoff.Publish(std::make_shared<Table>(1));
    const Table* current = handoff.Take();
    ASSERT_NE(current, nullptr);
    EXPECT_EQ(current->value, 1);
    EXPECT_EQ(handoff.Take(), current);  // nothing new
    handoff.Publish(std::make_shared<Table>(2));
    handoff.Publish(std::make_shared<Table>(3));  // 2 was never taken: dropped
    EXPECT_EQ(Table::live.load(), 3);             // 1 in use; 2 and 3 published since
    {
      testing::AllocationCounter counter;
      current = handoff.Take();
      EXPECT_EQ(counter.count(), 0u);
    }
    EXPECT_EQ(current->value, 3);
    EXPECT_EQ(Table::live.load(), 3);  // the older ones are freed by the control thread
    handoff.Release();
    EXPECT_EQ(Table::live.load(), 1);
    EXPECT_EQ(handoff.owned(), 1u);
  }
  EXPECT_EQ(Table::live.load(), 0);
}

TEST(Handoff, APublishThatRunsOutOfMemoryPublishesNothing) {
  Handoff<const Table> handoff;
  handoff.Publish(std::make_shared<Table>(1));
  const Table* first = handoff.Take();
  auto next = std::make_shared<Table>(2);
  {
    testing::AllocationFailure fail(1);  // the entry is made; keeping it fails
    EXPECT_THROW(handoff.Publish(next), std::bad_alloc);
  }
  // the servo side still has the first table, alive, and nothing freed is published
  EXPECT_EQ(handoff.Take(), first);
  EXPECT_EQ(first->canary, 0x5AFE);
  handoff.Publish(std::make_shared<Table>(3));
  EXPECT_EQ(handoff.Take()->value, 3);
}

TEST(Handoff, NeverFreesWhatTheServoThreadUsesUnderContention) {
  Handoff<const Table> handoff;
  handoff.Publish(std::make_shared<Table>(0));
  std::atomic<bool> stop{false};
  std::atomic<long> bad{0}, takes{0};
  std::atomic<int> seen{-1};
  std::thread servo([&] {
    int last = -1;
    while (!stop.load(std::memory_order_relaxed)) {
      const Table* current = handoff.Take();
      if (current->canary != 0x5AFE) ++bad;  // freed under us
      if (current->value < last) ++bad;      // went back in time
      last = current->value;
      seen.store(last);
      ++takes;
    }
  });
  for (int i = 1; i <= 20000; ++i) {
    handoff.Publish(std::make_shared<Table>(i));
    if (i % 7 == 0) std::this_thread::yield();
  }
  while (takes.load() < 1000 || seen.load() != 20000) std::this_thread::yield();
  stop = true;
  servo.join();
  handoff.Release();
  EXPECT_EQ(bad.load(), 0);
  EXPECT_EQ(handoff.owned(), 1u);  // the servo thread ends on the newest
}

}  // namespace
}  // namespace hapticad
