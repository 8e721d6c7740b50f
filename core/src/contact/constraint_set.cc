// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ConstraintSet::Add, Feasible and Project run on the servo tick (proxy update).
#include "hapticad/core/contact/constraint_set.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace hapticad {

bool ConstraintSet::Add(const ConstraintPlane& plane, double tolerance) {
  if (full()) return false;
  for (int i = 0; i < count_; ++i) {
    // coplanar triangles of one face give the same plane: one constraint is enough
    if (planes_[i].normal.dot(plane.normal) > 1.0 - 1e-12 &&
        std::abs(planes_[i].offset - plane.offset) <= tolerance) {
      return false;
    }
  }
  planes_[count_++] = plane;
  return true;
}

bool ConstraintSet::Feasible(const Vec3& x, double tolerance) const {
  for (int i = 0; i < count_; ++i) {
    if (planes_[i].normal.dot(x) < planes_[i].offset - tolerance) return false;
  }
  return true;
}

Vec3 ConstraintSet::Project(const Vec3& goal, const Vec3& fallback, double tolerance) const {
  if (Feasible(goal, tolerance)) return goal;
  double best_d2 = std::numeric_limits<double>::infinity();
  Vec3 best = fallback;
  auto consider = [&](const Vec3& x) {
    const double d2 = (x - goal).squaredNorm();
    if (d2 < best_d2 && Feasible(x, tolerance)) {
      best_d2 = d2;
      best = x;
    }
  };
  // onto one plane
  for (int i = 0; i < count_; ++i) {
    const ConstraintPlane& p = planes_[i];
    consider(goal - (p.normal.dot(goal) - p.offset) * p.normal);
  }
  // onto the line of two planes: x = g - a n_i - b n_j with n_i.x = d_i, n_j.x = d_j
  for (int i = 0; i < count_; ++i) {
    for (int j = i + 1; j < count_; ++j) {
      const ConstraintPlane& p = planes_[i];
      const ConstraintPlane& q = planes_[j];
      const double c = p.normal.dot(q.normal);
      const double det = 1.0 - c * c;
      if (det < 1e-12) continue;  // parallel planes have no line
      const double ri = p.normal.dot(goal) - p.offset;
      const double rj = q.normal.dot(goal) - q.offset;
      const double a = (ri - c * rj) / det;
      const double b = (rj - c * ri) / det;
      consider(goal - a * p.normal - b * q.normal);
    }
  }
  // onto the point of three planes
  if (count_ == 3) {
    Eigen::Matrix3d n;
    n.row(0) = planes_[0].normal.transpose();
    n.row(1) = planes_[1].normal.transpose();
    n.row(2) = planes_[2].normal.transpose();
    if (std::abs(n.determinant()) > 1e-9) {
      consider(
          n.partialPivLu().solve(Vec3(planes_[0].offset, planes_[1].offset, planes_[2].offset)));
    }
  }
  return best;
}

}  // namespace hapticad
