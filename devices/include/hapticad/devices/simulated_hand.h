// SPDX-License-Identifier: GPL-3.0-or-later
// SimulatedHand: a haptic device without hardware whose handle is held by a model of
// a user's hand. The handle is a point mass with damping; the hand pulls it toward a
// target through a spring-damper (the grip, saturating at what a hand pushes); the
// rendered force pushes back. So, as on a real device, a hand aiming into a part is
// stopped at its surface by the force, and friction drags the handle behind the hand.
//
//   m a = F_cmd + sat(k_g (x_target - x) + c_g (v_target - v), F_grip) - b v
//
// integrated in sub-steps of `step_s` (semi-implicit Euler) between reads, the handle
// stopped at the workspace's walls. The force is a zero-order hold of the last command,
// dropped to zero by a device-side watchdog when no command came for `watchdog_s`.
// What the device reports is what a real one would: the position quantised to
// limits.position_resolution_m and `latency_s` old, the velocity estimated from those
// readings by a VelocityFilter.
//
// The target: SetTarget() from any one thread at any time (wait-free mailbox: a GUI's
// mouse), or a ScriptedPath (a script, or a recorded trajectory such as a trace's times
// and positions) set between sessions with FollowPath().
//
// Frames: the device frame `_d` (with the servo loop's default identity mapping it is
// the world frame; give limits whose workspace holds the part). SI units.
// ReadState() and WriteForce() are servo-tick safe (no allocation, lock or I/O).
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "hapticad/devices/device.h"
#include "hapticad/devices/mailbox.h"
#include "hapticad/devices/scripted_path.h"
#include "hapticad/devices/simulated_device.h"
#include "hapticad/devices/velocity_filter.h"

namespace hapticad {

struct HandModel {
  double mass_kg = 0.15;                  // handle and the fingers holding it, > 0
  double damping_n_s_per_m = 1.0;         // mechanism friction and tissue, >= 0
  double grip_stiffness_n_per_m = 400.0;  // the hand's pull toward its target, >= 0
  double grip_damping_n_s_per_m = 6.0;    // relative to the target's velocity, >= 0
  double max_grip_force_n = 15.0;         // a hand pushes only so hard, > 0
  double latency_s = 0.001;               // age of a position report, 0..0.5
  double velocity_cutoff_hz = 40.0;       // the device layer's velocity filter
  double watchdog_s = 0.005;              // device-side watchdog, > 0 (as a HID device's)
  double step_s = 1e-4;                   // physics sub-step, 1e-6..1e-3
};

// Throws std::invalid_argument naming the first bad field.
void ValidateHandModel(const HandModel& model);

// Limits of the default simulated hand: SimulatedProbeLimits() with an Omni's encoder
// step (0.055 mm, field notes).
DeviceLimits SimulatedHandLimits();

// The hand's true state, before quantisation and latency.
struct HandState {
  double time_s = 0.0;
  Vec3 position_d = Vec3::Zero();
  Vec3 velocity_d = Vec3::Zero();
  Vec3 target_d = Vec3::Zero();
  Vec3 force_d = Vec3::Zero();  // the force acting on the handle (after the watchdog)
};

class SimulatedHand final : public Device {
 public:
  // Throws std::invalid_argument for invalid limits or model.
  explicit SimulatedHand(DeviceLimits limits = SimulatedHandLimits(), HandModel model = {});

  const DeviceInfo& info() const override { return info_; }
  // Puts the handle at rest at the target (or the path's start), inside the workspace.
  void BeginSession() override;
  ReadStatus ReadState(double loop_time_s, DeviceState* state) override;
  void WriteForce(const Vec3& force_d) override;
  void EndSession() override;
  // The hand's physics advance with the loop's clock: a host that stalls the servo
  // thread pauses it (no watchdog fault, no skipped ticks; the mouse's target waits).
  bool runs_on_loop_time() const override { return true; }

  // Any one thread, any time: where the hand aims, device frame, m. Non-finite targets
  // are refused (std::invalid_argument). Ignored while following a path.
  void SetTarget(const Vec3& target_d);
  // Between sessions only (std::logic_error during one): follow `path` (validated;
  // std::invalid_argument) from loop time 0, or go back to the target.
  void FollowPath(ScriptedPath path);
  void FollowTarget();
  bool following_path() const { return !path_.times_s.empty(); }

  // The true state as of the last read (one reader thread).
  HandState true_state() { return published_.Read(); }
  const HandModel& model() const { return model_; }
  bool in_session() const { return in_session_.load(std::memory_order_acquire); }

 private:
  struct Reading {
    double time_s;
    Vec3 position_d;
  };
  void Integrate(double t_s);
  Vec3 Quantise(const Vec3& p) const;
  Vec3 Clamp(const Vec3& p) const;

  DeviceInfo info_;
  HandModel model_;
  ScriptedPath path_;
  PathCursor cursor_{&path_};
  Mailbox<Vec3> target_{Vec3::Zero()};
  Mailbox<HandState> published_;
  std::atomic<bool> in_session_{false};

  // servo thread's
  bool started_ = false;
  double time_s_ = 0.0;
  Vec3 position_d_ = Vec3::Zero();
  Vec3 velocity_d_ = Vec3::Zero();
  Vec3 force_d_ = Vec3::Zero();
  double force_time_s_ = 0.0;
  Vec3 target_d_ = Vec3::Zero();
  Vec3 target_velocity_d_ = Vec3::Zero();
  std::vector<Reading> history_;  // ring of readings, for the latency
  std::size_t history_head_ = 0;  // next slot
  std::size_t history_size_ = 0;
  VelocityFilter velocity_filter_;
  double last_reported_time_s_ = -1.0;
};

}  // namespace hapticad
