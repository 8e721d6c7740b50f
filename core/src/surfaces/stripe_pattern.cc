// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: EvaluateLinear and EvaluateCircular run on the servo tick.
#include "hapticad/core/surfaces/stripe_pattern.h"

#include <algorithm>
#include <cmath>

namespace hapticad {
namespace {

// Some unit vector orthogonal to unit n (the stripe direction when weight is 0).
Vec3 AnyPerpendicular(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return n.cross(helper).normalized();
}

}  // namespace

StripeFrame ProjectStripe(const Vec3& direction, const Vec3& normal) {
  const double length = direction.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return {AnyPerpendicular(normal), 0.0};
  const Vec3 d = direction / length;
  const Vec3 tangent = d - d.dot(normal) * normal;
  const double sine = tangent.norm();  // sine of the angle between d and the normal
  if (!(sine > 1e-12)) return {AnyPerpendicular(normal), 0.0};
  return {tangent / sine, std::min(1.0, sine / kProjectionBlend)};
}

StripeFrame EvaluateLinear(const LinearPattern& pattern, const Vec3& point_w, const Vec3& normal) {
  if (!(pattern.radius_m > 0.0)) return ProjectStripe(pattern.direction_w, normal);
  const Vec3& a = pattern.axis_w;
  // the direction's parts along the axis and round it (a x outward) at the origin ...
  const Vec3 o = pattern.origin_w - pattern.axis_point_w;
  const Vec3 round_o = a.cross(o - o.dot(a) * a) / pattern.radius_m;
  const double along = pattern.direction_w.dot(a), round = pattern.direction_w.dot(round_o);
  // ... kept at the point: the same parts of the axis and of the round direction there
  // (on the axis itself there is no round direction: the one at the origin)
  const Vec3 q = point_w - pattern.axis_point_w;
  const Vec3 radial = q - q.dot(a) * a;
  const double r = radial.norm();
  const Vec3 round_p = r > 1e-9 * pattern.radius_m ? Vec3(a.cross(radial) / r) : round_o;
  return ProjectStripe(along * a + round * round_p, normal);
}

const char* DescribeLinearCylinderProblem(const LinearPattern& p) {
  if (p.radius_m == 0.0) return "";
  if (!(std::isfinite(p.radius_m) && p.radius_m > 0.0)) return "cylinder radius must be > 0";
  if (!p.origin_w.allFinite() || !p.axis_point_w.allFinite() || !p.axis_w.allFinite() ||
      std::abs(p.axis_w.norm() - 1.0) > 1e-6) {
    return "cylinder axis must be a finite point and a unit vector, the origin finite";
  }
  const Vec3 o = p.origin_w - p.axis_point_w;
  const Vec3 radial = o - o.dot(p.axis_w) * p.axis_w;
  if (!(std::abs(radial.norm() - p.radius_m) <= 1e-6 * p.radius_m)) {
    return "origin must lie on the cylinder (radius from the axis)";
  }
  if (std::abs(p.direction_w.dot(radial)) > 1e-6 * p.radius_m) {
    return "direction must be tangent to the cylinder at the origin";
  }
  return "";
}

StripeFrame EvaluateCircular(const CircularPattern& pattern, const Vec3& point_w,
                             const Vec3& normal) {
  const Vec3 offset = point_w - pattern.centre_w;
  const Vec3 radial = offset - offset.dot(pattern.axis_w) * pattern.axis_w;
  const double r = radial.norm();
  // tangent of the circle through the point: axis x radial
  StripeFrame frame = ProjectStripe(pattern.axis_w.cross(radial), normal);
  frame.weight *= std::min(1.0, r / pattern.blend_radius_m);
  return frame;
}

}  // namespace hapticad
