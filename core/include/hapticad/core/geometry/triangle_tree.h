// SPDX-License-Identifier: GPL-3.0-or-later
// TriangleTree: CGAL's AABB tree over a TriangleMesh, built completely before use.
//
// CGAL builds its tree and its distance-query kd-tree lazily on the first query; a
// servo tick must never pay for that, so Build() does both. The CGAL types stay inside
// triangle_tree.cc (licence and compile time walled off, as libigl does).
//
// Frame and units: those of the mesh (the scene's local frame, metres).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

// First contact of a query swept from a to b: a point (radius 0) or a sphere.
struct SweepHit {
  std::uint32_t triangle;
  double s;     // in [0, 1] along a -> b
  Vec3 point;   // the query's centre at contact, a + s (b - a)
  Vec3 normal;  // unit contact normal, pointing to the side the query came from
};

// Closest point on the surface to a query point.
struct SurfacePoint {
  std::uint32_t triangle;
  Vec3 point;
  double distance;
};

// Half-spaces n . x <= offset that the swept query provably never comes within its
// radius of (the proxy's constraint planes, lowered by the radius): triangles entirely
// inside one are skipped without a contact test. On a convex surface
// this discards everything under the face the proxy slides on.
struct SweepFloors {
  static constexpr int kMax = 3;
  int count = 0;
  Vec3 normal[kMax];  // unit
  double offset[kMax];
};

// A first-contact query: a point (radius 0) or a sphere whose centre sweeps a -> b.
struct SweepQuery {
  Vec3 a = Vec3::Zero();  // model units, the tree's frame
  Vec3 b = Vec3::Zero();
  double radius = 0.0;
  double bary_tol = 1e-9;               // as in IntersectSegmentTriangle
  const SweepFloors* floors = nullptr;  // may be null
  // A triangle likely to be hit (the last contact), tested before the traversal so its
  // contact prunes the rest early. Any value, or -1.
  std::int64_t hint = -1;
};

class TriangleTree {
 public:
  // Builds the tree and the distance acceleration. `mesh` must outlive the tree.
  // `pad` (model units) grows every node box so a segment grazing a box edge is not
  // lost to rounding; the scene passes a small fraction of its size.
  static std::unique_ptr<TriangleTree> Build(const TriangleMesh& mesh, double pad);

  // First contact of the query. Triangles are two-sided. Servo-tick safe: no
  // allocation, no lock.
  bool FirstHit(const SweepQuery& query, SweepHit* hit) const;

  // How much every node box is grown (model units).
  double pad() const;

  // Closest surface point to `p`. Uses CGAL's accelerated distance query: not for the
  // servo tick (CGAL's kd-tree search allocates).
  SurfacePoint CalcClosestPoint(const Vec3& p) const;

  std::size_t num_triangles() const;
  // Bytes of the node array and the primitive array (not the kd-tree).
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
