// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/huge_page_allocator.h"

#include <cstdint>
#include <numeric>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(HugePageAllocator, LargeBlocksAreHugePageAlignedAndHoldTheirValues) {
  HugePageVector<std::uint32_t> v(3'000'000);  // 12 MB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % HugePageAllocator<int>::kHugePage, 0u);
  std::iota(v.begin(), v.end(), 0u);
  EXPECT_EQ(v[2'999'999], 2'999'999u);
  // growing moves the contents into a new block, freeing the old one
  v.resize(5'000'000, 7u);
  EXPECT_EQ(v[1234], 1234u);
  EXPECT_EQ(v[4'999'999], 7u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % HugePageAllocator<int>::kHugePage, 0u);
}

TEST(HugePageAllocator, SmallBlocksAreOrdinary) {
  HugePageVector<double> v(10, 1.5);
  EXPECT_EQ(v.size(), 10u);
  EXPECT_EQ(v[9], 1.5);
  HugePageVector<double> w;  // empty: allocates nothing
  EXPECT_EQ(w.data(), nullptr);
}

}  // namespace
}  // namespace hapticad
