// SPDX-License-Identifier: GPL-3.0-or-later
// ConstraintSet: up to three half-spaces n . x >= d that hold the god-object proxy
// outside the surface (one face, an edge, a concave corner), and the exact projection
// of a goal onto their intersection.
//
// Projection solves min |x - g|^2 subject to every half-space. The optimum is the
// projection of g onto the affine hull of its active set, and it is the closest of
// those candidates that is feasible: with at most three planes there are eight
// candidates (none, 3 planes, 3 lines, 1 point), so the QP is solved exactly by
// enumeration. Units: any, consistently (the scene's local metres). Servo-tick safe.
#pragma once

#include <cstdint>

#include "hapticad/core/vec3.h"

namespace hapticad {

struct ConstraintPlane {
  Vec3 normal;             // unit, pointing to the free side
  double offset;           // the plane is normal . x = offset
  std::uint32_t triangle;  // the triangle that made it
};

class ConstraintSet {
 public:
  static constexpr int kMaxPlanes = 3;

  void Clear() { count_ = 0; }
  int count() const { return count_; }
  bool full() const { return count_ == kMaxPlanes; }
  const ConstraintPlane& plane(int i) const { return planes_[i]; }

  // Adds a plane unless full or a plane with the same normal and offset (within
  // `tolerance`) is already there. Returns whether it was added.
  bool Add(const ConstraintPlane& plane, double tolerance);

  // The feasible point closest to `goal`; `tolerance` is the slack in the feasibility
  // test. With no feasible candidate (cannot happen for planes that a proxy reached
  // from outside) returns `fallback`.
  Vec3 Project(const Vec3& goal, const Vec3& fallback, double tolerance) const;

 private:
  bool Feasible(const Vec3& x, double tolerance) const;

  ConstraintPlane planes_[kMaxPlanes];
  int count_ = 0;
};

}  // namespace hapticad
