// SPDX-License-Identifier: GPL-3.0-or-later
// Anisotropic friction of seed 000 §2.2: a friction coefficient that depends on the
// direction of sliding relative to the stripes of a pattern.
//
// mu_a is the coefficient along the stripes (the low-friction direction), mu_n across
// them. For a sliding direction at angle theta to the stripes:
//   eq. 3 (paper)      mu(theta) = mu_a + 2 theta (mu_n - mu_a) / pi
//   friction ellipse   mu(theta) = mu_a mu_n / sqrt(mu_n^2 cos^2 theta + mu_a^2 sin^2 theta)
// with theta folded into [0, pi/2] (mu is even and pi-periodic in theta). The ellipse is
// the orthotropic (physically derived) alternative; both agree at 0 and pi/2.
//
// The paper's 1-D model allows different parameters for positive and negative
// velocity along a direction: backward_factor scales mu_a when the velocity points
// against the stripe direction (v . t < 0), as on fabric or a fish scale.
//
// The friction force still opposes the velocity (seed 000 eq. 2): only its magnitude
// depends on direction. A true orthotropic contact would also turn the force away from
// -v; the paper, and HaptiCAD, do not. All functions are pure and servo-tick safe.
#pragma once

#include "hapticad/core/surfaces/friction.h"
#include "hapticad/core/vec3.h"

namespace hapticad {

enum class AnisotropyInterpolation { kLinear, kEllipse };

// Folds any angle (radians) into [0, pi/2]: even and pi-periodic. NaN stays NaN.
double FoldAngle(double theta);

// mu(theta) for theta already folded into [0, pi/2].
double InterpolateFriction(double mu_along, double mu_across, double theta,
                           AnisotropyInterpolation interpolation);

struct AnisotropicFriction {
  double across_factor = 1.5;    // mu_n / mu_a (static and dynamic alike), >= 0
  double backward_factor = 1.0;  // mu_a against the stripe direction / along it, >= 0
  AnisotropyInterpolation interpolation = AnisotropyInterpolation::kLinear;
};

// The friction parameters for sliding with tangential velocity v_t on a surface whose
// stripes run along the unit tangent `stripe`. `weight` in [0, 1] blends from the
// isotropic mean of mu_a and mu_n (0) to the full anisotropy (1); patterns use it where
// their direction is undefined. `along` holds mu_a (static, dynamic) and the speeds.
FrictionParams DirectionalFriction(const FrictionParams& along, const AnisotropicFriction& a,
                                   const Vec3& stripe, double weight, const Vec3& v_t);

}  // namespace hapticad
