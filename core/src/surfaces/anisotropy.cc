// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: DirectionalFriction runs on the servo tick.
#include "hapticad/core/surfaces/anisotropy.h"

#include <cmath>

namespace hapticad {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double FoldAngle(double theta) {
  // pi-periodic, then even: |theta| mod pi, mirrored about pi/2
  double t = std::fmod(std::abs(theta), kPi);
  if (t > 0.5 * kPi) t = kPi - t;
  return t;
}

double InterpolateFriction(double mu_a, double mu_n, double theta,
                           AnisotropyInterpolation interpolation) {
  if (interpolation == AnisotropyInterpolation::kLinear) {
    return mu_a + 2.0 * theta * (mu_n - mu_a) / kPi;  // seed 000 eq. 3
  }
  if (mu_a == 0.0 || mu_n == 0.0) {
    // A degenerate ellipse, one axis zero: its coefficient on its axes as the header says
    // (mu_a at 0, mu_n at pi/2; 0/0 gave 0 along the stripes), 0 off them, where the
    // ellipse's limit is. The cosine of pi/2 is not 0 in doubles: the end is tested.
    if (theta == 0.0) return mu_a;
    if (theta >= 0.5 * kPi) return mu_n;
    return 0.0;
  }
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return mu_a * mu_n / std::sqrt(mu_n * mu_n * c * c + mu_a * mu_a * s * s);
}

FrictionParams DirectionalFriction(const FrictionParams& along, const AnisotropicFriction& a,
                                   const Vec3& stripe, double weight, const Vec3& v_t) {
  const double along_component = v_t.dot(stripe);
  const double across_component = (v_t - along_component * stripe).norm();
  // folded angle straight from the components: no acos of a rounded cosine
  const double theta = std::atan2(across_component, std::abs(along_component));
  const double scale_a = along_component < 0.0 ? a.backward_factor : 1.0;
  auto mu = [&](double mu_along) {
    const double mu_a = scale_a * mu_along;
    const double mu_n = a.across_factor * mu_along;
    const double anisotropic = InterpolateFriction(mu_a, mu_n, theta, a.interpolation);
    const double isotropic = 0.5 * (mu_along + mu_n);
    return weight * anisotropic + (1.0 - weight) * isotropic;
  };
  FrictionParams out = along;
  out.static_coefficient = mu(along.static_coefficient);
  out.dynamic_coefficient = mu(along.dynamic_coefficient);
  return out;
}

}  // namespace hapticad
