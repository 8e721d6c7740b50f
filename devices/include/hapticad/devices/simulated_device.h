// SPDX-License-Identifier: GPL-3.0-or-later
// SimulatedDevice: a probe that follows a scripted path, for headless feeling, tests and
// demos without hardware. It does not react to the force it is sent (a position-
// controlled probe); it records the last command.
//
// ScriptedPath: waypoints (time s, position m, world frame) with strictly increasing
// times; the probe moves linearly between them and rests at the last one. Velocity is
// exact: the slope of the current segment.
#pragma once

#include <cstddef>
#include <vector>

#include "hapticad/devices/device.h"

namespace hapticad {

struct ScriptedPath {
  std::vector<double> times_s;
  std::vector<Vec3> positions_w;

  // Throws std::invalid_argument if empty, of unequal lengths, with non-finite values
  // or with times that do not strictly increase.
  void Validate() const;
  double duration_s() const { return times_s.empty() ? 0.0 : times_s.back(); }
};

// A simulated probe has no motors: by default it takes the limits of a capable desktop
// device (Novint Falcon class: 8.9 N, 3 N/mm, about 0.1 m of travel; field notes), so
// what a designer tunes on it is renderable on real hardware of that class.
inline DeviceLimits SimulatedProbeLimits() {
  DeviceLimits limits;
  limits.max_force_n = 8.9;
  limits.max_stiffness_n_per_m = 3000.0;
  limits.workspace_min_w = Vec3::Constant(-0.05);
  limits.workspace_max_w = Vec3::Constant(0.05);
  return limits;
}

class SimulatedDevice final : public Device {
 public:
  SimulatedDevice(ScriptedPath path, DeviceLimits limits);

  const DeviceInfo& info() const override { return info_; }
  bool ReadState(double loop_time_s, DeviceState* state) override;
  void WriteForce(const Vec3& force_w) override { last_force_w_ = force_w; }

  const Vec3& last_force_w() const { return last_force_w_; }
  const ScriptedPath& path() const { return path_; }

 private:
  DeviceInfo info_;
  ScriptedPath path_;
  std::size_t segment_ = 0;  // cursor: time only moves forward in a session
  Vec3 last_force_w_ = Vec3::Zero();
};

}  // namespace hapticad
