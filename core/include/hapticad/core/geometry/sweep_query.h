// SPDX-License-Identifier: GPL-3.0-or-later
// What a first-contact query asks and answers: SweepQuery, SweepHit, SweepFloors, and
// the closest-point answer SurfacePoint. Shared by TriangleTree, TriangleGrid and
// SweepSearch. Units and frame: the mesh's.
#pragma once

#include <cstdint>

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
  // Only the triangles of one connected piece (SolidAnalysis::piece_of_vertex, indexed
  // by a triangle's first vertex), for a ray that asks about one part of an assembly
  // alone. Null: every triangle.
  const std::uint32_t* piece_of_vertex = nullptr;
  std::uint32_t piece = 0;
};

}  // namespace hapticad
