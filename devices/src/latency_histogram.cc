// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: LatencyHistogram::Record runs on the servo tick.
#include "hapticad/devices/latency_histogram.h"

#include <cmath>

namespace hapticad {

namespace {
constexpr std::int64_t kSub = std::int64_t{1} << LatencyHistogram::kSubBits;

int FloorLog2(std::uint64_t v) { return 63 - __builtin_clzll(v); }
}  // namespace

std::size_t LatencyHistogram::BinOf(std::int64_t ns) {
  if (ns < kSub) return static_cast<std::size_t>(ns < 0 ? 0 : ns);
  const int e = FloorLog2(static_cast<std::uint64_t>(ns));
  if (e > kMaxExponent) return kBins - 1;
  const std::int64_t sub = (ns >> (e - kSubBits)) & (kSub - 1);
  return static_cast<std::size_t>(kSub + (e - kSubBits) * kSub + sub);
}

double LatencyHistogram::BinMiddle(std::size_t bin) {
  if (bin < static_cast<std::size_t>(kSub)) return static_cast<double>(bin);
  const std::int64_t octave = (static_cast<std::int64_t>(bin) - kSub) / kSub;
  const std::int64_t sub = (static_cast<std::int64_t>(bin) - kSub) % kSub;
  const double width = std::ldexp(1.0, static_cast<int>(octave));
  return static_cast<double>(kSub + sub) * width + 0.5 * width;
}

void LatencyHistogram::Record(std::int64_t ns) {
  auto& bin = bins_[BinOf(ns)];
  bin.store(bin.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  count_.store(count_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  if (ns > max_ns_.load(std::memory_order_relaxed)) max_ns_.store(ns, std::memory_order_relaxed);
}

void LatencyHistogram::Reset() {
  for (auto& b : bins_) b.store(0, std::memory_order_relaxed);
  count_.store(0, std::memory_order_relaxed);
  max_ns_.store(0, std::memory_order_relaxed);
}

double LatencyHistogram::Percentile(double q) const {
  std::uint64_t total = 0;
  for (const auto& b : bins_) total += b.load(std::memory_order_relaxed);
  if (total == 0) return 0.0;
  const double clamped = q < 0.0 ? 0.0 : (q > 1.0 ? 1.0 : q);
  const auto rank = static_cast<std::uint64_t>(std::ceil(clamped * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < kBins; ++i) {
    seen += bins_[i].load(std::memory_order_relaxed);
    if (seen >= rank && seen > 0) return BinMiddle(i);
  }
  return BinMiddle(kBins - 1);
}

}  // namespace hapticad
