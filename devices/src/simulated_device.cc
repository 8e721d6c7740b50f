// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ReadState and WriteForce run on the servo tick.
#include "hapticad/devices/simulated_device.h"

#include <utility>

namespace hapticad {

SimulatedDevice::SimulatedDevice(ScriptedPath path, DeviceLimits limits) : path_(std::move(path)) {
  path_.Validate();
  ValidateDeviceLimits(limits);
  for (const Vec3& p : path_.positions) {
    limits.workspace_min_d = limits.workspace_min_d.cwiseMin(p);
    limits.workspace_max_d = limits.workspace_max_d.cwiseMax(p);
  }
  info_.kind = "sim";
  info_.name = "Simulated probe (scripted path)";
  info_.path = "sim:scripted";
  info_.limits = limits;
}

ReadStatus SimulatedDevice::ReadState(double t, DeviceState* state) {
  const PathSample sample = cursor_.Sample(t);
  state->time_s = t;
  state->position_d = sample.position;
  state->velocity_d = sample.velocity;
  state->buttons = 0;
  state->age_s = 0.0;
  return ReadStatus::kOk;
}

}  // namespace hapticad
