// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: Read() and Write() are called on the servo tick.
//
// Mailbox: the latest value of T passed from one writer thread to one reader thread,
// wait-free on both sides (a triple buffer). The writer never waits for the reader and
// the reader never waits for the writer: neither retries, locks nor allocates, so a
// real-time servo thread can be either side without priority inversion. (A seqlock
// would make the servo thread spin while a preempted writer holds it half-written.)
//
// Exactly one thread may write and exactly one may read at a time (Python callers are
// serialised by the GIL, which the bindings hold around these calls).
#pragma once

#include <atomic>
#include <cstdint>
#include <type_traits>

namespace hapticad {

template <class T>
class Mailbox {
  // copied by assignment: T must not allocate when copied (fixed-size Eigen is fine)
  static_assert(std::is_copy_assignable_v<T>, "mailbox values are copied by value");

 public:
  explicit Mailbox(const T& initial = T{}) {
    for (T& b : buffers_) b = initial;
  }
  Mailbox(const Mailbox&) = delete;
  Mailbox& operator=(const Mailbox&) = delete;

  // Writer side: publishes `value`; the reader sees it at its next Read().
  void Write(const T& value) {
    buffers_[back_] = value;
    const std::uint8_t previous = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel);
    back_ = previous & kIndex;
  }

  // Reader side: the latest published value (the initial one until a Write()).
  const T& Read() {
    if (middle_.load(std::memory_order_relaxed) & kFresh) {
      const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
      front_ = previous & kIndex;
    }
    return buffers_[front_];
  }

  // Reader side: true when a value was written since the reader's last Read().
  bool has_news() const { return (middle_.load(std::memory_order_acquire) & kFresh) != 0; }

 private:
  static constexpr std::uint8_t kIndex = 3;
  static constexpr std::uint8_t kFresh = 4;
  T buffers_[3];
  std::uint8_t back_ = 0;   // the writer's
  std::uint8_t front_ = 2;  // the reader's
  alignas(64) std::atomic<std::uint8_t> middle_{1};
};

}  // namespace hapticad
