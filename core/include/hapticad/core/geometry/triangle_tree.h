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

// First hit of a segment: triangle, parameter s in [0, 1] along a -> b, the point.
struct SegmentHit {
  std::uint32_t triangle;
  double s;
  Vec3 point;
};

// Closest point on the surface to a query point.
struct SurfacePoint {
  std::uint32_t triangle;
  Vec3 point;
  double distance;
};

class TriangleTree {
 public:
  // A cut through the tree around a box: the subtrees of at most kSubtreeSize triangles
  // whose bounding boxes meet the box. Every triangle that meets the box lies in one of
  // them, so a segment query confined to the box needs only these subtrees: a proxy
  // that moves a little each tick reuses the same few hot subtrees instead of walking
  // the whole tree (temporal coherence). Fixed size, no allocation.
  struct Neighbourhood {
    static constexpr int kCapacity = 64;
    static constexpr std::uint32_t kSubtreeSize = 64;
    Vec3 lo = Vec3::Zero();  // the box, local frame
    Vec3 hi = Vec3::Zero();
    int count = 0;
    bool valid = false;
    const void* subtree[kCapacity] = {};  // tree node, or a triangle primitive when size is 1
    std::uint32_t size[kCapacity] = {};
  };
  // Builds the tree and the distance acceleration. `mesh` must outlive the tree.
  // `pad` (model units) grows every node box so a segment grazing a box edge is not
  // lost to rounding; the scene passes a small fraction of its size.
  static std::unique_ptr<TriangleTree> Build(const TriangleMesh& mesh, double pad);

  // First triangle hit along a -> b. Servo-tick safe: no allocation, no lock.
  // `bary_tol` as in IntersectSegmentTriangle.
  bool FirstHit(const Vec3& a, const Vec3& b, double bary_tol, SegmentHit* hit) const;

  // Gathers the neighbourhood of box [lo, hi]. Servo-tick safe. Returns false, leaving
  // it invalid, when more than kCapacity subtrees meet the box (make the box smaller).
  bool GatherNeighbourhood(const Vec3& lo, const Vec3& hi, Neighbourhood* out) const;

  // First hit along a -> b among the neighbourhood's triangles only. Servo-tick safe.
  bool FirstHitIn(const Neighbourhood& neighbourhood, const Vec3& a, const Vec3& b, double bary_tol,
                  SegmentHit* hit) const;

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
