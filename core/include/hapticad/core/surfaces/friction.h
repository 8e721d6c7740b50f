// SPDX-License-Identifier: GPL-3.0-or-later
// Velocity-dependent friction of seed 000 §2.1 (Baraff's model, continuous form).
//
//   f_t = -mu_eq(|v|) f_n v_hat
//
// mu_eq(s), s = |v| the sliding speed (m/s):
//   0 <= s <= eps           mu_s * s / eps          (0 at rest, exactly mu_s at eps)
//   eps < s < eps + w       mu_s -> mu_d, cubic smoothstep (continuous, C1 at eps + w)
//   s >= eps + w            mu_d
// eps is Baraff's threshold below which contact counts as static; w the width of the
// static-to-dynamic transition. w = 0 gives Baraff's piecewise form (Fig. 3), with a
// jump of mu_s - mu_d at eps; the paper's own model (Fig. 4) is "a continuous function
// of velocity", which the default w = eps keeps. With mu_s == mu_d the transition is
// flat.
//
// Eq. 2 as printed, f_t = mu * v_hat, calls mu an "equivalent friction coefficient" and
// leaves out the normal force and the sign; read here as a coefficient (times f_n) of a
// force that opposes the sliding velocity.
//
// Stribeck option (stribeck_speed_mps = v_s > 0): above eps the decay is exponential,
//   mu_d + (mu_s - mu_d) exp(-(s - eps) / v_s),
// continuous at eps and approaching mu_d without reaching it (w is then unused).
//
// The paper's 1-D model may take different parameters for positive and negative
// velocity along a direction: see AnisotropicFriction (anisotropy.h).
//
// Because mu_eq is linear in the band, f_t = -(mu_s / eps) f_n v there: the unit
// vector v_hat is never formed from a tiny |v|, so v = 0, 1e-300 or a denormal give a
// finite force. All functions are pure and safe on the servo tick.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

struct FrictionParams {
  double static_coefficient = 0.5;      // mu_s, dimensionless, >= 0
  double dynamic_coefficient = 0.4;     // mu_d, dimensionless, >= 0
  double stick_speed_mps = 0.002;       // eps, m/s, > 0
  double transition_speed_mps = 0.002;  // w, m/s, >= 0
  double stribeck_speed_mps = 0.0;      // v_s, m/s, >= 0; 0 = smoothstep transition
};

// mu_eq(s) for a sliding speed s >= 0 (m/s). Negative or NaN s returns 0.
double EquivalentFriction(const FrictionParams& params, double speed_mps);

// Friction force (N) for normal force f_n >= 0 (N) and tangential velocity v_t (m/s).
// Opposes v_t. Returns zero for non-finite inputs.
Vec3 CalcFrictionForce(const FrictionParams& params, double normal_force_n, const Vec3& v_t_mps);

}  // namespace hapticad
