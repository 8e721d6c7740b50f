// SPDX-License-Identifier: GPL-3.0-or-later
// Firmware: the device side of the HaptiCAD HID protocol, written from
// devices/hid/PROTOCOL.md alone (its own byte packing: it shares no code with the host
// backend, so each checks the other). Used by the hidapi emulator; not thread-safe
// (the emulator serialises calls). Report I/O does not allocate.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>

#include "hapticad/devices/latency_histogram.h"
#include "hid_emulator.h"

namespace hapticad::hidemu {

class Firmware {
 public:
  // `plugged_at_s`: emulator time at which it is plugged in (its device time 0).
  Firmware(FirmwareConfig config, double plugged_at_s);
  Firmware(const Firmware&) = delete;
  Firmware& operator=(const Firmware&) = delete;

  const FirmwareConfig& config() const { return config_; }
  bool plugged() const { return plugged_; }
  void Unplug() { plugged_ = false; }
  void SetHandTarget(const Vec3& target_m);

  // Runs the device up to emulator time `now_s`.
  void AdvanceTo(double now_s);
  // The next queued input report whose delivery time has come: bytes copied (at most
  // `length`), 0 when none, -1 when unplugged.
  int ReadReport(double now_s, std::uint8_t* data, std::size_t length);
  // An output report written by the host at `now_s`: `length` or -1 when unplugged.
  int WriteReport(double now_s, const std::uint8_t* data, std::size_t length);
  // How long a host write begun at `now_s` blocks (kSlowWrite, kLateWrite); 0: it does
  // not. `*fails`: whether it then fails (times out). CountTimedOut() counts one that did.
  double WriteBlockS(double now_s, bool* fails) const;
  void CountTimedOut() { ++outputs_timed_out_; }
  // How long a host feature-report request begun at `now_s` blocks before it times out
  // (kSlowFeature; kSlowSession for the session report 0x04); 0: it does not.
  double FeatureBlockS(double now_s, std::uint8_t report_id) const;
  // Whether a host read at `now_s` is interrupted (kInterruptRead).
  bool ReadInterrupted(double now_s) const;
  // Feature reports (data[0] = report ID): bytes, or -1 for an unknown report.
  int GetFeature(std::uint8_t* data, std::size_t length);
  int SendFeature(const std::uint8_t* data, std::size_t length);

  Snapshot snapshot() const;

 private:
  struct Packet {
    double deliver_at_s = 0.0;
    std::size_t length = 0;
    std::array<std::uint8_t, 64> bytes{};
  };
  template <std::size_t N>
  struct Queue {  // fixed-capacity FIFO: no allocation
    std::array<Packet, N> items;
    std::size_t head = 0, size = 0;
    bool Push(const Packet& p) {
      if (size == N) return false;
      items[(head + size) % N] = p;
      ++size;
      return true;
    }
    Packet& Front() { return items[head]; }
    const Packet& Front() const { return items[head]; }
    void Pop() {
      head = (head + 1) % N;
      --size;
    }
  };

  bool Active(Fault fault, double t, double* param = nullptr) const;
  void Step(double t, double h);
  void ApplyOutput(const Packet& p);
  void SendInputReport(double t);
  void Deliver(const Packet& p);
  Vec3 HandTarget(double t, Vec3* velocity) const;
  Vec3 AppliedForce(double t) const;

  FirmwareConfig config_;
  double plugged_at_s_;
  bool plugged_ = true;
  std::mt19937 rng_;

  double time_s_ = 0.0;  // device time
  double next_report_s_ = 0.0;
  Vec3 position_ = Vec3::Zero();
  Vec3 velocity_ = Vec3::Zero();
  bool hand_override_ = false;
  Vec3 hand_target_ = Vec3::Zero();

  bool session_open_ = false;
  std::uint16_t version_ = 0;
  std::uint16_t watchdog_ms_ = 0;
  bool enabled_ = false;
  Vec3 commanded_ = Vec3::Zero();
  bool clamped_ = false;
  double last_command_s_ = -1e9;
  bool watchdog_was_tripped_ = false;
  bool have_output_sequence_ = false;
  std::uint16_t last_output_sequence_ = 0;

  std::uint16_t sequence_ = 0;
  std::array<double, 256> sent_at_s_{};  // by input sequence & 255
  std::array<std::uint16_t, 256> sent_sequence_{};
  std::uint16_t round_trip_us_ = 0;
  LatencyHistogram round_trip_;
  bool holding_ = false;  // reorder: a report held back to swap with the next
  Packet held_;
  double max_applied_ = 0.0;

  Queue<64> to_host_;     // hidraw keeps 64 reports; newer ones are dropped when full
  Queue<256> in_flight_;  // sent, not yet delivered (latency)
  Queue<256> from_host_;  // output reports on their way to the device

  std::uint64_t reports_generated_ = 0, reports_read_ = 0, outputs_received_ = 0,
                outputs_applied_ = 0, outputs_rejected_ = 0, outputs_timed_out_ = 0,
                watchdog_trips_ = 0;
};

}  // namespace hapticad::hidemu
