// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/spsc_ring.h"

#include <thread>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(SpscRing, RefusesPushesWhenFullAndKeepsOrder) {
  SpscRing<int> ring(4);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.Push(i));
  EXPECT_FALSE(ring.Push(99));
  int x = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(ring.Pop(&x));
    EXPECT_EQ(x, i);
  }
  EXPECT_FALSE(ring.Pop(&x));
}

TEST(SpscRing, CarriesEveryItemAcrossThreadsInOrder) {
  SpscRing<long> ring(64);
  constexpr long kCount = 200000;
  std::thread producer([&] {
    for (long i = 0; i < kCount;) {
      if (ring.Push(i)) ++i;
    }
  });
  long expected = 0;
  long x;
  while (expected < kCount) {
    if (ring.Pop(&x)) {
      ASSERT_EQ(x, expected);
      ++expected;
    }
  }
  producer.join();
}

}  // namespace
}  // namespace hapticad
