// SPDX-License-Identifier: GPL-3.0-or-later
// SolidAnalysis: whether a scene's surface bounds solids, so that a point is inside or
// outside it, and where its pieces are.
//
// A closed surface that does not intersect itself splits space into inside and
// outside, and the parity of the crossings on any ray out decides which side a point
// is on (a hollow part's cavity, inside two shells, is outside): `bounds_solids`.
//
// Parts that touch face to face or overlap (an assembly: a button in its housing) make
// the surface intersect itself, and the parity of all crossings means nothing there.
// If each closed connected piece crosses only other pieces, though, each bounds a solid
// on its own (or, wound inward, a cavity: a hollow part's inner shell), and a
// point is inside where the pieces round it wind round it a positive number of times:
// each piece the point is inside (by the parity of that piece's crossings alone) adds
// its `piece_winding`, +1 wound outward (a positive volume), -1 inward. That is
// `pieces_bound_solids`. Pieces are wound as the CAD tessellation gives them (outer
// shells outward, inner shells inward); the repair keeps each piece consistent.
//
// A piece with an open edge (a sheet, a surface model's shell not yet closed) bounds
// nothing: its `piece_winding` is 0, and a point is inside or outside the closed pieces
// whatever open ones lie round it. So a scene of parts and a sheet still knows what is
// inside its parts. Where that cannot be answered this cheaply, pieces_bound_solids is
// false (GodObjectProxy::ResetOutside then leaves the proxy alone): a closed piece that
// crosses itself (its parity and winding mean nothing), or no closed piece at all.
//
// Units and frame: the mesh's. Built off the servo thread (CGAL's self-intersection
// test: allocates, about a second on a million triangles); read by it afterwards.
#pragma once

#include <cstdint>
#include <vector>

#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct SolidAnalysis {
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  bool closed = false;  // every edge has two triangles
  // Some two triangles cross or overlap (not just share an edge or vertex).
  bool self_intersecting = false;
  // Closed and found not self-intersecting (false when the test could not be run).
  bool bounds_solids = false;
  // Some piece is closed, and no closed piece crosses itself (true too when
  // bounds_solids).
  bool pieces_bound_solids = false;
  // When pieces_bound_solids: the box round each connected piece of the surface (a
  // point in none of the closed ones is outside every solid), and how it winds (+1 or
  // -1; 0 for an open piece).
  std::vector<Vec3> piece_lo;
  std::vector<Vec3> piece_hi;
  std::vector<std::int8_t> piece_winding;
  // When pieces_bound_solids but not bounds_solids: each vertex's piece (kNone for a
  // vertex of no triangle), for sweeps that see one piece alone. Empty otherwise.
  std::vector<std::uint32_t> piece_of_vertex;

  // Whether p is in the box of a closed piece (one that bounds a solid or a cavity).
  bool InAnySolidPiece(const Vec3& p) const {
    for (std::size_t i = 0; i < piece_lo.size(); ++i) {
      if (piece_winding[i] != 0 && InPiece(static_cast<std::uint32_t>(i), p)) return true;
    }
    return false;
  }
  bool InPiece(std::uint32_t piece, const Vec3& p) const {
    return p.cwiseMax(piece_lo[piece]) == p && p.cwiseMin(piece_hi[piece]) == p;
  }
  std::size_t CalcMemoryBytes() const;
};

SolidAnalysis AnalyseSolids(const TriangleMesh& mesh);

}  // namespace hapticad
