// SPDX-License-Identifier: GPL-3.0-or-later
// Stripe patterns of seed 000 §2.2: where the stripes (the low-friction direction) run
// at a contact point. Linear and circular patterns here; the user-drawn curve pattern
// is in curve_pattern.h.
//
// A pattern is defined in a plane; on a curved face its direction is carried to the
// contact point by projection onto the tangent plane ("by space projection, the method
// can be extended to ... 3D anisotropic surface", seed 000 §2). On a cylinder a linear
// pattern is instead rolled round the axis, as the roughness grid and the grating are
// (surface_frame.h): stripes round a handle stay round it all the way, and a helix stays
// a helix (projected, a fixed direction turned normal to the face a quarter turn away,
// fading to isotropic there, and "backward" reversed on the far side). Where the
// direction is undefined — the centre of a circular pattern, or a face that turns until
// the stripe direction is normal to it — the frame's weight falls continuously to 0 and
// friction becomes the isotropic mean (anisotropy.h), so force never jumps.
//
// Frame and units: world frame, metres. Evaluation is pure and servo-tick safe.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

struct StripeFrame {
  Vec3 stripe;    // unit tangent along the stripes, orthogonal to the normal
  double weight;  // anisotropy strength in [0, 1]
};

// Below this sine between the stripe direction and the normal, the weight falls
// linearly to zero (about 6 degrees from the normal).
constexpr double kProjectionBlend = 0.1;

// Carries `direction` (any length) onto the tangent plane of unit `normal`.
StripeFrame ProjectStripe(const Vec3& direction, const Vec3& normal);

// Linear pattern: stripes along `direction_w`, a unit vector in the face's plane. The
// plugin sets it from the face's parametric frame at its centre: the u direction
// (dS/du) turned by the pattern angle counter-clockwise about the outward normal.
// On a cylinder (radius_m > 0: the face lies radius_m from the line through
// axis_point_w along the unit axis_w, and direction_w is tangent to it at origin_w, a
// point of the face) the direction is rolled round the axis to the contact point: the
// same parts along the axis and round it.
struct LinearPattern {
  Vec3 direction_w;
  double radius_m = 0.0;  // 0: a plane (or any other face: projected)
  Vec3 origin_w = Vec3::Zero();
  Vec3 axis_point_w = Vec3::Zero();
  Vec3 axis_w = Vec3::UnitZ();
};
StripeFrame EvaluateLinear(const LinearPattern& pattern, const Vec3& point_w, const Vec3& normal);
// What is wrong with a linear pattern's cylinder ("" when nothing, or when it has none).
const char* DescribeLinearCylinderProblem(const LinearPattern& pattern);

// Circular pattern: stripes run along circles about the line through `centre_w` with
// direction `axis_w` (unit). Within `blend_radius_m` of the centre the weight falls
// linearly to 0 at the centre itself, where the circle's tangent is undefined.
struct CircularPattern {
  Vec3 centre_w;
  Vec3 axis_w;
  double blend_radius_m;  // > 0
};
StripeFrame EvaluateCircular(const CircularPattern& pattern, const Vec3& point_w,
                             const Vec3& normal);

}  // namespace hapticad
