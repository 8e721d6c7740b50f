// SPDX-License-Identifier: GPL-3.0-or-later
// ForceSafety: the last word on every force the servo loop sends, independent of the
// renderer (which may be wrong, or new).
//
//   reading check  unplugged, no data yet, device-reported fault, stale data (age over
//                  `stale_after_s`), a loop gap over `watchdog_s`, non-finite or
//                  impossible position or speed (outside the workspace grown by
//                  `workspace_margin` of its size, faster than `max_speed_mps`)
//                  => zero force this tick, a kFault* flag
//   force shaping  non-finite force => zero and kFaultNonFinite; clamp to the device's
//                  max_force_n; hold to continuous_force_n once the force's thermal
//                  average (I^2 t: mean of |F|^2 over `thermal_time_constant_s`) exceeds
//                  it, the cap moving between the two over `ramp_s` (no step either
//                  way); ramp linearly over `ramp_s` at session start, after any fault
//                  and whenever the loop asks: from the force last sent at a scene
//                  swap (the hand still touches: no step), from zero after a new
//                  mapping or a clutch release, after a fault and at the start (a
//                  force no contact backs any more stops at once; stopping adds no
//                  energy)
//   give up        faults (or no data) for `fault_timeout_s` without a break
//
// Units: s, m, N (device frame). Servo-tick safe (no allocation, no lock, no I/O).
#pragma once

#include <cstdint>

#include "hapticad/devices/device.h"

namespace hapticad {

struct SafetyConfig {
  double ramp_s = 0.2;                    // >= 0; 0 disables the ramp
  double watchdog_s = 0.005;              // > 0
  double stale_after_s = 0.005;           // > 0
  double fault_timeout_s = 2.0;           // > 0
  double workspace_margin = 0.25;         // >= 0, fraction of the workspace's size per axis
  double max_speed_mps = 10.0;            // > 0
  double thermal_time_constant_s = 10.0;  // > 0
};

// Throws std::invalid_argument naming the first bad field.
void ValidateSafetyConfig(const SafetyConfig& config);

enum class RampFrom { kLastSent, kZero };

class ForceSafety {
 public:
  // Throws std::invalid_argument for invalid limits or config.
  ForceSafety(const DeviceLimits& limits, const SafetyConfig& config);

  // Starts a session at loop time `t_s`: the ramp starts, the thermal average and
  // the fault history are cleared.
  void BeginSession(double t_s);

  // The kFault* flags of one reading (0: it may be rendered). `gap_s` is the time
  // since the previous tick started (0 for the first tick).
  std::uint32_t CheckReading(ReadStatus status, const DeviceState& state, double gap_s) const;

  // The force to send at loop time `t_s`, given this tick's fault flags and the
  // rendered force (device frame). Adds kDeviceFault, kFaultNonFinite, kRamping,
  // kSafetyClamped or kThermalLimited to `*flags`.
  Vec3 Shape(double t_s, std::uint32_t faults, const Vec3& force_d, std::uint32_t* flags);

  // Ramps again starting with the next tick, over `ramp_s`, to the force asked for:
  // from the force last sent (zero after a fault), or from zero (the force last sent
  // stops at once: what the hand touched before says nothing any more).
  void RestartRamp(RampFrom from) {
    ramp_pending_ = true;
    if (from == RampFrom::kZero) last_sent_.setZero();
  }
  // The force a ramp blends from stops now: nothing the hand touches backs it any more
  // (no contact, or the clutch). The rest of a running ramp goes from zero.
  void DropBlend() {
    ramp_from_.setZero();
    last_sent_.setZero();
  }

  // True when faults have lasted `fault_timeout_s` without a good tick in between.
  bool fault_timed_out() const { return fault_timed_out_; }
  double thermal_force_n() const;  // sqrt of the thermal average, N

  const DeviceLimits& limits() const { return limits_; }
  const SafetyConfig& config() const { return config_; }

 private:
  DeviceLimits limits_;
  SafetyConfig config_;
  Vec3 allowed_min_d_;
  Vec3 allowed_max_d_;
  bool ramp_pending_ = true;
  double ramp_start_s_ = 0.0;
  Vec3 ramp_from_ = Vec3::Zero();  // the force the ramp starts from
  Vec3 last_sent_ = Vec3::Zero();  // what Shape() returned last
  bool in_fault_ = false;
  double fault_since_s_ = 0.0;
  bool fault_timed_out_ = false;
  bool have_time_ = false;
  double last_t_s_ = 0.0;
  double heat_n2_ = 0.0;        // thermal average of |F|^2, N^2
  double thermal_cap_n_ = 0.0;  // the force allowed by the motors' heat, N (slews)
};

}  // namespace hapticad
