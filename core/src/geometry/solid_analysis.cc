// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/solid_analysis.h"

#include <cstdint>
#include <numeric>

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

std::uint32_t Root(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

SolidAnalysis AnalyseSolids(const TriangleMesh& mesh) {
  SolidAnalysis out;
  out.closed = mesh.closed();
  Mesh sm;
  sm.reserve(static_cast<Mesh::size_type>(mesh.num_vertices()),
             static_cast<Mesh::size_type>(3 * mesh.num_triangles() / 2),
             static_cast<Mesh::size_type>(mesh.num_triangles()));
  for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.vertex(v);
    sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangle(t);
    // OpenMesh took every triangle, so Surface_mesh should too; if it refuses one (a
    // vertex it cannot join), the test below would miss that triangle: no answer then
    if (sm.add_face(Mesh::Vertex_index(tri[0]), Mesh::Vertex_index(tri[1]),
                    Mesh::Vertex_index(tri[2])) == Mesh::null_face()) {
      return out;
    }
  }
  out.self_intersecting = CGAL::Polygon_mesh_processing::does_self_intersect(sm);
  out.bounds_solids = out.closed && !out.self_intersecting;
  if (!out.bounds_solids) return out;
  // pieces: triangles joined through shared vertices (union-find)
  std::vector<std::uint32_t> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangle(t);
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t a = Root(parent, tri[0]);
      const std::uint32_t b = Root(parent, tri[k]);
      if (a != b) parent[b] = a;
    }
  }
  std::vector<std::int64_t> piece_of(mesh.num_vertices(), -1);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    for (const std::uint32_t v : mesh.triangle(t)) {
      const std::uint32_t root = Root(parent, v);
      if (piece_of[root] < 0) {
        piece_of[root] = static_cast<std::int64_t>(out.piece_lo.size());
        out.piece_lo.push_back(mesh.vertex(v));
        out.piece_hi.push_back(mesh.vertex(v));
      }
      const auto i = static_cast<std::size_t>(piece_of[root]);
      out.piece_lo[i] = out.piece_lo[i].cwiseMin(mesh.vertex(v));
      out.piece_hi[i] = out.piece_hi[i].cwiseMax(mesh.vertex(v));
    }
  }
  return out;
}

}  // namespace hapticad
