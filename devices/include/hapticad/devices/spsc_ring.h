// SPDX-License-Identifier: GPL-3.0-or-later
// SpscRing: a fixed-capacity single-producer single-consumer ring of trivially copyable
// items. The servo thread pushes, another thread pops; neither locks nor allocates
// after construction. A push to a full ring is refused (the caller counts the loss).
#pragma once

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace hapticad {

template <class T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "ring items are copied by value");

 public:
  // `capacity` is rounded up to a power of two (>= 2).
  explicit SpscRing(std::size_t capacity) {
    std::size_t n = 2;
    while (n < capacity) n <<= 1;
    items_.resize(n);
    mask_ = n - 1;
  }

  std::size_t capacity() const { return items_.size(); }

  // Producer side. Returns false (and drops the item) when full.
  bool Push(const T& item) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == items_.size()) return false;
    items_[head & mask_] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. Returns false when empty.
  bool Pop(T* item) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    *item = items_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

 private:
  std::vector<T> items_;
  std::size_t mask_ = 0;
  // on separate cache lines: the two threads write one each
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace hapticad
