// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/simulated_device.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {

void ScriptedPath::Validate() const {
  if (times_s.empty()) throw std::invalid_argument("scripted path: no waypoints");
  if (times_s.size() != positions_w.size()) {
    throw std::invalid_argument("scripted path: " + std::to_string(times_s.size()) + " times for " +
                                std::to_string(positions_w.size()) + " positions");
  }
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    if (!std::isfinite(times_s[i]) || !positions_w[i].allFinite()) {
      throw std::invalid_argument("scripted path: waypoint " + std::to_string(i) +
                                  " is not finite");
    }
    if (i > 0 && !(times_s[i] > times_s[i - 1])) {
      throw std::invalid_argument("scripted path: time of waypoint " + std::to_string(i) +
                                  " does not increase");
    }
  }
}

SimulatedDevice::SimulatedDevice(ScriptedPath path, DeviceLimits limits) : path_(std::move(path)) {
  path_.Validate();
  info_.kind = "sim";
  info_.name = "Simulated probe (scripted path)";
  info_.path = "sim:scripted";
  info_.limits = limits;
}

bool SimulatedDevice::ReadState(double t, DeviceState* state) {
  const auto& times = path_.times_s;
  const auto& points = path_.positions_w;
  state->time_s = t;
  state->buttons = 0;
  if (t <= times.front() || times.size() == 1) {
    state->position_w = points.front();
    state->velocity_w.setZero();
    return true;
  }
  if (t >= times.back()) {
    state->position_w = points.back();
    state->velocity_w.setZero();
    return true;
  }
  // a session's clock only moves forward; step the cursor, restart if rewound
  if (t < times[segment_]) segment_ = 0;
  while (segment_ + 1 < times.size() && times[segment_ + 1] <= t) ++segment_;
  const double t0 = times[segment_];
  const double t1 = times[segment_ + 1];
  const Vec3 velocity = (points[segment_ + 1] - points[segment_]) / (t1 - t0);
  state->position_w = points[segment_] + (t - t0) * velocity;
  state->velocity_w = velocity;
  return true;
}

}  // namespace hapticad
