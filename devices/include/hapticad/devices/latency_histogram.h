// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: Record() is called on the servo tick.
//
// LatencyHistogram: durations in nanoseconds counted into log-linear bins (32 per
// octave: any value is known to within 1/32 = 3 %), from 1 ns to about 18 minutes,
// in 9 KiB of counters allocated once. One thread records (wait-free: relaxed loads
// and stores, no read-modify-write); any thread may read percentiles at any time
// (a reading taken during recording is off by at most the samples in flight).
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace hapticad {

class LatencyHistogram {
 public:
  static constexpr int kSubBits = 5;  // 32 bins per octave
  static constexpr int kMaxExponent = 40;
  static constexpr std::size_t kBins = (std::size_t{1} << kSubBits) * (kMaxExponent - kSubBits + 2);

  // Writer side. Negative durations count as zero; huge ones land in the last bin.
  void Record(std::int64_t ns);

  // Writer side, or when no writer runs.
  void Reset();

  std::uint64_t count() const { return count_.load(std::memory_order_relaxed); }
  std::int64_t max_ns() const { return max_ns_.load(std::memory_order_relaxed); }
  // The value below which a fraction `q` (0..1) of the samples lie: the middle of the
  // bin holding that rank. 0 when empty.
  double Percentile(double q) const;

  static std::size_t BinOf(std::int64_t ns);
  static double BinMiddle(std::size_t bin);

 private:
  std::array<std::atomic<std::uint64_t>, kBins> bins_{};
  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::int64_t> max_ns_{0};
};

}  // namespace hapticad
