// SPDX-License-Identifier: GPL-3.0-or-later
// GodObjectProxy: a point proxy that follows the device but never crosses the surface
// (Zilles and Salisbury 1995; Ruspini et al. 1997).
//
// Each tick the proxy moves from where it is toward the goal (the device position)
// along a segment. The first triangle the segment hits becomes a constraint plane,
// offset by `surface_offset` to the free side; the proxy stops on that offset plane
// and the goal is re-projected onto the constraint set. This repeats until the segment
// is free or three planes bind (a concave corner). Forces come from proxy - goal.
//
// Frame and units: the scene's local frame, metres. Update() is servo-tick safe: no
// allocation, no lock, bounded work (at most kMaxIterations tree queries).
#pragma once

#include "hapticad/core/contact/constraint_set.h"
#include "hapticad/core/geometry/triangle_mesh.h"
#include "hapticad/core/geometry/triangle_tree.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

struct ProxyConfig {
  double surface_offset_m = 1e-8;  // how far off the surface the proxy rests (> 0)
  double bary_tolerance = 1e-9;    // inclusive edge tolerance of the triangle test
};

class GodObjectProxy {
 public:
  static constexpr int kMaxIterations = 4;

  // `mesh` and `tree` must outlive the proxy.
  GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree, ProxyConfig config);

  // Places the proxy at `position_l` without collision (the caller knows it is free).
  void Reset(const Vec3& position_l);

  // Moves the proxy toward `goal_l`, constrained by the surface.
  void Update(const Vec3& goal_l);

  const Vec3& position() const { return position_; }
  const ConstraintSet& constraints() const { return constraints_; }
  bool in_contact() const { return constraints_.count() > 0; }

 private:
  const TriangleMesh& mesh_;
  const TriangleTree& tree_;
  ProxyConfig config_;
  Vec3 position_ = Vec3::Zero();
  ConstraintSet constraints_;
};

}  // namespace hapticad
