// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: VelocityFilter::Update runs on the servo tick.
#include "hapticad/devices/velocity_filter.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace hapticad {

VelocityFilter::VelocityFilter(double cutoff_hz) : cutoff_hz_(cutoff_hz) {
  if (!(cutoff_hz > 0.0 && cutoff_hz <= 1e5)) {
    throw std::invalid_argument("velocity filter: cutoff " + std::to_string(cutoff_hz) +
                                " Hz is outside (0, 1e5]");
  }
  tau_s_ = 1.0 / (2.0 * M_PI * cutoff_hz);
}

void VelocityFilter::Reset() {
  primed_ = false;
  stage1_.setZero();
  velocity_.setZero();
}

bool VelocityFilter::Update(double time_s, const Vec3& position) {
  if (!std::isfinite(time_s) || !position.allFinite()) return false;
  if (!primed_) {
    primed_ = true;
    last_time_s_ = time_s;
    last_position_ = position;
    return true;
  }
  const double dt = time_s - last_time_s_;
  if (!(dt > 0.0)) return false;
  const Vec3 raw = (position - last_position_) / dt;
  // exact discretisation of a first-order lag for this step's dt
  const double alpha = 1.0 - std::exp(-dt / tau_s_);
  stage1_ += alpha * (raw - stage1_);
  velocity_ += alpha * (stage1_ - velocity_);
  last_time_s_ = time_s;
  last_position_ = position;
  return true;
}

}  // namespace hapticad
