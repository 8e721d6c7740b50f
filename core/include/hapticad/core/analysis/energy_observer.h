// SPDX-License-Identifier: GPL-3.0-or-later
// EnergyObserver: the passivity observer of Hannaford and Ryu (2002, "Time-domain
// passivity control of haptic interfaces"), and Colgate's stiffness bound.
//
// A haptic display (the virtual environment rendered through a device) is passive if it
// never gives out more energy than it took in. The observer sums, over servo ticks, the
// energy absorbed at the operator's port:
//   E(n) = sum_{k <= n} [ -F(k) . (x(k+1) - x(k))  +  b |x(k+1) - x(k)|^2 / T(k) ]
// The first term is what the environment absorbs, F(k) being the force it commanded
// (held over the tick by the device's zero-order hold) and x the device position; the
// second is the least the device's own damping b dissipates over a tick of length T
// (by Cauchy-Schwarz, b int v^2 >= b dx^2 / T). E < 0 means the display made energy:
// the sampled spring is too stiff for the device's damping and rate. With b = 0 this
// is the environment's port alone, as in Hannaford and Ryu.
//
// Colgate and Schenkel (1997): a sampled spring K with virtual damping B on a device of
// physical damping b at period T is passive if b > K T / 2 + |B|, so K < 2 (b - |B|) / T.
// The observer's per-tick balance, -K dx^2 / 2 + b dx^2 / T, says the same.
//
// Units: SI (N, m, s, J, N/m, N s/m). Observe() is servo-tick safe (no allocation).
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

class EnergyObserver {
 public:
  // `device_damping` (N s/m, >= 0): the device's own damping, 0 to observe the virtual
  // environment alone.
  explicit EnergyObserver(double device_damping = 0.0) : damping_(device_damping) {}

  // Records one tick of length `period_s` (> 0): the force commanded at position
  // x_before, held until the device reached x_after.
  void Observe(const Vec3& force_n, const Vec3& x_before_m, const Vec3& x_after_m,
               double period_s) {
    const Vec3 dx = x_after_m - x_before_m;
    energy_j_ += -force_n.dot(dx) + damping_ * dx.squaredNorm() / period_s;
    if (energy_j_ < lowest_j_) lowest_j_ = energy_j_;
  }
  void Reset() { energy_j_ = lowest_j_ = 0.0; }

  double energy_j() const { return energy_j_; }  // absorbed so far (>= 0 when passive)
  double lowest_j() const { return lowest_j_; }  // the least it has been

 private:
  double damping_;
  double energy_j_ = 0.0;
  double lowest_j_ = 0.0;
};

// The largest passive stiffness for a device of damping `device_damping` (N s/m) at the
// longest servo period `period_s`, with virtual damping `virtual_damping` rendered as
// well. Zero when the virtual damping already takes all the device's. Throws
// std::invalid_argument for a non-positive period or negative damping.
double CalcColgateStiffnessBound(double device_damping, double virtual_damping, double period_s);

}  // namespace hapticad
