// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace hapticad::hidemu {
namespace {

constexpr double kPhysicsStep = 1e-4;  // s
// the emulator clock minus the plug-in time loses bits: 100.1 - 100.0 < 0.1
constexpr double kEpsilon = 1e-9;  // s

// PROTOCOL.md §2: little-endian
void Put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = v & 0xFF;
  p[1] = v >> 8;
}
void Put32(std::uint8_t* p, std::uint32_t v) {
  p[0] = v & 0xFF;
  p[1] = (v >> 8) & 0xFF;
  p[2] = (v >> 16) & 0xFF;
  p[3] = v >> 24;
}
std::uint16_t Get16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }
std::uint32_t Get32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// PROTOCOL.md §2: CRC-16/CCITT-FALSE, bit by bit as a small MCU would
std::uint16_t Crc(const std::uint8_t* p, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  while (n--) {
    crc ^= static_cast<std::uint16_t>(*p++) << 8;
    for (int i = 0; i < 8; ++i) crc = crc & 0x8000 ? (crc << 1) ^ 0x1021 : crc << 1;
  }
  return crc;
}

std::int32_t Nanometres(double m) {
  const double nm = std::round(m * 1e9);
  return static_cast<std::int32_t>(std::clamp(nm, -2147483648.0, 2147483647.0));
}
std::uint32_t Micro(double x) { return static_cast<std::uint32_t>(std::llround(x * 1e6)); }

}  // namespace

Firmware::Firmware(FirmwareConfig config, double plugged_at_s)
    : config_(std::move(config)), plugged_at_s_(plugged_at_s), rng_(config_.seed) {
  next_report_s_ = 0.0;
  Vec3 v;
  position_ = HandTarget(0.0, &v);
}

bool Firmware::Active(Fault fault, double t, double* param) const {
  for (const FaultWindow& w : config_.faults) {
    if (w.fault == fault && t + kEpsilon >= w.start_s && t + kEpsilon < w.end_s) {
      if (param) *param = w.param;
      return true;
    }
  }
  return false;
}

void Firmware::SetHandTarget(const Vec3& target_m) {
  hand_override_ = true;
  hand_target_ = target_m;
}

Vec3 Firmware::HandTarget(double t, Vec3* velocity) const {
  velocity->setZero();
  if (hand_override_) return hand_target_;
  const auto& ts = config_.hand_times_s;
  const auto& ps = config_.hand_positions_m;
  if (ts.empty()) return Vec3::Zero();
  if (t <= ts.front()) return ps.front();
  if (t >= ts.back()) return ps.back();
  const std::size_t i = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin() - 1;
  *velocity = (ps[i + 1] - ps[i]) / (ts[i + 1] - ts[i]);
  return ps[i] + (t - ts[i]) * *velocity;
}

Vec3 Firmware::AppliedForce(double t) const {
  if (!session_open_ || !enabled_ || Active(Fault::kDeviceFault, t)) return Vec3::Zero();
  const std::uint16_t watchdog = watchdog_ms_ ? watchdog_ms_ : config_.watchdog_ms;
  if ((t - last_command_s_) * 1000.0 > watchdog) return Vec3::Zero();
  Vec3 f = commanded_;
  if (f.norm() > config_.max_force_n) f *= config_.max_force_n / f.norm();
  return f;
}

void Firmware::AdvanceTo(double now_s) {
  const double target = now_s - plugged_at_s_;
  const double period = 1.0 / config_.report_rate_hz;
  while (plugged_) {
    if (Active(Fault::kUnplug, time_s_)) {
      plugged_ = false;
      break;
    }
    if (next_report_s_ <= time_s_ + kEpsilon) {  // a report is due now
      SendInputReport(next_report_s_);
      next_report_s_ = std::round(next_report_s_ / period + 1.0) * period;
    }
    while (in_flight_.size > 0 && in_flight_.Front().deliver_at_s <= time_s_ + kEpsilon) {
      Deliver(in_flight_.Front());
      in_flight_.Pop();
    }
    if (time_s_ >= target - kEpsilon) break;
    const double t_next = std::min({target, next_report_s_, time_s_ + kPhysicsStep});
    if (Active(Fault::kUnplug, t_next)) {
      plugged_ = false;
      break;
    }
    Step(t_next, t_next - time_s_);
    time_s_ = t_next;
  }
}

void Firmware::Deliver(const Packet& p) {
  to_host_.Push(p);  // a full hidraw queue drops the newest report
}

void Firmware::Step(double t_end, double h) {
  while (from_host_.size > 0 && from_host_.Front().deliver_at_s <= t_end + kEpsilon) {
    ApplyOutput(from_host_.Front());
    from_host_.Pop();
  }
  const bool tripped =
      session_open_ && enabled_ &&
      (t_end - last_command_s_) * 1000.0 > (watchdog_ms_ ? watchdog_ms_ : config_.watchdog_ms);
  if (tripped && !watchdog_was_tripped_) ++watchdog_trips_;
  watchdog_was_tripped_ = tripped;
  if (h <= 0.0) return;
  const Vec3 force = AppliedForce(time_s_);
  max_applied_ = std::max(max_applied_, force.norm());
  Vec3 target_velocity;
  const Vec3 target = HandTarget(time_s_, &target_velocity);
  const Vec3 hand = config_.hand_stiffness_n_per_m * (target - position_) +
                    config_.hand_damping_n_s_per_m * (target_velocity - velocity_);
  const Vec3 accel = (force + hand - config_.damping_n_s_per_m * velocity_) / config_.mass_kg;
  velocity_ += h * accel;
  position_ += h * velocity_;
  for (int a = 0; a < 3; ++a) {  // end stops
    if (position_[a] < config_.workspace_min_m[a]) {
      position_[a] = config_.workspace_min_m[a];
      velocity_[a] = std::max(0.0, velocity_[a]);
    } else if (position_[a] > config_.workspace_max_m[a]) {
      position_[a] = config_.workspace_max_m[a];
      velocity_[a] = std::min(0.0, velocity_[a]);
    }
  }
}

void Firmware::ApplyOutput(const Packet& p) {
  const std::uint8_t* d = p.bytes.data();
  if (p.length != 20 || d[0] != 0x02 || Crc(d, 18) != Get16(d + 18)) {
    ++outputs_rejected_;
    return;
  }
  const std::uint16_t sequence = Get16(d + 2);
  if (have_output_sequence_ && static_cast<std::int16_t>(sequence - last_output_sequence_) <= 0) {
    ++outputs_rejected_;  // late or repeated: never override a newer command
    return;
  }
  have_output_sequence_ = true;
  last_output_sequence_ = sequence;
  ++outputs_applied_;
  enabled_ = (d[1] & 1) != 0;
  for (int a = 0; a < 3; ++a) {
    commanded_[a] = static_cast<std::int32_t>(Get32(d + 6 + 4 * a)) * 1e-6;
  }
  clamped_ = commanded_.norm() > config_.max_force_n;
  last_command_s_ = p.deliver_at_s;
  const std::uint16_t answered = Get16(d + 4);
  if (sent_sequence_[answered & 255] == answered) {
    const double rtt = p.deliver_at_s - sent_at_s_[answered & 255];
    round_trip_.Record(std::llround(rtt * 1e9));
    round_trip_us_ = static_cast<std::uint16_t>(std::clamp<long>(std::lround(rtt * 1e6), 1, 65535));
  }
}

void Firmware::SendInputReport(double t) {
  if (Active(Fault::kStall, t)) return;
  ++sequence_;
  ++reports_generated_;
  std::uint8_t status = 0;
  const bool faulty = Active(Fault::kDeviceFault, t);
  if (AppliedForce(t) != Vec3::Zero() ||
      (session_open_ && enabled_ && !watchdog_was_tripped_ && !faulty)) {
    status |= 1;
  }
  if (watchdog_was_tripped_) status |= 2;
  if (faulty) status |= 4;
  if (Active(Fault::kNotHomed, t)) status |= 8;
  if (clamped_) status |= 16;

  double device_time = t;
  for (const FaultWindow& w : config_.faults) {
    if (w.fault == Fault::kFreezeClock && Active(Fault::kFreezeClock, t) &&
        t + kEpsilon >= w.start_s && t + kEpsilon < w.end_s) {
      device_time = w.start_s;
    }
  }
  const double step = config_.position_resolution_m;
  Vec3 reported = position_;
  if (step > 0) reported = (reported / step).array().round().matrix() * step;

  Packet p;
  std::uint8_t* d = p.bytes.data();
  d[0] = 0x01;
  d[1] = status;
  Put16(d + 2, sequence_);
  Put32(d + 4, static_cast<std::uint32_t>(std::llround(device_time * 1e6)));
  for (int a = 0; a < 3; ++a) {
    std::int32_t nm = Nanometres(reported[a]);
    if (Active(Fault::kExtreme, t))
      nm = a == 1 ? std::numeric_limits<std::int32_t>::min()
                  : std::numeric_limits<std::int32_t>::max();
    Put32(d + 8 + 4 * a, static_cast<std::uint32_t>(nm));
  }
  Put32(d + 20, 0);  // buttons
  Put16(d + 24, round_trip_us_);
  Put16(d + 26, Active(Fault::kZeroEcho, t) ? 0 : last_output_sequence_);
  Put16(d + 30, Crc(d, 30));
  p.length = 32;
  sent_at_s_[sequence_ & 255] = t;
  sent_sequence_[sequence_ & 255] = sequence_;

  double param = 0.0;
  p.deliver_at_s = t + config_.transport_latency_s;
  if (Active(Fault::kLate, t, &param)) p.deliver_at_s += param;
  if (Active(Fault::kTruncate, t, &param)) p.length = static_cast<std::size_t>(param);
  if (Active(Fault::kGarbage, t)) {
    std::uniform_int_distribution<int> byte(0, 255);
    for (auto& b : p.bytes) b = static_cast<std::uint8_t>(byte(rng_));
    if (byte(rng_) < 128) {
      d[0] = 0x01;  // a believable ID and length: only the CRC can tell
      p.length = 32;
    } else {
      p.length = 1 + static_cast<std::size_t>(byte(rng_)) % 64;
    }
  }
  if (Active(Fault::kDrop, t, &param) &&
      std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < param) {
    return;  // lost on the way
  }
  if (Active(Fault::kReorder, t)) {
    if (!holding_) {
      holding_ = true;
      held_ = p;
      return;
    }
    holding_ = false;
    in_flight_.Push(p);
    in_flight_.Push(held_);
    return;
  }
  if (holding_) {  // the window closed with a report held back
    holding_ = false;
    in_flight_.Push(held_);
  }
  in_flight_.Push(p);
  if (Active(Fault::kDuplicate, t)) in_flight_.Push(p);
}

int Firmware::ReadReport(double, std::uint8_t* data, std::size_t length) {
  if (!plugged_) return -1;
  if (to_host_.size == 0) return 0;
  const Packet& p = to_host_.Front();
  const std::size_t n = std::min(length, p.length);
  std::memcpy(data, p.bytes.data(), n);
  to_host_.Pop();
  ++reports_read_;
  return static_cast<int>(n);
}

int Firmware::WriteReport(double now_s, const std::uint8_t* data, std::size_t length) {
  if (!plugged_) return -1;
  ++outputs_received_;
  const double t = now_s - plugged_at_s_;
  if (Active(Fault::kDropOutput, t)) return static_cast<int>(length);
  Packet p;
  p.deliver_at_s = t + config_.transport_latency_s;
  p.length = std::min<std::size_t>(length, p.bytes.size());
  std::memcpy(p.bytes.data(), data, p.length);
  from_host_.Push(p);
  return static_cast<int>(length);
}

double Firmware::WriteBlockS(double now_s, bool* fails) const {
  double param = 0.0;
  *fails = false;
  if (!plugged_) return 0.0;
  if (Active(Fault::kSlowWrite, now_s - plugged_at_s_, &param)) {
    *fails = true;
    return param;
  }
  if (Active(Fault::kLateWrite, now_s - plugged_at_s_, &param)) return param;
  return 0.0;
}

double Firmware::FeatureBlockS(double now_s, std::uint8_t report_id) const {
  double param = 0.0;
  if (!plugged_) return 0.0;
  const double t = now_s - plugged_at_s_;
  if (Active(Fault::kSlowFeature, t, &param)) return param;
  if (report_id == 0x04 && Active(Fault::kSlowSession, t, &param)) return param;
  return 0.0;
}

bool Firmware::ReadInterrupted(double now_s) const {
  return plugged_ && Active(Fault::kInterruptRead, now_s - plugged_at_s_);
}

int Firmware::GetFeature(std::uint8_t* data, std::size_t length) {
  std::uint8_t d[64] = {};
  std::size_t n = 0;
  if (data[0] == 0x03) {  // PROTOCOL.md §3.3
    d[0] = 0x03;
    d[1] = config_.dof;
    Put16(d + 2, config_.magic);
    Put16(d + 4, config_.version_min);
    Put16(d + 6, config_.version_max);
    Put16(d + 8, config_.watchdog_ms);
    Put16(d + 10, config_.report_rate_hz);
    Put32(d + 12, Micro(config_.max_force_n));
    Put32(d + 16, Micro(config_.continuous_force_n));
    Put32(d + 20, static_cast<std::uint32_t>(std::llround(config_.max_stiffness_n_per_m)));
    Put32(d + 24, static_cast<std::uint32_t>(std::llround(config_.max_damping_n_s_per_m * 1e3)));
    for (int a = 0; a < 3; ++a) {
      Put32(d + 28 + 4 * a, static_cast<std::uint32_t>(Nanometres(config_.workspace_min_m[a])));
      Put32(d + 40 + 4 * a, static_cast<std::uint32_t>(Nanometres(config_.workspace_max_m[a])));
    }
    Put32(d + 52, static_cast<std::uint32_t>(std::llround(config_.position_resolution_m * 1e9)));
    n = 64;
  } else if (data[0] == 0x04) {  // §3.4
    d[0] = 0x04;
    d[1] = session_open_ ? 1 : 0;
    Put16(d + 2, version_);
    Put16(d + 4, watchdog_ms_);
    n = 8;
  } else {
    return -1;
  }
  n = std::min(n, length);
  std::memcpy(data, d, n);
  return static_cast<int>(n);
}

int Firmware::SendFeature(const std::uint8_t* data, std::size_t length) {
  if (data[0] != 0x04 || length < 8) return -1;
  const std::uint16_t version = Get16(data + 2);
  if (version >= config_.version_min && version <= config_.version_max &&
      !config_.refuse_sessions) {
    session_open_ = (data[1] & 1) != 0;
    version_ = version;
    watchdog_ms_ = config_.fixed_watchdog_ms ? config_.fixed_watchdog_ms : Get16(data + 4);
  } else {
    session_open_ = false;
    version_ = 0;
  }
  if (!session_open_) {
    enabled_ = false;
    commanded_.setZero();
  }
  return static_cast<int>(length);
}

Snapshot Firmware::snapshot() const {
  Snapshot s;
  s.plugged = plugged_;
  s.session_open = session_open_;
  s.version = version_;
  s.time_s = time_s_;
  s.position_m = position_;
  s.velocity_m = velocity_;
  s.commanded_force_n = commanded_;
  s.applied_force_n = AppliedForce(time_s_);
  s.max_applied_force_n = max_applied_;
  s.watchdog_tripped = watchdog_was_tripped_;
  s.watchdog_trips = watchdog_trips_;
  s.reports_generated = reports_generated_;
  s.reports_read = reports_read_;
  s.outputs_received = outputs_received_;
  s.outputs_applied = outputs_applied_;
  s.outputs_rejected = outputs_rejected_;
  s.outputs_timed_out = outputs_timed_out_;
  s.round_trips = round_trip_.count();
  s.round_trip_last_s = round_trip_us_ * 1e-6;
  s.round_trip_p50_s = round_trip_.Percentile(0.5) * 1e-9;
  s.round_trip_p99_s = round_trip_.Percentile(0.99) * 1e-9;
  s.round_trip_max_s = round_trip_.max_ns() * 1e-9;
  return s;
}

}  // namespace hapticad::hidemu
