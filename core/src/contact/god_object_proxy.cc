// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: GodObjectProxy::Update and FirstHit run on the servo thread every tick.
#include "hapticad/core/contact/god_object_proxy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hapticad {
namespace {

bool FiniteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree,
                               ProxyConfig config)
    : mesh_(mesh), tree_(tree), config_(config) {
  if (!FiniteNonNegative(config_.radius_m) || !(config_.surface_offset_m > 0.0) ||
      !std::isfinite(config_.surface_offset_m)) {
    throw std::invalid_argument("proxy: the radius must be finite and >= 0, the offset > 0");
  }
}

void GodObjectProxy::Reset(const Vec3& position_l) {
  position_ = position_l;
  constraints_.Clear();
  last_triangle_ = -1;
}

bool GodObjectProxy::FirstHit(const Vec3& a, const Vec3& b, SweepHit* hit,
                              const SweepFloors* floors, std::int64_t hint) {
  SweepQuery query;
  query.radius = config_.radius_m;
  query.bary_tol = config_.bary_tolerance;
  query.floors = floors;
  query.hint = hint;
  query.a = a;
  query.b = b;
  return tree_.FirstHit(query, hit);
}

void GodObjectProxy::Update(const Vec3& goal_l) {
  const double offset = config_.surface_offset_m;
  // feasibility slack: well below the offset, well above rounding at scene scale
  const double slack = 0.25 * offset;
  constraints_.Clear();
  Vec3 target = goal_l;
  // the sweeps after the first stay on the constraint planes: whatever lies r and half
  // the offset below them cannot be touched
  SweepFloors floors;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Vec3 d = target - position_;
    if (d.squaredNorm() <= slack * slack) break;
    floors.count = constraints_.count();
    for (int i = 0; i < floors.count; ++i) {
      floors.normal[i] = constraints_.plane(i).normal;
      floors.offset[i] = constraints_.plane(i).offset - config_.radius_m - 0.5 * offset;
    }
    SweepHit hit;
    if (!FirstHit(position_, target, &hit, &floors, iteration == 0 ? last_triangle_ : -1)) {
      position_ = target;
      break;
    }
    // the plane through the centre at contact, facing where the proxy came from
    const Vec3& n = hit.normal;
    const double plane_offset = n.dot(hit.point) + offset;
    // stop where the sweep meets the offset plane, never beyond the contact itself
    const double n_dot_d = n.dot(d);
    double s = n_dot_d < 0.0 ? (plane_offset - n.dot(position_)) / n_dot_d : 0.0;
    s = std::clamp(s, 0.0, hit.s);
    position_ += s * d;
    if (constraints_.full()) break;
    constraints_.Add({n, plane_offset, hit.triangle}, slack);
    target = constraints_.Project(goal_l, position_, slack);
  }
  last_triangle_ = in_contact() ? constraints_.plane(0).triangle : -1;
}

}  // namespace hapticad
