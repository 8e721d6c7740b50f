// SPDX-License-Identifier: GPL-3.0-or-later
// SimulatedDevice: a position-controlled probe that follows a ScriptedPath exactly,
// for reproducible strokes (`hapticad feel`), tests and demos without hardware. It
// does not react to the force it is sent (see SimulatedHand for a handle that does);
// it records the last command. Velocity is exact: the slope of the current segment.
//
// Its workspace is the limits' box grown to hold the whole path (a script goes where
// it says), so the safety layer never mistakes a scripted stroke for a bad reading.
// It lives on the loop's clock (runs_on_loop_time): a host stall pauses the stroke.
#pragma once

#include "hapticad/devices/device.h"
#include "hapticad/devices/scripted_path.h"

namespace hapticad {

// A simulated probe has no motors: by default it takes the limits of a capable desktop
// device (Novint Falcon class: 8.9 N, 3 N/mm, about 0.1 m of travel; field notes), so
// what a designer tunes on it is renderable on real hardware of that class.
inline DeviceLimits SimulatedProbeLimits() {
  DeviceLimits limits;
  limits.max_force_n = 8.9;
  limits.max_stiffness_n_per_m = 3000.0;
  limits.workspace_min_d = Vec3::Constant(-0.05);
  limits.workspace_max_d = Vec3::Constant(0.05);
  return limits;
}

class SimulatedDevice final : public Device {
 public:
  // Throws std::invalid_argument for an invalid path or limits.
  SimulatedDevice(ScriptedPath path, DeviceLimits limits);

  const DeviceInfo& info() const override { return info_; }
  ReadStatus ReadState(double loop_time_s, DeviceState* state) override;
  void WriteForce(const Vec3& force_d) override { last_force_d_ = force_d; }
  bool runs_on_loop_time() const override { return true; }

  const Vec3& last_force_d() const { return last_force_d_; }
  const ScriptedPath& path() const { return path_; }

 private:
  DeviceInfo info_;
  ScriptedPath path_;
  PathCursor cursor_{&path_};
  Vec3 last_force_d_ = Vec3::Zero();
};

}  // namespace hapticad
