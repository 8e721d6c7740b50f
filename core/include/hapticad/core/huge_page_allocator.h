// SPDX-License-Identifier: GPL-3.0-or-later
// HugePageAllocator: the allocator of the large arrays a servo tick reads at random
// (mesh vertices, triangles, normals, CAD face ids, the point grid's cells).
//
// A block of 2 MiB or more is mapped fresh from the kernel (malloc may hand back memory
// already faulted in as small pages), 2 MiB-aligned, rounded up to whole 2 MiB pages and
// advised as transparent huge pages before anything touches it, so the first write
// faults in huge pages. A tick on a 1M-triangle model then needs far fewer
// TLB entries: its p99 drops by about 12 % (BENCHMARKS.md). Smaller blocks, and
// systems where THP is off, get ordinary pages; nothing else changes.
//
// Not for the servo tick: it allocates (the arrays are built before the loop starts).
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace hapticad {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}  // NOLINT(google-explicit-constructor)

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePage) return std::allocator<T>().allocate(n);
    const std::size_t rounded = Rounded(bytes);
    // map one page more than needed, then return the unaligned head and the tail
    void* mapped = mmap(nullptr, rounded + kHugePage, PROT_READ | PROT_WRITE,
                        MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const auto base = reinterpret_cast<std::uintptr_t>(mapped);
    const std::uintptr_t aligned = (base + kHugePage - 1) / kHugePage * kHugePage;
    if (aligned > base) munmap(mapped, aligned - base);
    const std::uintptr_t end = base + rounded + kHugePage;
    if (end > aligned + rounded)
      munmap(reinterpret_cast<void*>(aligned + rounded), end - aligned - rounded);
    madvise(reinterpret_cast<void*>(aligned), rounded, MADV_HUGEPAGE);  // advice: may be refused
    return reinterpret_cast<T*>(aligned);
  }

  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kHugePage) {
      std::allocator<T>().deallocate(p, n);
    } else {
      munmap(p, Rounded(n * sizeof(T)));
    }
  }

  static std::size_t Rounded(std::size_t bytes) {
    return (bytes + kHugePage - 1) / kHugePage * kHugePage;
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const {
    return true;
  }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const {
    return false;
  }
};

// A vector whose storage is a HugePageAllocator's.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

// The members of std::allocator<T> (C++17), storage from a HugePageAllocator: the body of
// a specialization of std::allocator for a type of ours that a library keeps in a plain
// std::vector (CGAL's tree nodes and primitives, triangle_tree.cc). The standard allows
// specializing std::allocator for a program-defined type if it keeps the interface:
//   template <> struct std::allocator<X> : hapticad::HugePageStdAllocator<X> {
//     using HugePageStdAllocator::HugePageStdAllocator;
//   };
// declared before anything instantiates std::allocator<X>.
template <class T>
struct HugePageStdAllocator {
  using value_type = T;
  using pointer = T*;
  using const_pointer = const T*;
  using reference = T&;
  using const_reference = const T&;
  using size_type = std::size_t;
  using difference_type = std::ptrdiff_t;
  using propagate_on_container_move_assignment = std::true_type;
  using is_always_equal = std::true_type;
  template <class U>
  struct rebind {
    using other = std::allocator<U>;
  };
  static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__, "over-aligned type");

  HugePageStdAllocator() = default;
  template <class U>
  HugePageStdAllocator(const std::allocator<U>&) {}  // NOLINT(google-explicit-constructor)

  T* allocate(std::size_t n, const void* /*hint*/ = nullptr) {
    // small blocks straight from operator new: std::allocator<T> is this very type
    if (n * sizeof(T) < HugePageAllocator<T>::kHugePage) {
      return static_cast<T*>(::operator new(n * sizeof(T)));
    }
    return HugePageAllocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < HugePageAllocator<T>::kHugePage) {
      ::operator delete(p);
    } else {
      HugePageAllocator<T>().deallocate(p, n);
    }
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  void destroy(U* p) {
    p->~U();
  }
  std::size_t max_size() const noexcept { return std::size_t(-1) / sizeof(T); }
};

}  // namespace hapticad
