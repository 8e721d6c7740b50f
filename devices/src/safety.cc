// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: CheckReading and Shape run on the servo tick.
#include "hapticad/devices/safety.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hapticad/devices/trace_sample.h"

namespace hapticad {
namespace {

void Require(bool ok, const char* field, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("safety config: ") + field + " = " +
                                std::to_string(value) + " is out of range");
  }
}

}  // namespace

void ValidateSafetyConfig(const SafetyConfig& c) {
  Require(std::isfinite(c.ramp_s) && c.ramp_s >= 0.0, "ramp_s", c.ramp_s);
  Require(std::isfinite(c.watchdog_s) && c.watchdog_s > 0.0, "watchdog_s", c.watchdog_s);
  Require(std::isfinite(c.stale_after_s) && c.stale_after_s > 0.0, "stale_after_s",
          c.stale_after_s);
  Require(std::isfinite(c.fault_timeout_s) && c.fault_timeout_s > 0.0, "fault_timeout_s",
          c.fault_timeout_s);
  Require(std::isfinite(c.workspace_margin) && c.workspace_margin >= 0.0, "workspace_margin",
          c.workspace_margin);
  Require(std::isfinite(c.max_speed_mps) && c.max_speed_mps > 0.0, "max_speed_mps",
          c.max_speed_mps);
  Require(std::isfinite(c.thermal_time_constant_s) && c.thermal_time_constant_s > 0.0,
          "thermal_time_constant_s", c.thermal_time_constant_s);
}

ForceSafety::ForceSafety(const DeviceLimits& limits, const SafetyConfig& config)
    : limits_(limits), config_(config) {
  ValidateDeviceLimits(limits);
  ValidateSafetyConfig(config);
  thermal_cap_n_ = limits.max_force_n;
  const Vec3 margin = config.workspace_margin * (limits.workspace_max_d - limits.workspace_min_d);
  allowed_min_d_ = limits.workspace_min_d - margin;
  allowed_max_d_ = limits.workspace_max_d + margin;
}

void ForceSafety::BeginSession(double t_s) {
  ramp_pending_ = false;
  ramp_start_s_ = t_s;
  ramp_from_.setZero();
  last_sent_.setZero();
  in_fault_ = false;
  fault_timed_out_ = false;
  have_time_ = false;
  heat_n2_ = 0.0;
  thermal_cap_n_ = limits_.max_force_n;
}

std::uint32_t ForceSafety::CheckReading(ReadStatus status, const DeviceState& s,
                                        double gap_s) const {
  std::uint32_t faults = 0;
  switch (status) {
    case ReadStatus::kOk:
      break;
    case ReadStatus::kNoData:
      faults |= kFaultNoData;
      break;
    case ReadStatus::kOutOfRange:
      faults |= kFaultOutOfRange;
      break;
    case ReadStatus::kDeviceFault:
      faults |= kFaultReported;
      break;
    case ReadStatus::kUnplugged:
      faults |= kFaultUnplugged;
      break;
  }
  if (gap_s > config_.watchdog_s) faults |= kFaultWatchdog;
  if (status != ReadStatus::kOk) return faults;
  // the device said ok: check what it said anyway
  if (!s.position_d.allFinite() || !s.velocity_d.allFinite() || !std::isfinite(s.age_s)) {
    return faults | kFaultNonFinite;
  }
  if (s.age_s > config_.stale_after_s) faults |= kFaultStale;
  if (!(s.position_d.array() >= allowed_min_d_.array()).all() ||
      !(s.position_d.array() <= allowed_max_d_.array()).all() ||
      s.velocity_d.norm() > config_.max_speed_mps) {
    faults |= kFaultOutOfRange;
  }
  return faults;
}

Vec3 ForceSafety::Shape(double t_s, std::uint32_t faults, const Vec3& force_d,
                        std::uint32_t* flags) {
  const double dt = have_time_ ? std::max(0.0, t_s - last_t_s_) : 0.0;
  have_time_ = true;
  last_t_s_ = t_s;

  Vec3 f = force_d;
  if (faults == 0 && !f.allFinite()) faults = kFaultNonFinite;  // from the renderer
  if (faults != 0) {
    *flags |= faults | kDeviceFault;
    if (!in_fault_) {
      in_fault_ = true;
      fault_since_s_ = t_s;
    }
    if (t_s - fault_since_s_ >= config_.fault_timeout_s) fault_timed_out_ = true;
    ramp_pending_ = true;
    f.setZero();
  } else {
    in_fault_ = false;
    if (ramp_pending_) {
      ramp_pending_ = false;
      ramp_start_s_ = t_s;
      ramp_from_ = last_sent_;  // zero after a fault
    }
    const double max_force = limits_.max_force_n;
    const double norm = f.norm();
    if (norm > max_force) {
      f *= max_force / norm;
      *flags |= kSafetyClamped;
    }
    // warm motors: the cap comes down to the continuous force over a ramp, not in one
    // tick (a hand pressing at 2.5 N would feel the part give way), and goes back up
    // the same way once they have cooled
    const double continuous = limits_.continuous_force_n;
    const bool warm = continuous > 0.0 && heat_n2_ > continuous * continuous;
    const double target = warm ? continuous : max_force;
    if (config_.ramp_s > 0.0) {
      const double slew = std::max(max_force - continuous, 0.0) * dt / config_.ramp_s;
      thermal_cap_n_ += std::clamp(target - thermal_cap_n_, -slew, slew);
    } else {
      thermal_cap_n_ = target;
    }
    const auto hold_to_cap = [&] {
      if (thermal_cap_n_ < max_force && f.norm() > thermal_cap_n_) {
        f *= thermal_cap_n_ / f.norm();
        *flags |= kThermalLimited;
      }
    };
    hold_to_cap();
    if (config_.ramp_s > 0.0) {
      const double ramp = (t_s - ramp_start_s_) / config_.ramp_s;
      if (ramp < 1.0) {
        // from the force last sent (zero at the start and after a fault) to this one
        f = ramp_from_ + std::max(0.0, ramp) * (f - ramp_from_);
        *flags |= kRamping;
        // both ends are within the maximum, so is the mix; the thermal cap holds
        hold_to_cap();
      }
    }
  }
  last_sent_ = f;
  // the motors heat with what was actually sent
  const double alpha = 1.0 - std::exp(-dt / config_.thermal_time_constant_s);
  heat_n2_ += alpha * (f.squaredNorm() - heat_n2_);
  return f;
}

double ForceSafety::thermal_force_n() const { return std::sqrt(heat_n2_); }

}  // namespace hapticad
