// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: GodObjectProxy::Update and FirstHit run on the servo thread every tick.
#include "hapticad/core/contact/god_object_proxy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hapticad {
namespace {

bool FiniteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

void CheckConfig(const ProxyConfig& config) {
  if (!FiniteNonNegative(config.radius_m) || !(config.surface_offset_m > 0.0) ||
      !std::isfinite(config.surface_offset_m)) {
    throw std::invalid_argument("proxy: the radius must be finite and >= 0, the offset > 0");
  }
}

}  // namespace

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleTree& tree,
                               ProxyConfig config)
    : mesh_(mesh), tree_(&tree), config_(config) {
  CheckConfig(config_);
}

GodObjectProxy::GodObjectProxy(const TriangleMesh& mesh, const TriangleGrid& grid,
                               ProxyConfig config)
    : mesh_(mesh), grid_(&grid), config_(config) {
  CheckConfig(config_);
  if (config_.radius_m != 0.0) {
    throw std::invalid_argument(
        "proxy: the grid answers a point proxy only; a sphere needs the tree");
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
  return grid_ != nullptr ? grid_->FirstHit(query, hit) : tree_->FirstHit(query, hit);
}

void GodObjectProxy::Update(const Vec3& goal_l) {
  const double offset = config_.surface_offset_m;
  // feasibility slack: well below the offset, well above rounding at scene scale
  const double slack = 0.25 * offset;
  const Vec3 start = position_;
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
  // Load the cell the proxy is heading for while it is still a few ticks away (at
  // 0.05-0.1 mm a tick on a 1M-triangle model a new cell comes every 5 ticks or so).
  const Vec3 step = position_ - start;
  const double length = step.norm();
  if (grid_ != nullptr && length > 0.0) {
    grid_->WarmUp(position_ + (0.75 * grid_->cell_size() / length) * step, &warm_up_);
  }
}

}  // namespace hapticad
