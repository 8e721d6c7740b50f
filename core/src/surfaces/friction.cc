// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CalcFrictionForce runs on the servo tick.
#include "hapticad/core/surfaces/friction.h"

#include <cmath>

namespace hapticad {

double EquivalentFriction(const FrictionParams& p, double s) {
  if (!(s > 0.0)) return 0.0;  // also catches NaN
  const double eps = p.stick_speed_mps;
  if (s <= eps) return p.static_coefficient * (s / eps);
  if (p.stribeck_speed_mps > 0.0) {
    return p.dynamic_coefficient + (p.static_coefficient - p.dynamic_coefficient) *
                                       std::exp(-(s - eps) / p.stribeck_speed_mps);
  }
  const double w = p.transition_speed_mps;
  if (!(s < eps + w)) return p.dynamic_coefficient;
  // smoothstep from mu_s at eps to mu_d at eps + w
  const double x = (s - eps) / w;
  const double blend = x * x * (3.0 - 2.0 * x);
  return p.static_coefficient + (p.dynamic_coefficient - p.static_coefficient) * blend;
}

Vec3 CalcFrictionForce(const FrictionParams& p, double f_n, const Vec3& v_t) {
  const double s = v_t.norm();
  if (!std::isfinite(s) || !std::isfinite(f_n) || f_n <= 0.0) return Vec3::Zero();
  // f_t = -mu_eq(s) f_n v / s, written so that s never divides: in the static band
  // mu_eq(s) / s is the constant mu_s / eps
  const double mu_over_speed = s <= p.stick_speed_mps ? p.static_coefficient / p.stick_speed_mps
                                                      : EquivalentFriction(p, s) / s;
  return -(mu_over_speed * f_n) * v_t;
}

}  // namespace hapticad
