// SPDX-License-Identifier: GPL-3.0-or-later
// SelectNth: std::nth_element for a float key, with a partition that does not branch on
// the comparison.
//
// CGAL's tree build splits every node at the median of its primitives' reference points;
// std::nth_element's partition mispredicts about every other comparison there, and the
// splits were most of a 1M-triangle tree's build. Lomuto's partition written without the
// branch (each element is moved whether or not it goes first) does the same selection in
// about half the time (BENCHMARKS.md). Quickselect with a median-of-three pivot; keys
// equal to the pivot are gathered in a second pass, so repeated keys cost no extra
// rounds; after 2 log2(n) + 8 rounds (an adversarial order) it hands the rest to
// std::nth_element, keeping its O(n) bound.
//
// Build-time code (not for the servo tick). T must be cheap to copy.
#pragma once

#include <algorithm>
#include <cstddef>

namespace hapticad {

namespace median_select_internal {

// Moves the elements of [lo, hi) for which goes_first(key) holds to the front; returns
// where they end.
template <class T, class Key, class Predicate>
std::size_t Partition(T* a, std::size_t lo, std::size_t hi, const Key& key,
                      const Predicate& goes_first) {
  std::size_t m = lo;
  for (std::size_t i = lo; i < hi; ++i) {
    const T x = a[i];
    const bool first = goes_first(key(x));
    a[i] = a[m];
    a[m] = x;
    m += first;
  }
  return m;
}

inline float MedianOf3(float a, float b, float c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

}  // namespace median_select_internal

// Rearranges a[0, n) so that a[k] holds the key std::sort would put there, no key before
// it is greater and none after it smaller. key(const T&) returns a float (no NaN).
// Precondition: k < n.
template <class T, class Key>
void SelectNth(T* a, std::size_t n, std::size_t k, const Key& key) {
  using median_select_internal::MedianOf3;
  using median_select_internal::Partition;
  std::size_t lo = 0;
  std::size_t hi = n;
  int rounds = 8;
  for (std::size_t m = n; m > 1; m /= 2) rounds += 2;
  while (hi - lo > 16) {
    if (--rounds < 0) {
      std::nth_element(a + lo, a + k, a + hi,
                       [&key](const T& p, const T& q) { return key(p) < key(q); });
      return;
    }
    const float pivot = MedianOf3(key(a[lo]), key(a[lo + (hi - lo) / 2]), key(a[hi - 1]));
    const std::size_t less = Partition(a, lo, hi, key, [pivot](float x) { return x < pivot; });
    if (k < less) {
      hi = less;
      continue;
    }
    // the keys equal to the pivot (its own at least) come next
    const std::size_t equal = Partition(a, less, hi, key, [pivot](float x) { return x <= pivot; });
    if (k < equal) return;
    lo = equal;
  }
  for (std::size_t i = lo + 1; i < hi; ++i) {  // insertion sort
    const T x = a[i];
    std::size_t j = i;
    for (; j > lo && key(x) < key(a[j - 1]); --j) a[j] = a[j - 1];
    a[j] = x;
  }
}

}  // namespace hapticad
