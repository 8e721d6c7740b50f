// SPDX-License-Identifier: GPL-3.0-or-later
// VertexBuckets: items (edges, half-edges) grouped by a vertex of theirs, by a counting
// sort in O(items + vertices): the values of the items whose vertex is v are
// values[first[v]] .. values[first[v + 1]), in item order. What a mesh's build and its
// repair use to find each vertex's edges without sorting all of them.
//
// Allocates: not for the servo tick.
#pragma once

#include <cstddef>
#include <vector>

namespace hapticad {

template <class Index>
struct VertexBuckets {
  std::vector<Index> first;   // num_vertices + 1 offsets
  std::vector<Index> values;  // one per item

  typename std::vector<Index>::iterator begin(std::size_t v) { return values.begin() + first[v]; }
  typename std::vector<Index>::iterator end(std::size_t v) { return values.begin() + first[v + 1]; }
};

// Items i in [0, num_items), each with vertex_of(i) < num_vertices and value_of(i).
template <class Index, class VertexOf, class ValueOf>
VertexBuckets<Index> BucketByVertex(std::size_t num_vertices, std::size_t num_items,
                                    VertexOf vertex_of, ValueOf value_of) {
  VertexBuckets<Index> out;
  out.first.assign(num_vertices + 1, 0);
  for (std::size_t i = 0; i < num_items; ++i) ++out.first[vertex_of(i) + 1];
  for (std::size_t v = 0; v < num_vertices; ++v) out.first[v + 1] += out.first[v];
  out.values.resize(num_items);
  std::vector<Index> next(out.first.begin(), out.first.end() - 1);
  for (std::size_t i = 0; i < num_items; ++i) out.values[next[vertex_of(i)]++] = value_of(i);
  return out;
}

}  // namespace hapticad
