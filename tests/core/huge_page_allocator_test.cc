// SPDX-License-Identifier: GPL-3.0-or-later
// a type of ours whose std::allocator is a HugePageStdAllocator, as CGAL's tree nodes are
// in triangle_tree.cc; declared before anything can instantiate std::allocator<Node>
#include <memory>
namespace hapticad::test_huge_pages {
struct Node {
  double box[6];
  const Node* children[2];
};
}  // namespace hapticad::test_huge_pages

#include "hapticad/core/huge_page_allocator.h"

namespace std {
template <>
struct allocator<hapticad::test_huge_pages::Node>
    : hapticad::HugePageStdAllocator<hapticad::test_huge_pages::Node> {
  using HugePageStdAllocator::HugePageStdAllocator;
};
}  // namespace std

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

using test_huge_pages::Node;

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

TEST(HugePageStdAllocator, APlainVectorOfTheSpecializedTypeGetsHugePages) {
  std::vector<Node> nodes;
  nodes.reserve(100'000);  // 6.4 MB, as CGAL reserves its nodes
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(nodes.data()) % HugePageAllocator<int>::kHugePage, 0u);
  for (int i = 0; i < 100'000; ++i) nodes.emplace_back().box[0] = i;
  EXPECT_EQ(nodes[99'999].box[0], 99'999.0);
  std::vector<Node> small(3);  // ordinary blocks from operator new
  small[2].box[5] = 1.0;
  EXPECT_EQ(small[2].box[5], 1.0);
  std::vector<Node> moved = std::move(nodes);
  EXPECT_EQ(moved.size(), 100'000u);
  EXPECT_EQ(moved[5].box[0], 5.0);
}

}  // namespace
}  // namespace hapticad
