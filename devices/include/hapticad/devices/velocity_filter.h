// SPDX-License-Identifier: GPL-3.0-or-later
// VelocityFilter: handle velocity from timestamped positions, as a device layer must
// estimate it from encoder readings. The finite difference of consecutive positions
// goes through two cascaded first-order low-pass stages (a critically damped
// second-order filter) whose coefficients follow each sample's own time step, so late
// or bunched reports do not bias it. A 0.055 mm encoder step differenced at 1 kHz is
// ±55 mm/s of noise: the default 40 Hz cutoff brings it to a few mm/s at the price of
// about 8 ms of lag.
//
// Units: s, m, m/s; any frame. Servo-tick safe (no allocation).
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

class VelocityFilter {
 public:
  // Throws std::invalid_argument unless 0 < cutoff_hz <= 1e5.
  explicit VelocityFilter(double cutoff_hz = 40.0);

  // Forgets the history; the next Update() only records its position.
  void Reset();

  // Adds a sample taken at `time_s`. Returns false (and ignores the sample) when
  // time does not move forward or the inputs are not finite.
  bool Update(double time_s, const Vec3& position);

  const Vec3& velocity() const { return velocity_; }
  double cutoff_hz() const { return cutoff_hz_; }

 private:
  double cutoff_hz_;
  double tau_s_;
  bool primed_ = false;
  double last_time_s_ = 0.0;
  Vec3 last_position_ = Vec3::Zero();
  Vec3 stage1_ = Vec3::Zero();
  Vec3 velocity_ = Vec3::Zero();
};

}  // namespace hapticad
