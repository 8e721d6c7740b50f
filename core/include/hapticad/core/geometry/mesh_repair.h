// SPDX-License-Identifier: GPL-3.0-or-later
// RepairSoup: makes a tessellator's or a file's triangle soup fit to touch, and says
// what it did and what it could not do. Nothing is silently accepted or dropped.
//
// In order:
//   1. triangles with a vertex that is not finite are removed (counted); an index out
//      of range cannot be repaired and throws;
//   2. duplicate vertices are merged: exact duplicates everywhere (CGAL's
//      merge_duplicate_points_in_polygon_soup), and vertices on open edges that lie
//      within `weld_tolerance` of each other, which stitches the tessellations of
//      neighbouring CAD faces so no crack is left between them;
//   3. degenerate triangles (a repeated vertex, or thinner than `needle_tolerance` of
//      their longest edge: needles and caps narrower than the proxy's edge tolerance)
//      and duplicate triangles are removed. Removing one must not open a closed
//      surface (a T-junction's collinear filler is as much part of it as any other), so
//      first it is mended: a needle (its shortest edge too below the tolerance: two
//      vertices nearly one) has that edge collapsed, its two ends welded, which removes
//      the triangle across it too; a cap (a vertex on its longest edge) has the one
//      triangle across that edge split at the vertex, the halves keeping its CAD face,
//      the new corner's normal interpolated along the edge (on a sphere or a cylinder,
//      the surface's own). What cannot be mended (the edge open or of more than two
//      triangles, a collapse that would pinch the surface, a split that would leave a
//      degenerate half, two caps back to back) is removed, and step 6 reports what
//      that leaves open. O(n) when nothing is degenerate, as in a CAD tessellation;
//      else an O(n) pass more for each kind;
//   4. orientation is made consistent (CGAL's orient_polygon_soup); a non-manifold
//      edge or vertex is split by duplicating its vertex, as CGAL does, and counted;
//   5. a closed piece wound inward with a vertex outside every other closed piece (a
//      void lies wholly inside its part; exact predicates: a parity count for a few
//      vertices, CGAL's Side_of_triangle_mesh for many) is a part listed the wrong way
//      round, e.g. by a file writer that winds clockwise, or by step 4 following one
//      flipped triangle: it is turned outward, and so is, inward, a piece that only it
//      holds and whose surface never meets it (its void, listed the same way). A
//      part's own void, wound inward inside it, is left so, and so is any piece where
//      the vertices tried tell nothing (on a surface, or in an open piece's box: a
//      cracked shell round a void). Without this the proxy could not tell such a
//      part's inside from its outside when it restarts;
//   6. what stays open is reported: edges with one triangle are holes or cracks.
// CAD face ids and corner normals follow their triangles (a flipped triangle's corner
// normals are reordered with its corners, not negated: they are the CAD surface's, not
// the winding's).
//
// Units: the soup's; tolerances are fractions of its bounding-box diagonal, so a part
// in mm or in m is repaired the same. Not for the servo thread (allocates, seconds on
// millions of triangles).
#pragma once

#include <cstddef>
#include <string>

#include "hapticad/core/geometry/triangle_soup.h"

namespace hapticad {

struct RepairOptions {
  double weld_tolerance = 1e-7;     // open-edge vertices closer than this (x diagonal) merge
  double needle_tolerance = 1e-10;  // height / longest edge below this: degenerate
};

struct RepairReport {
  std::size_t input_vertices = 0;
  std::size_t input_triangles = 0;
  std::size_t removed_nonfinite = 0;   // triangles with a NaN or infinite vertex
  std::size_t merged_vertices = 0;     // vertices folded into another (duplicates, welds)
  std::size_t welded_vertices = 0;     // of those, merged across an open edge within tolerance
  std::size_t removed_degenerate = 0;  // repeated vertex, zero area, needles and caps
  std::size_t collapsed_needles = 0;   // needles whose short edge was welded (it and the
                                       // triangle across are among those removed)
  std::size_t split_caps = 0;          // of those removed, caps mended: the triangle across
                                       // the long edge split in two at the cap's vertex
  std::size_t removed_duplicates = 0;  // same three vertices as another triangle
  std::size_t reoriented = 0;          // triangles flipped to agree with their neighbours
  std::size_t inside_out_shells = 0;   // closed pieces turned round (step 5)
  std::size_t non_manifold_edges = 0;  // edges of more than two triangles (split)
  std::size_t non_manifold_vertices = 0;
  std::size_t boundary_edges = 0;  // edges of one triangle after repair: holes, cracks
  std::size_t output_triangles = 0;

  // Whether every edge of the repaired soup has exactly two triangles (a closed, manifold
  // surface): the non-manifold edges of the input were split, so what is left open are
  // the boundary edges. Two closed parts touching along an edge are closed (Describe()
  // says so too; a warning said "not closed" of them).
  bool watertight() const { return boundary_edges == 0; }
  // One line for the user: what was repaired and what was not.
  std::string Describe() const;
};

// Throws std::invalid_argument naming the problem for input that cannot be repaired:
// an index out of range, shapes that disagree, or nothing left to touch.
TriangleSoup RepairSoup(const TriangleSoup& soup, const RepairOptions& options,
                        RepairReport* report);

}  // namespace hapticad
