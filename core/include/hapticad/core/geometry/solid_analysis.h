// SPDX-License-Identifier: GPL-3.0-or-later
// SolidAnalysis: whether a scene's surface bounds solids, so that a point is inside or
// outside it, and where its pieces are.
//
// A closed surface that does not intersect itself splits space into inside and
// outside, and the parity of the crossings on any ray out decides which side a point
// is on (a hollow part's cavity, inside two shells, is outside). Parts that touch face to
// face or overlap make the surface intersect itself, and a surface with a hole or a
// sheet in it is open: for those the question has no answer this cheap, and
// `bounds_solids` is false (GodObjectProxy::ResetOutside then leaves the proxy alone).
//
// Units and frame: the mesh's. Built off the servo thread (CGAL's self-intersection
// test: allocates, about a second on a million triangles); read by it afterwards.
#pragma once

#include <vector>

#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct SolidAnalysis {
  bool closed = false;  // every edge has two triangles
  // Some two triangles cross or overlap (not just share an edge or vertex).
  bool self_intersecting = false;
  // Closed and found not self-intersecting (false when the test could not be run).
  bool bounds_solids = false;
  // When bounds_solids: the box round each connected piece of the surface; a point in
  // none of them is outside every solid.
  std::vector<Vec3> piece_lo;
  std::vector<Vec3> piece_hi;

  bool InAnyPiece(const Vec3& p) const {
    for (std::size_t i = 0; i < piece_lo.size(); ++i) {
      if (p.cwiseMax(piece_lo[i]) == p && p.cwiseMin(piece_hi[i]) == p) return true;
    }
    return false;
  }
};

SolidAnalysis AnalyseSolids(const TriangleMesh& mesh);

}  // namespace hapticad
