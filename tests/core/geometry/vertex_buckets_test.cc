// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/vertex_buckets.h"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(VertexBuckets, EachVertexHoldsTheValuesOfItsItemsInItemOrder) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::uint32_t> pick(0, 9);
  std::vector<std::uint32_t> vertex(200);
  for (auto& v : vertex) v = pick(rng);
  vertex[0] = 11;  // vertices 10 and 12 stay empty
  const auto buckets = BucketByVertex<std::uint32_t>(
      13, vertex.size(), [&](std::size_t i) { return vertex[i]; },
      [](std::size_t i) { return static_cast<std::uint32_t>(1000 + i); });
  ASSERT_EQ(buckets.first.size(), 14u);
  ASSERT_EQ(buckets.values.size(), vertex.size());
  for (std::uint32_t v = 0; v < 13; ++v) {
    std::vector<std::uint32_t> expected;
    for (std::size_t i = 0; i < vertex.size(); ++i) {
      if (vertex[i] == v) expected.push_back(static_cast<std::uint32_t>(1000 + i));
    }
    const std::vector<std::uint32_t> got(buckets.values.begin() + buckets.first[v],
                                         buckets.values.begin() + buckets.first[v + 1]);
    EXPECT_EQ(got, expected) << v;
  }
}

}  // namespace
}  // namespace hapticad
