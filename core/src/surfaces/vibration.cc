// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CalcVibrationForce runs on the servo tick.
#include "hapticad/core/surfaces/vibration.h"

#include <cmath>

namespace hapticad {

Vec3 CalcVibrationForce(const Vibration& v, double t) {
  if (!v.powered || !std::isfinite(t)) return Vec3::Zero();
  // phase from the fractional number of cycles: exact for long sessions
  const double cycles = v.frequency_hz * t;
  const double phase = 2.0 * 3.14159265358979323846 * (cycles - std::floor(cycles));
  return v.amplitude_n * std::sin(phase) * v.axis_w;
}

}  // namespace hapticad
