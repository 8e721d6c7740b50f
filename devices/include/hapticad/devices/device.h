// SPDX-License-Identifier: GPL-3.0-or-later
// Device: the narrow interface every haptic device backend implements (simulated, HID).
//
// Frames and units: world frame, SI (m, m/s, N). Backends map their own workspace into
// it. ReadState() and WriteForce() are called on the servo thread once per tick: they
// must not allocate, lock or block beyond the device I/O itself.
#pragma once

#include <cstdint>
#include <string>

#include "hapticad/core/vec3.h"

namespace hapticad {

struct DeviceLimits {
  double max_force_n = 3.3;                      // peak force the device can render, N
  double max_stiffness_n_per_m = 400.0;          // largest stable contact stiffness, N/m
  Vec3 workspace_min_w = Vec3::Constant(-0.08);  // reachable box, m
  Vec3 workspace_max_w = Vec3::Constant(0.08);
};

struct DeviceInfo {
  std::string kind;  // "sim", "hid"
  std::string name;
  std::string path;  // where it was found ("sim:scripted", a hidraw path)
  DeviceLimits limits;
};

struct DeviceState {
  double time_s = 0.0;             // device clock, s
  Vec3 position_w = Vec3::Zero();  // m
  Vec3 velocity_w = Vec3::Zero();  // m/s, filtered
  std::uint32_t buttons = 0;       // bit i = button i pressed
};

class Device {
 public:
  virtual ~Device() = default;

  virtual const DeviceInfo& info() const = 0;

  // The latest state. `loop_time_s` is the servo loop's clock (s since it started),
  // which a simulated device uses as its own. Returns false when no valid state is
  // available this tick; the loop then commands zero force.
  virtual bool ReadState(double loop_time_s, DeviceState* state) = 0;

  // Commands a force (N, world frame) until the next call.
  virtual void WriteForce(const Vec3& force_w) = 0;
};

}  // namespace hapticad
