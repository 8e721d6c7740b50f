// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/solid_analysis.h"

#include <cstdint>
#include <utility>

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include "hapticad/core/geometry/connected_pieces.h"

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

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
    // TriangleMesh took every triangle (manifold), so Surface_mesh should too; if it refuses one (a
    // vertex it cannot join), the test below would miss that triangle: no answer then
    if (sm.add_face(Mesh::Vertex_index(tri[0]), Mesh::Vertex_index(tri[1]),
                    Mesh::Vertex_index(tri[2])) == Mesh::null_face()) {
      return out;
    }
  }
  out.self_intersecting = CGAL::Polygon_mesh_processing::does_self_intersect(sm);
  out.bounds_solids = out.closed && !out.self_intersecting;
  if (!out.bounds_solids) return out;
  ConnectedPieces pieces = FindConnectedPieces(mesh);
  out.piece_lo = std::move(pieces.lo);
  out.piece_hi = std::move(pieces.hi);
  return out;
}

}  // namespace hapticad
