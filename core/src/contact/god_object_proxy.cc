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
  warmed_triangle_ = kNoTriangle;
  warm_step_ = 0;
}

bool GodObjectProxy::ResetOutside(const Vec3& position_l) {
  Reset(position_l);
  const SolidAnalysis* solids = config_.solids;
  // outside every piece's box (or not a point): outside every solid
  if (solids == nullptr || !solids->bounds_solids || !position_l.allFinite() ||
      !solids->InAnyPiece(position_l)) {
    return false;
  }
  // three orthonormal directions (15 times the rows of a rotation) and their opposites,
  // askew to every axis and axis plane, so no ray runs along an axis-aligned CAD
  // model's faces (constexpr: a function-local static would take a guard on first use)
  static constexpr double kAxes[3][3] = {{-11.0, -2.0, 10.0}, {10.0, -5.0, 10.0}, {2.0, 14.0, 5.0}};
  int inside = 0;
  int outside = 0;
  struct Exit {
    double distance;
    SweepHit hit;
  } exits[kExitRays];
  for (int ray = 0; ray < kExitRays; ++ray) {
    const double* axis = kAxes[ray / 2];
    const Vec3 u = (ray % 2 == 0 ? 1.0 : -1.0) / 15.0 * Vec3(axis[0], axis[1], axis[2]);
    SweepHit first;
    const int crossings = CountCrossings(position_l, u, &first);
    if (crossings < 0) continue;
    if (crossings % 2 == 0) {
      ++outside;
      continue;
    }
    exits[inside++] = {(first.point - position_l).norm(), first};
  }
  if (inside <= outside) return false;
  // nearest first; an insertion sort of at most six (std::sort's path for more than 16,
  // dead here, draws GCC 12's -Warray-bounds)
  for (int i = 1; i < inside; ++i) {
    for (int j = i; j > 0 && exits[j].distance < exits[j - 1].distance; --j) {
      std::swap(exits[j], exits[j - 1]);
    }
  }
  const double r = config_.radius_m;
  const double offset = config_.surface_offset_m;
  for (int i = 0; i < inside; ++i) {
    // off the face it crossed, on the far side (the hit's normal faces the inside)
    const Vec3& face = exits[i].hit.point;
    const Vec3 out = -exits[i].hit.normal;
    SweepHit blocked;
    if (r > 0.0 && PointHit(face + offset * out, face + (2.0 * r + offset) * out, &blocked)) {
      continue;  // a sphere there would stick into something else
    }
    Reset(face + (r + offset) * out);
    return true;
  }
  return false;
}

int GodObjectProxy::CountCrossings(const Vec3& p, const Vec3& u, SweepHit* first) const {
  const Vec3 end = p + (p.norm() + mesh_.bounding_radius()) * u;  // beyond every vertex
  // past each crossing by the surface offset, so the next sweep does not meet it (or
  // its neighbour across an edge it went through) again
  const double step = config_.surface_offset_m;
  Vec3 a = p;
  for (int crossings = 0; crossings <= kMaxCrossings; ++crossings) {
    SweepHit hit;
    if (!PointHit(a, end, &hit)) return crossings;
    if (crossings == 0) *first = hit;
    a = hit.point + step * u;
    if ((end - a).dot(u) <= 0.0) return crossings + 1;
  }
  return -1;
}

bool GodObjectProxy::Sweep(const Vec3& a, const Vec3& b, double radius, const SweepFloors* floors,
                           std::int64_t hint, SweepHit* hit) const {
  SweepQuery query;
  query.radius = radius;
  query.bary_tol = config_.bary_tolerance;
  query.floors = floors;
  query.hint = hint;
  query.a = a;
  query.b = b;
  SweepSearch search(mesh_, query);
  ++sweeps_;
  if (config_.pieces != nullptr && config_.pieces->Settle(query, &search)) {
    ++settled_sweeps_;
  } else {
    if (grid_ != nullptr) {
      grid_->Search(&search);
    } else {
      tree_->Search(&search);
    }
  }
  if (!search.found()) return false;
  search.Report(hit);
  return true;
}

bool GodObjectProxy::PointHit(const Vec3& a, const Vec3& b, SweepHit* hit) const {
  return Sweep(a, b, 0.0, nullptr, -1, hit);
}

bool GodObjectProxy::FirstHit(const Vec3& a, const Vec3& b, SweepHit* hit,
                              const SweepFloors* floors, std::int64_t hint) {
  return Sweep(a, b, config_.radius_m, floors, hint, hit);
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
  std::int64_t hint = last_triangle_;  // the last contact: the likeliest to be hit
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Vec3 d = target - position_;
    if (d.squaredNorm() <= slack * slack) break;
    floors.count = constraints_.count();
    for (int i = 0; i < floors.count; ++i) {
      floors.normal[i] = constraints_.plane(i).normal;
      floors.offset[i] = constraints_.plane(i).offset - config_.radius_m - 0.5 * offset;
    }
    SweepHit hit;
    if (!FirstHit(position_, target, &hit, &floors, hint)) {
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
    hint = hit.triangle;
    constraints_.Add({n, plane_offset, hit.triangle}, slack);
    target = constraints_.Project(goal_l, position_, slack);
  }
  // kept through a lift-off: a sweep that stays above it is proven free (ConvexPieces)
  if (in_contact()) last_triangle_ = constraints_.plane(0).triangle;
  // Load what the next ticks will read: on a convex piece the triangles round the
  // contact (once per contact triangle, a step a tick over its first three ticks), else
  // the grid's cells the proxy is heading for.
  if (config_.pieces != nullptr && in_contact()) {
    const std::uint32_t t = constraints_.plane(0).triangle;
    if (t == warmed_triangle_) {
      if (warm_step_ < ConvexPieces::kWarmUpSteps) config_.pieces->WarmUp(t, warm_step_++);
      return;
    }
    if (config_.pieces->WarmUp(t, 0)) {
      warmed_triangle_ = t;
      warm_step_ = 1;
      return;
    }
  }
  // The cells ahead, while they are still a few ticks away (at 0.05-0.1 mm a tick on a
  // 1M-triangle model a new cell comes every 5 ticks or so): every cell on the next
  // 0.75 cell of its path.
  const Vec3 step = position_ - start;
  const double length = step.norm();
  if (grid_ != nullptr && length > 0.0) {
    grid_->WarmUp(position_, position_ + (0.75 * grid_->cell_size() / length) * step, &warm_up_);
  }
}

}  // namespace hapticad
