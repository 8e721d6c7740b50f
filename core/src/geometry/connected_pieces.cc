// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/connected_pieces.h"

#include <limits>
#include <numeric>

namespace hapticad {
namespace {

std::uint32_t Root(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

ConnectedPieces FindConnectedPieces(const TriangleMesh& mesh) {
  const auto num_vertices = static_cast<std::uint32_t>(mesh.num_vertices());
  // union-find over the vertices, joined by every triangle
  std::vector<std::uint32_t> parent(num_vertices);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<bool> used(num_vertices, false);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      used[tri[k]] = true;
      const std::uint32_t a = Root(parent, tri[0]);
      const std::uint32_t b = Root(parent, tri[k]);
      if (a != b) parent[b] = a;
    }
  }
  ConnectedPieces out;
  out.of_vertex.assign(num_vertices, ConnectedPieces::kNone);
  std::vector<std::uint32_t> of_root(num_vertices, ConnectedPieces::kNone);
  for (std::uint32_t v = 0; v < num_vertices; ++v) {
    if (!used[v]) continue;
    std::uint32_t& piece = of_root[Root(parent, v)];
    if (piece == ConnectedPieces::kNone) {
      piece = static_cast<std::uint32_t>(out.lo.size());
      out.lo.push_back(Vec3::Constant(std::numeric_limits<double>::infinity()));
      out.hi.push_back(Vec3::Constant(-std::numeric_limits<double>::infinity()));
    }
    out.of_vertex[v] = piece;
    out.lo[piece] = out.lo[piece].cwiseMin(mesh.vertex(v));
    out.hi[piece] = out.hi[piece].cwiseMax(mesh.vertex(v));
  }
  return out;
}

}  // namespace hapticad
