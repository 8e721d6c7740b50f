// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CalcFrameCoordinates runs on the servo tick.
#include "hapticad/core/surfaces/surface_frame.h"

#include <cmath>

namespace hapticad {

FrameCoordinates CalcFrameCoordinates(const SurfaceFrame& frame, const Vec3& point_w) {
  FrameCoordinates c;
  if (!(frame.radius_m > 0.0)) {
    const Vec3 local = point_w - frame.origin_w;
    c.x = local.dot(frame.e1_w);
    c.y = local.dot(frame.e2_w);
    c.e1_w = frame.e1_w;
    c.e2_w = frame.e2_w;
    return c;
  }
  const Vec3& a = frame.axis_w;
  // the origin's radial and round directions (b1 outward from the axis, b2 = a x b1)
  const Vec3 o = frame.origin_w - frame.axis_point_w;
  const Vec3 b1 = (o - o.dot(a) * a) / frame.radius_m;
  const Vec3 b2 = a.cross(b1);
  const Vec3 q = point_w - frame.axis_point_w;
  const double t = (q - o).dot(a);
  const double angle = std::atan2(q.dot(b2), q.dot(b1));
  const double s = frame.radius_m * angle;
  // (s, t) in the origin's tangent plane, spanned by b2 and a
  const double e1_round = frame.e1_w.dot(b2), e1_along = frame.e1_w.dot(a);
  const double e2_round = frame.e2_w.dot(b2), e2_along = frame.e2_w.dot(a);
  c.x = s * e1_round + t * e1_along;
  c.y = s * e2_round + t * e2_along;
  // the round direction at the point: b2 turned by the angle about the axis
  const Vec3 round = std::cos(angle) * b2 - std::sin(angle) * b1;
  c.e1_w = e1_round * round + e1_along * a;
  c.e2_w = e2_round * round + e2_along * a;
  return c;
}

const char* DescribeFrameProblem(const SurfaceFrame& f) {
  auto unit = [](const Vec3& v) { return v.allFinite() && std::abs(v.norm() - 1.0) <= 1e-6; };
  if (!f.origin_w.allFinite()) return "origin is not finite";
  if (!unit(f.e1_w) || !unit(f.e2_w)) return "e1 and e2 must be finite unit vectors";
  if (std::abs(f.e1_w.dot(f.e2_w)) > 1e-6) return "e1 and e2 must be orthogonal";
  if (f.radius_m == 0.0) return "";
  if (!(std::isfinite(f.radius_m) && f.radius_m > 0.0)) return "cylinder radius must be > 0";
  if (!f.axis_point_w.allFinite() || !unit(f.axis_w)) {
    return "cylinder axis must be a finite point and a unit vector";
  }
  const Vec3 normal = f.e1_w.cross(f.e2_w);
  if (std::abs(normal.dot(f.axis_w)) > 1e-6) {
    return "cylinder axis must lie in the frame's tangent plane";
  }
  const Vec3 o = f.origin_w - f.axis_point_w;
  const double distance = (o - o.dot(f.axis_w) * f.axis_w).norm();
  if (!(std::abs(distance - f.radius_m) <= 1e-6 * f.radius_m)) {
    return "origin must lie on the cylinder (radius from the axis)";
  }
  return "";
}

}  // namespace hapticad
