// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/contact/god_object_proxy.h"

#include <algorithm>

namespace hapticad {

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree,
                               ProxyConfig config)
    : mesh_(mesh), tree_(tree), config_(config) {}

void GodObjectProxy::Reset(const Vec3& position_l) {
  position_ = position_l;
  constraints_.Clear();
}

void GodObjectProxy::Update(const Vec3& goal_l) {
  const double offset = config_.surface_offset_m;
  // feasibility slack: well below the offset, well above rounding at scene scale
  const double slack = 0.25 * offset;
  constraints_.Clear();
  Vec3 target = goal_l;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Vec3 d = target - position_;
    if (d.squaredNorm() <= slack * slack) break;
    SegmentHit hit;
    if (!tree_.FirstHit(position_, target, config_.bary_tolerance, &hit)) {
      position_ = target;
      break;
    }
    // the plane faces the side the segment comes from, whatever the winding: open
    // sheets and zero-thickness plates are felt from both sides
    Vec3 n = mesh_.face_normal(hit.triangle);
    const double approach = n.dot(d);
    if (approach > 0.0) n = -n;
    const double plane_offset = n.dot(mesh_.vertex(mesh_.triangle(hit.triangle)[0])) + offset;
    // stop where the segment meets the offset plane, never beyond the hit itself
    const double n_dot_d = n.dot(d);
    double s = n_dot_d < 0.0 ? (plane_offset - n.dot(position_)) / n_dot_d : 0.0;
    s = std::clamp(s, 0.0, hit.s);
    position_ += s * d;
    if (constraints_.full()) break;
    constraints_.Add({n, plane_offset, hit.triangle}, slack);
    target = constraints_.Project(goal_l, position_, slack);
  }
}

}  // namespace hapticad
