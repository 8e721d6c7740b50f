// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CalcViscousTextureForce runs on the servo tick.
#include "hapticad/core/surfaces/viscous_texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hapticad {
namespace {
constexpr double kPi = 3.14159265358979323846;
// e^50: a harmonic 5e21 times the fundamental, which the level's clamp to 0..1 makes a
// square wave long before; finite for any finite beta up to 1e280
constexpr double kMaxHarmonicExponent = 50.0;
}  // namespace

double ViscousTextureLevel(const ViscousTextureParams& p, double x, double speed) {
  if (!std::isfinite(x) || !std::isfinite(speed)) return 0.0;
  const double v = speed / kViscousSpeedUnitMps;
  const double alpha = p.alpha_h + v * p.alpha_vis;
  const double phase = 2.0 * kPi * std::fmod(x, p.period_m) / p.period_m;
  // sin(i phase) by the recurrence s_{i+1} = 2 cos(phase) s_i - s_{i-1}, and
  // i^-alpha = exp(-alpha ln i): one sin, one cos and three exp instead of 4 + 4 calls
  static constexpr double kLog[kViscousHarmonics + 1] = {0.0, 0.0, 0.69314718055994531,
                                                         1.09861228866810969, 1.38629436111989061};
  const double c2 = 2.0 * std::cos(phase);
  double s_previous = 0.0;
  double s_current = std::sin(phase);
  double harmonics = s_current;  // i = 1: 1^-alpha = 1
  for (int i = 2; i <= kViscousHarmonics; ++i) {
    const double s_next = c2 * s_current - s_previous;
    s_previous = s_current;
    s_current = s_next;
    // a harmonic may grow with its order (alpha < 0) but not to inf: inf - inf is NaN,
    // which took the whole force off (the push too) at half of a period at alpha -650
    harmonics += std::exp(std::min(-alpha * kLog[i], kMaxHarmonicExponent)) * s_current;
  }
  return p.f_dc + v * p.f_vis + (p.beta_h + v * p.beta_vis) * harmonics;
}

ViscousTextureParams PaperPreset(int dc, int vis) {
  if (dc < 0 || dc > 2 || vis < 0 || vis > 2)
    throw std::out_of_range("paper preset index outside 0..2");
  ViscousTextureParams p;
  p.f_dc = kPaperDcLevels[dc];
  p.f_vis = kPaperViscosities[vis];
  return p;
}

Vec3 CalcViscousTextureForce(const ViscousTextureParams& params, double full_range_n, double x_m,
                             const Vec3& v_t, double stick_speed_mps) {
  const double s = v_t.norm();
  if (!std::isfinite(s) || !(s > 0.0)) return Vec3::Zero();
  const double raw = ViscousTextureLevel(params, x_m, s);
  // (NaN only from parameters beyond any texture: beta * 5e21 overflowing; nothing felt)
  const double level = std::isnan(raw) ? 0.0 : std::clamp(raw, 0.0, 1.0);
  // magnitude level * range, ramped over the static band; divide by max(s, eps) once
  const double per_speed = level * full_range_n / std::max(s, stick_speed_mps);
  return -per_speed * v_t;
}

}  // namespace hapticad
