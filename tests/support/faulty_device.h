// SPDX-License-Identifier: GPL-3.0-or-later
// FaultyDevice: wraps a real Device and corrupts what it reports inside time windows
// (NaN or Inf positions, impossible positions, stale data, a chosen ReadStatus), for
// the servo loop's safety tests where no backend can produce the fault itself (HID
// reports are fixed-point and cannot carry a NaN; the HID emulator covers the rest).
// Servo-tick safe: no allocation.
#pragma once

#include <limits>

#include "hapticad/devices/device.h"

namespace hapticad::testing {

class FaultyDevice final : public Device {
 public:
  enum class Fault { kNone, kNaN, kInf, kFarAway, kTooFast, kStale, kStatus };

  explicit FaultyDevice(Device* inner) : inner_(inner) {}

  // Inject `fault` for loop times in [start_s, end_s); kStatus reports `status`.
  void Inject(Fault fault, double start_s, double end_s, ReadStatus status = ReadStatus::kOk) {
    fault_ = fault;
    start_s_ = start_s;
    end_s_ = end_s;
    status_ = status;
  }

  // Buttons reported with every reading from now on.
  void SetButtons(std::uint32_t buttons) { buttons_ = buttons; }

  const DeviceInfo& info() const override { return inner_->info(); }
  void BeginSession() override { inner_->BeginSession(); }
  void EndSession() override { inner_->EndSession(); }
  bool runs_on_loop_time() const override { return inner_->runs_on_loop_time(); }
  void WriteForce(const Vec3& f) override {
    last_force_d_ = f;
    inner_->WriteForce(f);
  }
  ReadStatus ReadState(double t, DeviceState* s) override {
    const ReadStatus status = inner_->ReadState(t, s);
    s->buttons |= buttons_;
    if (t < start_s_ - 1e-9 || t >= end_s_ - 1e-9) return status;  // loop times are k * T
    const double nan = std::numeric_limits<double>::quiet_NaN();
    switch (fault_) {
      case Fault::kNone:
        break;
      case Fault::kNaN:
        s->position_d.y() = nan;
        break;
      case Fault::kInf:
        s->velocity_d.x() = std::numeric_limits<double>::infinity();
        break;
      case Fault::kFarAway:
        s->position_d.z() = 5.0;  // 5 m: no desktop device reaches that
        break;
      case Fault::kTooFast:
        s->velocity_d.x() = 50.0;
        break;
      case Fault::kStale:
        s->age_s = 0.05;
        break;
      case Fault::kStatus:
        return status_;
    }
    return status;
  }
  std::string DescribeFault() const override { return "injected by the test"; }

  const Vec3& last_force_d() const { return last_force_d_; }

 private:
  Device* inner_;
  Fault fault_ = Fault::kNone;
  double start_s_ = 0.0;
  double end_s_ = 0.0;
  ReadStatus status_ = ReadStatus::kOk;
  std::uint32_t buttons_ = 0;
  Vec3 last_force_d_ = Vec3::Zero();
};

}  // namespace hapticad::testing
