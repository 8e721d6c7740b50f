// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ReadState and WriteForce run on the servo tick.
#include "hapticad/devices/simulated_hand.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {
namespace {

// enough readings for 0.5 s of latency at 10 kHz, with room to spare
constexpr std::size_t kHistory = 8192;

void Require(bool ok, const char* field, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("hand model: ") + field + " = " +
                                std::to_string(value) + " is out of range");
  }
}

}  // namespace

void ValidateHandModel(const HandModel& m) {
  auto finite = [](double x) { return std::isfinite(x); };
  Require(finite(m.mass_kg) && m.mass_kg > 0.0, "mass_kg", m.mass_kg);
  Require(finite(m.damping_n_s_per_m) && m.damping_n_s_per_m >= 0.0, "damping_n_s_per_m",
          m.damping_n_s_per_m);
  Require(finite(m.grip_stiffness_n_per_m) && m.grip_stiffness_n_per_m >= 0.0,
          "grip_stiffness_n_per_m", m.grip_stiffness_n_per_m);
  Require(finite(m.grip_damping_n_s_per_m) && m.grip_damping_n_s_per_m >= 0.0,
          "grip_damping_n_s_per_m", m.grip_damping_n_s_per_m);
  Require(finite(m.max_grip_force_n) && m.max_grip_force_n > 0.0, "max_grip_force_n",
          m.max_grip_force_n);
  Require(finite(m.latency_s) && m.latency_s >= 0.0 && m.latency_s <= 0.5, "latency_s",
          m.latency_s);
  Require(finite(m.velocity_cutoff_hz) && m.velocity_cutoff_hz > 0.0, "velocity_cutoff_hz",
          m.velocity_cutoff_hz);
  Require(finite(m.watchdog_s) && m.watchdog_s > 0.0, "watchdog_s", m.watchdog_s);
  Require(finite(m.step_s) && m.step_s >= 1e-6 && m.step_s <= 1e-3, "step_s", m.step_s);
}

DeviceLimits SimulatedHandLimits() {
  DeviceLimits limits = SimulatedProbeLimits();
  limits.position_resolution_m = 0.055e-3;
  return limits;
}

SimulatedHand::SimulatedHand(DeviceLimits limits, HandModel model)
    : model_(model), velocity_filter_(model.velocity_cutoff_hz) {
  ValidateDeviceLimits(limits);
  ValidateHandModel(model);
  info_.kind = "sim";
  info_.name = "Simulated hand";
  info_.path = "sim:hand";
  info_.limits = limits;
  history_.resize(kHistory);
  target_.Write(0.5 * (limits.workspace_min_d + limits.workspace_max_d));
}

void SimulatedHand::SetTarget(const Vec3& target_d) {
  if (!target_d.allFinite()) throw std::invalid_argument("simulated hand: target is not finite");
  target_.Write(target_d);
}

void SimulatedHand::FollowPath(ScriptedPath path) {
  if (in_session())
    throw std::logic_error("simulated hand: cannot change the path during a session");
  path.Validate();
  path_ = std::move(path);
  cursor_ = PathCursor(&path_);
}

void SimulatedHand::FollowTarget() {
  if (in_session())
    throw std::logic_error("simulated hand: cannot change the path during a session");
  path_ = ScriptedPath{};
  cursor_ = PathCursor(&path_);
}

void SimulatedHand::BeginSession() {
  in_session_.store(true, std::memory_order_release);
  started_ = false;
  history_size_ = 0;
  history_head_ = 0;
  velocity_filter_.Reset();
  last_reported_time_s_ = -1.0;
  force_d_.setZero();
}

void SimulatedHand::EndSession() {
  force_d_.setZero();
  in_session_.store(false, std::memory_order_release);
}

void SimulatedHand::WriteForce(const Vec3& force_d) {
  // a real device's firmware would refuse non-finite commands too
  force_d_ = force_d.allFinite() ? force_d : Vec3::Zero();
  force_time_s_ = time_s_;
}

Vec3 SimulatedHand::Clamp(const Vec3& p) const {
  return p.cwiseMax(info_.limits.workspace_min_d).cwiseMin(info_.limits.workspace_max_d);
}

Vec3 SimulatedHand::Quantise(const Vec3& p) const {
  const double step = info_.limits.position_resolution_m;
  if (step <= 0.0) return p;
  return (p / step).array().round().matrix() * step;
}

void SimulatedHand::Integrate(double t) {
  const double span = t - time_s_;
  if (!(span > 0.0)) return;
  const auto steps =
      std::min<long>(100000, std::max<long>(1, std::lround(std::ceil(span / model_.step_s))));
  const double h = span / static_cast<double>(steps);
  const Vec3& wmin = info_.limits.workspace_min_d;
  const Vec3& wmax = info_.limits.workspace_max_d;
  for (long i = 0; i < steps; ++i) {
    const double ts = time_s_ + static_cast<double>(i) * h;
    if (following_path()) {
      const PathSample s = cursor_.Sample(ts);
      target_d_ = s.position;
      target_velocity_d_ = s.velocity;
    }
    Vec3 grip = model_.grip_stiffness_n_per_m * (target_d_ - position_d_) +
                model_.grip_damping_n_s_per_m * (target_velocity_d_ - velocity_d_);
    const double grip_norm = grip.norm();
    if (grip_norm > model_.max_grip_force_n) grip *= model_.max_grip_force_n / grip_norm;
    // the device-side watchdog: no command for too long, no force
    const Vec3 command = ts - force_time_s_ <= model_.watchdog_s ? force_d_ : Vec3::Zero();
    const Vec3 accel = (command + grip - model_.damping_n_s_per_m * velocity_d_) / model_.mass_kg;
    velocity_d_ += h * accel;
    position_d_ += h * velocity_d_;
    for (int a = 0; a < 3; ++a) {  // the mechanism's end stops
      if (position_d_[a] < wmin[a]) {
        position_d_[a] = wmin[a];
        velocity_d_[a] = std::max(0.0, velocity_d_[a]);
      } else if (position_d_[a] > wmax[a]) {
        position_d_[a] = wmax[a];
        velocity_d_[a] = std::min(0.0, velocity_d_[a]);
      }
    }
  }
  time_s_ = t;
}

ReadStatus SimulatedHand::ReadState(double t, DeviceState* state) {
  if (!following_path()) {
    target_d_ = target_.Read();
    target_velocity_d_.setZero();
  }
  if (!started_) {
    started_ = true;
    time_s_ = t;
    force_time_s_ = t;
    if (following_path()) {
      const PathSample s = cursor_.Sample(t);
      target_d_ = s.position;
      target_velocity_d_ = s.velocity;
    }
    position_d_ = Clamp(target_d_);
    velocity_d_.setZero();
  } else {
    Integrate(t);
  }

  // record this reading, report the one `latency_s` old (or the oldest kept)
  history_[history_head_] = Reading{t, Quantise(position_d_)};
  history_head_ = (history_head_ + 1) % kHistory;
  history_size_ = std::min(history_size_ + 1, kHistory);
  const double wanted = t - model_.latency_s;
  std::size_t back = 0;  // 0 = newest
  while (back + 1 < history_size_ &&
         history_[(history_head_ + kHistory - 1 - back) % kHistory].time_s > wanted + 1e-12) {
    ++back;
  }
  const Reading& reading = history_[(history_head_ + kHistory - 1 - back) % kHistory];
  if (reading.time_s != last_reported_time_s_) {
    velocity_filter_.Update(reading.time_s, reading.position_d);
    last_reported_time_s_ = reading.time_s;
  }

  state->time_s = reading.time_s;
  state->position_d = reading.position_d;
  state->velocity_d = velocity_filter_.velocity();
  state->buttons = 0;
  state->age_s = 0.0;

  HandState published;
  published.time_s = t;
  published.position_d = position_d_;
  published.velocity_d = velocity_d_;
  published.target_d = target_d_;
  published.force_d = t - force_time_s_ <= model_.watchdog_s ? force_d_ : Vec3::Zero();
  published_.Write(published);
  return ReadStatus::kOk;
}

}  // namespace hapticad
