// SPDX-License-Identifier: GPL-3.0-or-later
// Counts heap allocations made by the current thread inside a scope (as Drake's
// limit_malloc does). Linking alloc_counter.cc replaces the global operator new.
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

}  // namespace hapticad::testing
