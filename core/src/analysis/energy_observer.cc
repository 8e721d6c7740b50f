// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/energy_observer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hapticad {

double CalcColgateStiffnessBound(double device_damping, double virtual_damping, double period_s) {
  if (!(period_s > 0.0) || !std::isfinite(period_s) || !(device_damping >= 0.0) ||
      !std::isfinite(device_damping) || !std::isfinite(virtual_damping)) {
    throw std::invalid_argument(
        "Colgate bound: the period must be > 0 and the damping finite, >= 0");
  }
  return std::max(0.0, 2.0 * (device_damping - std::abs(virtual_damping)) / period_s);
}

}  // namespace hapticad
