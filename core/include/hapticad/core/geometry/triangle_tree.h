// SPDX-License-Identifier: GPL-3.0-or-later
// TriangleTree: CGAL's AABB tree over a TriangleMesh, built completely before use.
//
// CGAL builds its tree lazily on the first query; a servo tick must never pay for that,
// so Build() does it. CGAL's distance-query kd-tree is never built (CalcClosestPoint
// needs none). The CGAL types stay inside triangle_tree.cc (licence and compile time
// walled off, as libigl does).
//
// Frame and units: those of the mesh (the scene's local frame, metres).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "hapticad/core/geometry/sweep_query.h"
#include "hapticad/core/geometry/sweep_search.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

class TriangleTree {
 public:
  // Builds the tree. `mesh` must outlive the tree.
  // `pad` (model units) grows every node box so a segment grazing a box edge is not
  // lost to rounding; the scene passes a small fraction of its size.
  static std::unique_ptr<TriangleTree> Build(const TriangleMesh& mesh, double pad);

  // First contact of the query. Triangles are two-sided. Servo-tick safe: no
  // allocation, no lock.
  bool FirstHit(const SweepQuery& query, SweepHit* hit) const;
  // Feeds the search every triangle that could beat its nearest contact so far: its
  // answer is then the first contact. Servo-tick safe.
  void Search(SweepSearch* search) const;

  // How much every node box is grown (model units).
  double pad() const;

  // Closest surface point to `p`: a walk of the boxes, nearest first, pruning those
  // farther than the nearest point so far. No allocation, but not for the servo tick:
  // its cost grows with the query's distance from the surface (a 638k-triangle ball,
  // through Python: 13-32 us within 2 % of its radius, 0.2-0.3 ms from a radius away
  // and beyond). Preconditions: the mesh has a triangle; `p` is finite and its squared
  // distance from the mesh does not overflow (|p| well under 1e150: beyond, no triangle
  // is taken and triangle 0 is answered at distance inf; HapticScene bounds it).
  SurfacePoint CalcClosestPoint(const Vec3& p) const;
  // The same, closer than `max_distance` to `p` only: the walk skips every box farther
  // away, so a point clear of the surface costs the few boxes round it, not a search for
  // the nearest triangle however far. Returns false (and leaves *out) if none is that
  // close (always for a max_distance that is not > 0). No allocation. Not for every
  // tick, but a restart tick runs it: a sphere proxy's GodObjectProxy::ResetOutside (the
  // tick that starts a session or takes a new scene or mapping) asks it up to
  // kMaxClearSteps + 1 = 5 times, within the proxy's radius.
  bool FindClosestPointWithin(const Vec3& p, double max_distance, SurfacePoint* out) const;

  std::size_t num_triangles() const;
  // Bytes of the node array and the primitive array: all the tree keeps.
  std::size_t CalcMemoryBytes() const;

  ~TriangleTree();
  TriangleTree(const TriangleTree&) = delete;
  TriangleTree& operator=(const TriangleTree&) = delete;

 private:
  struct Impl;
  explicit TriangleTree(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hapticad
