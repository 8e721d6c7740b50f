// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/latency_histogram.h"

#include <random>

#include <gtest/gtest.h>

namespace hapticad {
namespace {

TEST(LatencyHistogram, BinsAreContiguousAndWithinThreePercent) {
  for (std::int64_t v : {0L, 1L, 31L, 32L, 33L, 63L, 64L, 1000L, 123456L, 999999937L}) {
    const double mid = LatencyHistogram::BinMiddle(LatencyHistogram::BinOf(v));
    EXPECT_LE(std::abs(mid - static_cast<double>(v)), 0.5 + 0.0157 * static_cast<double>(v)) << v;
  }
  std::size_t previous = 0;
  for (std::int64_t v = 0; v < 5000; ++v) {
    const std::size_t bin = LatencyHistogram::BinOf(v);
    EXPECT_TRUE(bin == previous || bin == previous + 1) << v;
    previous = bin;
  }
  EXPECT_EQ(LatencyHistogram::BinOf(-5), 0u);
  EXPECT_EQ(LatencyHistogram::BinOf(std::int64_t{1} << 62), LatencyHistogram::kBins - 1);
}

TEST(LatencyHistogram, PercentilesOfAKnownDistribution) {
  LatencyHistogram h;
  EXPECT_EQ(h.Percentile(0.5), 0.0);
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::int64_t> uniform(1000, 2000);  // 1..2 us
  for (int i = 0; i < 100000; ++i) h.Record(uniform(rng));
  h.Record(1000000);  // one 1 ms outlier
  EXPECT_EQ(h.count(), 100001u);
  EXPECT_EQ(h.max_ns(), 1000000);
  EXPECT_NEAR(h.Percentile(0.5), 1500, 1500 * 0.03);
  EXPECT_NEAR(h.Percentile(0.99), 1990, 1990 * 0.03);
  EXPECT_NEAR(h.Percentile(1.0), 1e6, 1e6 * 0.03);
  h.Reset();
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.Percentile(0.99), 0.0);
}

}  // namespace
}  // namespace hapticad
