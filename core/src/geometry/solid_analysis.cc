// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/geometry/solid_analysis.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <utility>

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include "hapticad/core/geometry/connected_pieces.h"

namespace hapticad {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

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
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossings;
  PMP::self_intersections(sm, std::back_inserter(crossings));
  out.self_intersecting = !crossings.empty();
  out.bounds_solids = out.closed && !out.self_intersecting;
  ConnectedPieces pieces = FindConnectedPieces(mesh);
  const std::size_t num_pieces = pieces.lo.size();
  // a piece with an open edge (a sheet, a surface model's shell) bounds nothing
  std::vector<bool> piece_closed(num_pieces, true);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& across = mesh.across(t);
    if (across[0] == TriangleMesh::kNone || across[1] == TriangleMesh::kNone ||
        across[2] == TriangleMesh::kNone) {
      piece_closed[pieces.of_vertex[mesh.triangle(t)[0]]] = false;
    }
  }
  const auto piece_of = [&](Mesh::Face_index f) {
    return pieces.of_vertex[mesh.triangle(static_cast<std::uint32_t>(f))[0]];
  };
  for (const auto& [f, g] : crossings) {
    // a closed piece crossing itself: neither its parity nor its winding means anything
    if (piece_of(f) == piece_of(g) && piece_closed[piece_of(f)]) return out;
  }
  out.pieces_bound_solids =
      std::find(piece_closed.begin(), piece_closed.end(), true) != piece_closed.end();
  if (!out.pieces_bound_solids) return out;  // all open: nothing is inside anything
  // each piece's volume (the divergence theorem, about the mesh's local origin), whose
  // sign tells an outer shell from an inner one
  std::vector<double> volume(num_pieces, 0.0);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangle(t);
    volume[pieces.of_vertex[tri[0]]] +=
        mesh.vertex(tri[0]).dot(mesh.vertex(tri[1]).cross(mesh.vertex(tri[2])));
  }
  for (std::size_t c = 0; c < num_pieces; ++c) {
    out.piece_winding.push_back(!piece_closed[c] ? 0 : volume[c] < 0.0 ? -1 : 1);
  }
  out.piece_lo = std::move(pieces.lo);
  out.piece_hi = std::move(pieces.hi);
  if (!out.bounds_solids) out.piece_of_vertex = std::move(pieces.of_vertex);
  return out;
}

std::size_t SolidAnalysis::CalcMemoryBytes() const {
  return 2 * piece_lo.capacity() * sizeof(Vec3) + piece_winding.capacity() +
         piece_of_vertex.capacity() * sizeof(std::uint32_t);
}

}  // namespace hapticad
