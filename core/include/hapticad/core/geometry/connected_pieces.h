// SPDX-License-Identifier: GPL-3.0-or-later
// ConnectedPieces: the connected pieces of a mesh (its triangles joined through shared
// vertices: a part, a loose sheet) and the box round each. What the mesh repair, the
// solid analysis and the convex pieces start from.
//
// Units and frame: the mesh's. For the build: allocates, O(n).
#pragma once

#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct ConnectedPieces {
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::vector<std::uint32_t> of_vertex;  // each vertex's piece; kNone for one in no triangle
  std::vector<Vec3> lo;                  // each piece's box
  std::vector<Vec3> hi;
};

ConnectedPieces FindConnectedPieces(const TriangleMesh& mesh);

// The same for any indexed triangles: `corner(t, k)` is the vertex index of corner k of
// triangle t, `vertex(v)` the position of vertex v (a Vec3). Pieces are numbered in the
// order of their lowest vertex.
template <class Corner, class Vertex>
ConnectedPieces FindConnectedPieces(std::size_t num_vertices, std::size_t num_triangles,
                                    Corner corner, Vertex vertex) {
  // union-find over the vertices, joined by every triangle
  std::vector<std::uint32_t> parent(num_vertices);  // indices fit: a TriangleSoup's are 32-bit
  std::iota(parent.begin(), parent.end(), std::uint32_t{0});
  const auto root = [&parent](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> used(num_vertices, false);
  for (std::size_t t = 0; t < num_triangles; ++t) {
    const auto first = static_cast<std::uint32_t>(corner(t, 0));
    used[first] = true;
    for (int k = 1; k < 3; ++k) {
      const auto v = static_cast<std::uint32_t>(corner(t, k));
      used[v] = true;
      const std::uint32_t a = root(first);
      const std::uint32_t b = root(v);
      if (a != b) parent[b] = a;
    }
  }
  ConnectedPieces out;
  out.of_vertex.assign(num_vertices, ConnectedPieces::kNone);
  std::vector<std::uint32_t> of_root(num_vertices, ConnectedPieces::kNone);
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    if (!used[v]) continue;
    std::uint32_t& piece = of_root[root(v)];
    if (piece == ConnectedPieces::kNone) {
      piece = static_cast<std::uint32_t>(out.lo.size());
      out.lo.push_back(Vec3::Constant(std::numeric_limits<double>::infinity()));
      out.hi.push_back(Vec3::Constant(-std::numeric_limits<double>::infinity()));
    }
    out.of_vertex[v] = piece;
    const Vec3 p = vertex(v);
    out.lo[piece] = out.lo[piece].cwiseMin(p);
    out.hi[piece] = out.hi[piece].cwiseMax(p);
  }
  return out;
}

}  // namespace hapticad
