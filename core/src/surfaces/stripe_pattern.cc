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

StripeFrame EvaluateLinear(const LinearPattern& pattern, const Vec3& normal) {
  return ProjectStripe(pattern.direction_w, normal);
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
