// SPDX-License-Identifier: GPL-3.0-or-later
// HidDevice: a haptic device speaking the HaptiCAD HID protocol (PROTOCOL.md) through
// hidapi. Open() reads the device's information, negotiates the protocol version (of
// major 1 in the device's range, nearest 1.0) and checks its limits; a session enables forces;
// every tick ReadState() drains the input reports queued since the last tick (keeping the newest
// valid one) and WriteForce() hands one output report to the device's writer thread
// (HidOutputWriter, on a second hidapi handle of its own), which writes it: the tick never
// waits on USB, where a write can block for up to 5 s.
//
// Per report it rejects a wrong ID, length or CRC (truncated, garbage), a sequence
// that is not newer (duplicated, reordered), a device time that does not advance
// (frozen), and counts sequence gaps (dropped). After a gap of 16384 reports or more
// by the device's clock (a host stall) the 16-bit sequence may have wrapped past half:
// the device time decides, and the first report after the gap is used. Positions outside the stated
// workspace grown by 25 %, a FAULT, NOT_HOMED or WATCHDOG status give kOutOfRange or
// kDeviceFault (after a device watchdog trip the force must ramp in, not jump back), and never
// reach the velocity filter.
//
// A fault reported between two ticks (FAULT, NOT_HOMED or WATCHDOG in a report followed by
// clean ones before the tick reads them) makes that tick kDeviceFault: the device's force
// was zero meanwhile, so it ramps in again; the newest report's position is kept.
//
// Sequences. The device applies a command only if its sequence is newer than the last it
// applied, and that may be another session's (the device stayed plugged in between two
// sessions, each with a HidDevice of its own): BeginSession() goes on from the sequence the
// device echoes as applied (input report offset 26). Commands written for
// kCommandsIgnoredS with none echoed as applied are ignored by the device: kDeviceFault
// (zero force; a ramp-in once one gets through) and DescribeFault() says so.
//
// Commands that do not get through. When a force command has waited longer than the
// watchdog the device took (the session's watchdog_ms, or shorter; the device's default for 0)
// without the writer finishing a write, the device has dropped the force by itself: ReadState()
// says kDeviceFault (zero force, and a ramp-in once commands flow again). When one has
// waited kCommandTimeoutS, the device is lost: kUnplugged from then on, and
// DescribeFault() says that it stopped taking force commands. A failed read, or three
// failed writes in a row, is an unplug too. An interrupted read (EINTR: a signal reached
// the servo thread during hidapi's poll) is "no data this tick", not an unplug: hidapi
// reports a real unplug as POLLHUP/POLLERR or a failed read, which are not EINTR.
// DescribeFault() gives hidapi's reason (taken on the thread that saw it: DescribeFault()
// never calls hidapi, whose error text is not thread-safe).
//
// Ending. EndSession() hands the close (zero force with ENABLE = 0, SESSION = 0) to the
// writer and waits for it, kEndSessionWaitS of a writer stuck in the kernel (the writer's
// bounded waits: hid_output_writer.h), which sends it when its write returns. The
// destructor waits HidOutputWriter::kAbandonAfterS more for a stuck writer, then leaves it
// to finish and close its handle on its own.
//
// Age: time since the last fresh report, plus how much later than usual that report
// arrived (its delay over the smallest recent delay, comparing the device's clock with
// the host's monotonic clock at receipt; the smallest delay is allowed to creep up
// 1 ms per s so clock drift is not mistaken for lateness). A stall and late reports
// both show as age. The host clock is read here, not taken from the loop's scheduled
// tick time: a tick that runs late would otherwise make a report look early and every
// later one stale.
//
// Units: SI (device frame); velocity is filtered from positions on the device's own
// clock. ReadState()/WriteForce() are servo-tick safe: no allocation, no lock; their
// only system calls are hidapi's reads (hidraw's poll and read). hidapi itself (0.13, Debian
// 12's) allocates the error text of a read that fails or is interrupted (a signal): a tick
// allocates only at an unplug, which ends the session, or at an EINTR (the emulator, through
// which the tick's allocations are counted, allocates nothing). The statistics and
// DescribeFault() may be read from any thread. BeginSession() and EndSession() wait
// kEndSessionWaitS for a writer stuck in the kernel; BeginSession() sends its session
// request through the writer and waits kBeginSessionWaitS for the answer (bounded waits
// as hid_output_writer.h says: a writer thread only slow to be scheduled is waited for).
// Open() still asks on the calling thread, which a device that does not answer blocks for
// up to 5 s an exchange: the workbench opens devices on a worker thread (plugin
// .../device_opening.py), and ListDevices() waits for Probe() at most kProbeWaitS. Open()
// and Probe() may run on several threads at once: their calls into hidapi's global state
// (hid_open_path, and its error text after a failed open) take turns under one
// process-wide lock, which nothing that waits on a device holds.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "hapticad/devices/device.h"
#include "hapticad/devices/hid/hid_output_writer.h"
#include "hapticad/devices/hid/hid_protocol.h"
#include "hapticad/devices/latency_histogram.h"
#include "hapticad/devices/velocity_filter.h"

struct hid_device_;

namespace hapticad {

struct HidLinkStats {
  std::uint64_t reports_read = 0;      // every report hidapi returned
  std::uint64_t reports_used = 0;      // valid and newer: they became the state
  std::uint64_t malformed = 0;         // wrong ID, length or CRC
  std::uint64_t not_newer = 0;         // sequence or device time not newer
  std::uint64_t dropped = 0;           // sequence numbers skipped
  std::uint64_t out_of_range = 0;      // positions outside the workspace (+25 %)
  std::uint64_t device_faults = 0;     // reports with FAULT, NOT_HOMED or WATCHDOG (not used)
  std::uint64_t watchdog_reports = 0;  // of those, the ones saying the device watchdog tripped
  std::uint64_t writes = 0;
  std::uint64_t writes_failed = 0;
  // the writer thread (hid_output_writer.h: writes counts its hid_write() calls), and reads
  std::uint64_t writes_superseded = 0;       // commands replaced by a newer one before written
  std::uint64_t commands_late_ticks = 0;     // ticks a command had waited over the watchdog
  std::uint64_t commands_ignored_ticks = 0;  // ticks after kCommandsIgnoredS with none applied
  double write_max_us = 0.0;                 // the longest a hid_write() took
  std::uint64_t reads_interrupted = 0;       // reads that returned EINTR: no data that tick
  // round trip as measured by the device (input sent -> answering output received)
  double round_trip_last_us = 0.0;
  double round_trip_p50_us = 0.0;
  double round_trip_p99_us = 0.0;
  std::uint64_t round_trip_count = 0;
};

// What Probe() learns without opening a session (it changes nothing on the device).
struct HidProbe {
  DeviceInfo info;
  hid::InfoReport report;
};

class HidDevice final : public Device {
 public:
  // A force command waiting this long for the USB stack (the writer's hid_write has not
  // returned) means the device stopped taking commands: it is lost, as if unplugged.
  static constexpr double kCommandTimeoutS = 0.25;
  // Commands written this long in a session without the device echoing one of them as
  // applied (input report offset 26): it ignores them, zero force (ReadState says
  // kDeviceFault) until one gets through. Dozens of commands and reports at any rate the
  // protocol allows.
  static constexpr double kCommandsIgnoredS = 0.05;
  // How long BeginSession() waits for an input report, to go on from the last command the
  // device applied (its report period is 2.5 ms at most).
  static constexpr int kEchoWaitMs = 50;
  // How long EndSession() and BeginSession() wait for a writer stuck in the kernel.
  static constexpr double kEndSessionWaitS = 0.1;
  // How long BeginSession() waits for the device to answer its session request (a
  // feature-report exchange: milliseconds when the device answers).
  static constexpr double kBeginSessionWaitS = 1.0;

  // Reads the device information at `path` without touching any session (for
  // listings). Throws DeviceError with a sentence for the user: cannot open
  // (permissions: install the udev rule), not a HaptiCAD device, wrong protocol
  // version, impossible limits.
  static HidProbe Probe(const std::string& path);

  // Opens `path`, checks it as Probe() does and negotiates protocol 1.x (1.0, or the
  // lowest 1.x the device speaks if it does not speak 1.0) with the device watchdog `watchdog_ms`
  // (0: the device's default). The default, 5 ms, makes the device itself drop the force when the
  // servo loop misses more than 5 ms, even if the loop never runs again. A device that takes
  // a longer watchdog than asked (or, asked for 0, answers longer than its stated default)
  // is refused, at Open and at BeginSession: it would go on pushing that long after the
  // host stops. A session exchange that fails on USB says so, apart from a firmware that
  // answers wrongly. Throws DeviceError.
  static std::unique_ptr<HidDevice> Open(const std::string& path, int watchdog_ms = 5);

  ~HidDevice() override;
  HidDevice(const HidDevice&) = delete;
  HidDevice& operator=(const HidDevice&) = delete;

  const DeviceInfo& info() const override { return info_; }
  // Throws DeviceError if unplugged or refused, or if the writer is still stuck in a write
  // of the last session after kEndSessionWaitS.
  void BeginSession() override;
  ReadStatus ReadState(double loop_time_s, DeviceState* state) override;
  void WriteForce(const Vec3& force_d) override;
  void EndSession() override;
  std::string DescribeFault() const override;
  bool stopped_answering() const override {
    return unplugged() && lost_.load(std::memory_order_acquire) == Lost::kCommandsStuck;
  }

  // The link statistics so far: reads the counters and computes two percentiles from the
  // round-trip histogram (up to two scans of its 1184 bins each).
  HidLinkStats CalcLinkStats() const;

  // The host clock, s (CLOCK_MONOTONIC by default; the tests give the emulator's).
  using Clock = double (*)();
  void set_clock(Clock clock) { clock_ = clock; }
  static double MonotonicSeconds();
  // Control thread, for callers that step ReadState()/WriteForce() by hand (tests, tools)
  // and need every force command given so far written before they go on: waits for the
  // writer at most `wait_s`; true if it is done. Does not allocate.
  bool WaitUntilWritten(double wait_s = 1.0) { return writer_->WaitUntilWritten(wait_s); }
  const hid::InfoReport& device_report() const { return report_; }
  // The version negotiated: of major 1, in the device's range, nearest 1.0.
  std::uint16_t protocol_version() const { return version_; }
  bool unplugged() const { return unplugged_.load(std::memory_order_acquire); }

 private:
  // How the device was lost (DescribeFault words it).
  enum class Lost : std::uint8_t { kNo, kRead, kWrite, kCommandsStuck };

  HidDevice(hid_device_* handle, HidProbe probe);
  void Count(std::atomic<std::uint64_t>& counter, std::uint64_t n = 1);
  // Servo thread: the device is gone for `how`, hidapi's `reason` (may be null).
  void MarkLost(Lost how, const wchar_t* reason);

  hid_device_* handle_;  // the servo thread's reads (and the control thread's features)
  std::unique_ptr<HidOutputWriter> writer_;  // writes, on a handle of its own
  double command_stall_s_ = 0.005;           // the watchdog the device took
  DeviceInfo info_;
  hid::InfoReport report_;
  std::uint16_t version_;  // asked for and accepted
  int watchdog_ms_ = 5;
  Clock clock_ = &HidDevice::MonotonicSeconds;
  Vec3 allowed_min_d_;
  Vec3 allowed_max_d_;

  // servo thread's
  bool session_open_ = false;
  bool have_report_ = false;
  std::uint16_t last_sequence_ = 0;
  std::uint32_t last_device_time_us_ = 0;
  double device_time_s_ = 0.0;  // unwrapped
  bool have_good_ = false;
  double last_fresh_s_ = 0.0;   // host clock
  double fresh_delay_s_ = 0.0;  // how late the last fresh report was
  double min_offset_s_ = 0.0;   // smallest recent (host clock at receipt - device time)
  double min_offset_time_s_ = 0.0;
  ReadStatus verdict_ = ReadStatus::kNoData;
  Vec3 position_d_ = Vec3::Zero();
  std::uint32_t buttons_ = 0;
  std::atomic<std::uint8_t> last_status_{0};  // of the newest report used; DescribeFault reads it
  VelocityFilter velocity_filter_{40.0};
  std::uint16_t output_sequence_ = 0;  // the last sent; a session goes on from the device's echo
  std::uint16_t first_posted_ = 0;     // this session's first command's sequence
  bool posted_ = false;                // a command of this session was handed to the writer
  double first_post_s_ = 0.0;          // host clock then
  bool echo_applied_ = false;          // the device echoed one of this session's commands
  double echo_read_s_ = 0.0;           // host clock when the newest report was read
  double last_now_s_ = 0.0;            // host clock at the last ReadState() (or BeginSession())
  std::uint8_t buffer_[64] = {};

  // hidapi's reason, taken on the servo thread before unplugged_ turns true (hid_error is
  // not thread-safe; DescribeFault reads this instead)
  static constexpr int kReasonLength = 160;
  wchar_t unplug_reason_[kReasonLength] = {};
  std::atomic<Lost> lost_{Lost::kNo};         // written before unplugged_
  std::atomic<double> command_delay_s_{0.0};  // the last tick's CommandDelayS()
  std::atomic<bool> unplugged_{false};
  std::atomic<std::uint64_t> reports_read_{0}, reports_used_{0}, malformed_{0}, not_newer_{0},
      dropped_{0}, out_of_range_{0}, device_faults_{0}, watchdog_reports_{0}, reads_interrupted_{0},
      commands_late_ticks_{0}, commands_ignored_ticks_{0};
  std::atomic<bool> commands_ignored_{false};  // DescribeFault reads it
  std::atomic<double> round_trip_last_us_{0.0};
  LatencyHistogram round_trip_;
};

}  // namespace hapticad
