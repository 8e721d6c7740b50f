// SPDX-License-Identifier: GPL-3.0-or-later
// Counts heap allocations made by the current thread inside a scope (as Drake's
// limit_malloc does), and can make one of them fail. Linking alloc_counter.cc replaces
// the global operator new.
#pragma once

#include <cstddef>

namespace hapticad::testing {

class AllocationCounter {
 public:
  AllocationCounter();
  ~AllocationCounter();
  // Allocations by this thread since construction.
  std::size_t count() const;

 private:
  std::size_t start_;
};

// Inside its scope, this thread's allocations after the first `succeed` throw
// std::bad_alloc: what running out of memory looks like to the code under test.
class AllocationFailure {
 public:
  explicit AllocationFailure(std::size_t succeed);
  ~AllocationFailure();
};

}  // namespace hapticad::testing
