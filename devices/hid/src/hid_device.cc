// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: HidDevice::ReadState and HidDevice::WriteForce run on the servo tick.
#include "hapticad/devices/hid/hid_device.h"

#include <hidapi/hidapi.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cwchar>
#include <mutex>
#include <utility>

#include "hapticad/devices/hid/udev_advice.h"
#include "hid_text.h"

namespace hapticad {
namespace {

constexpr int kMaxReadsPerTick = 64;  // hidraw queues at most 64 reports
constexpr double kWorkspaceMargin = 0.25;
constexpr double kDriftAllowance = 1e-3;  // s per s: crystals drift 1e-4 at most
// A report more than this many reports' time after the last one (at the device's stated
// rate) may carry a sequence that has wrapped past half its 16-bit range: the device's
// 32-bit clock decides. A quarter of the range, so a device up to twice as fast as it
// states is still resynchronised.
constexpr double kSequenceUnwrapReports = 16384.0;

// The protocol version to ask a device for: the version of major 1 inside its range
// nearest this host's 1.0 (minor versions are compatible, PROTOCOL.md section 2). The
// range has passed DescribeInfoProblem, so it holds major 1.
std::uint16_t SelectVersion(const hid::InfoReport& info) {
  return std::clamp(hid::kHostVersion, info.version_min, info.version_max);
}

// Closes a handle unless released (Open's error paths).
struct HandleGuard {
  hid_device* handle;
  ~HandleGuard() {
    if (handle) hid_close(handle);
  }
};

// hid_open_path's outcome, taken under the lock on hidapi's global state (hid_text.h).
struct Opened {
  hid_device* handle = nullptr;
  int error = 0;       // open()'s errno, which hidapi keeps
  std::string reason;  // hidapi's hid_error(NULL) when the open failed
};

Opened OpenLocked(const std::string& path) {
  Opened opened;
  std::lock_guard<std::mutex> lock(hid::GlobalStateMutex());
  errno = 0;
  opened.handle = hid_open_path(path.c_str());
  opened.error = errno;
  if (!opened.handle) opened.reason = hid::ErrorText(nullptr);
  return opened;
}

hid_device* OpenPath(const std::string& path) {
  hid::EnsureHidInit();
  const Opened opened = OpenLocked(path);
  if (!opened.handle) {
    const std::string& reason = opened.reason;
    std::string message = "cannot open the HID device " + path + ": " + reason;
    if (opened.error == EACCES || opened.error == EPERM ||
        reason.find("ermission") != std::string::npos) {
      std::uint16_t vendor_id = 0, product_id = 0;
      // after OpenLocked has let go: FindUsbIds takes the lock itself
      const bool known = hid::FindUsbIds(path, &vendor_id, &product_id);
      message += hid::UdevAdvice(known, vendor_id, product_id);
    }
    throw DeviceError(message);
  }
  return opened.handle;
}

// The session report's exchange on `handle` (PROTOCOL.md section 3.4), and its outcome.
struct SessionAnswer {
  bool taken = false;       // the device took the version, the session flag and the watchdog
  bool unanswered = false;  // the exchange itself failed (USB), not the device's answer
  int watchdog_ms = 0;      // the watchdog the device took (its default for 0), when answered
  std::string why_not;      // when not taken
};

SessionAnswer ExchangeSession(hid_device* handle, const hid::SessionReport& session,
                              int default_watchdog_ms) {
  SessionAnswer answer;
  std::uint8_t out[hid::kSessionReportSize];
  hid::EncodeSession(session, out);
  if (hid_send_feature_report(handle, out, sizeof out) < 0) {
    answer.unanswered = true;
    answer.why_not = "setting the session report failed: " + hid::ErrorText(handle);
    return answer;
  }
  std::uint8_t in[256] = {hid::kSessionReportId};
  const int n = hid_get_feature_report(handle, in, sizeof in);
  if (n < 0) {
    answer.unanswered = true;
    answer.why_not = "reading the session report back failed: " + hid::ErrorText(handle);
    return answer;
  }
  hid::SessionReport accepted;
  if (!hid::DecodeSession(in, static_cast<std::size_t>(n), &accepted)) {
    answer.why_not = "its session report (" + std::to_string(n) + " bytes) is malformed";
    return answer;
  }
  if (accepted.version != session.version ||
      (accepted.flags & hid::kSessionOpen) != session.flags) {
    answer.why_not =
        "it answered version " +
        (accepted.version == 0 ? std::string("0") : hid::VersionString(accepted.version)) +
        ((accepted.flags & hid::kSessionOpen) ? " with a session open" : " with no session");
    return answer;
  }
  answer.watchdog_ms = accepted.watchdog_ms ? accepted.watchdog_ms : default_watchdog_ms;
  const int asked_ms = session.watchdog_ms ? session.watchdog_ms : default_watchdog_ms;
  // a longer watchdog than asked keeps pushing with the last force that long after the
  // host stops (a crashed servo loop): the host's bound on it is a safety limit
  if (answer.watchdog_ms > asked_ms) {
    answer.why_not = "it took a watchdog of " + std::to_string(answer.watchdog_ms) + " ms where " +
                     std::to_string(asked_ms) +
                     " ms was asked, so it would go on pushing with the last force for " +
                     std::to_string(answer.watchdog_ms) + " ms after the commands stop";
    return answer;
  }
  answer.taken = true;
  return answer;
}

hid::InfoReport ReadInfo(hid_device* handle, const std::string& path) {
  std::uint8_t buffer[256] = {hid::kInfoReportId};
  const int n = hid_get_feature_report(handle, buffer, sizeof buffer);
  if (n < 0) {
    throw DeviceError("the HID device " + path +
                      " did not answer the HaptiCAD device information request (feature report "
                      "0x03): " +
                      hid::ErrorText(handle) + "; it is probably not a HaptiCAD protocol device");
  }
  hid::InfoReport info;
  if (!hid::DecodeInfo(buffer, static_cast<std::size_t>(n), &info)) {
    throw DeviceError("the HID device " + path + " sent a device information report of " +
                      std::to_string(n) + " bytes (expected " +
                      std::to_string(hid::kInfoReportSize) +
                      "); it is probably not a HaptiCAD protocol device");
  }
  const std::string problem = hid::DescribeInfoProblem(info);
  if (!problem.empty()) {
    throw DeviceError("cannot use the HID device " + path + ": " + problem);
  }
  return info;
}

HidProbe ProbeOpen(hid_device* handle, const std::string& path) {
  HidProbe probe;
  probe.report = ReadInfo(handle, path);
  probe.info.kind = "hid";
  probe.info.path = path;
  probe.info.name = hid::ProductName(handle);
  probe.info.limits = hid::LimitsFromInfo(probe.report);
  return probe;
}

}  // namespace

HidProbe HidDevice::Probe(const std::string& path) {
  HandleGuard guard{OpenPath(path)};
  return ProbeOpen(guard.handle, path);
}

std::unique_ptr<HidDevice> HidDevice::Open(const std::string& path, int watchdog_ms) {
  if (watchdog_ms < 0 || watchdog_ms > 1000) {
    throw DeviceError("HID device watchdog " + std::to_string(watchdog_ms) +
                      " ms is outside 0..1000 ms");
  }
  HandleGuard guard{OpenPath(path)};
  HidProbe probe = ProbeOpen(guard.handle, path);
  // the writer's own handle: hidapi's per-handle error text must not be shared by threads
  const Opened writer = OpenLocked(path);
  HandleGuard writer_guard{writer.handle};
  if (!writer_guard.handle) {
    throw DeviceError("cannot open the HID device " + path +
                      " a second time, for its force commands: " + writer.reason);
  }
  std::unique_ptr<HidDevice> device(new HidDevice(guard.handle, std::move(probe)));
  guard.handle = nullptr;  // the device owns it now
  device->writer_ = std::make_unique<HidOutputWriter>(writer_guard.handle);
  writer_guard.handle = nullptr;  // the writer owns it now
  device->watchdog_ms_ = watchdog_ms;
  const hid::InfoReport& info = device->report_;
  hid::SessionReport negotiate;  // SESSION = 0: the version and watchdog, no force yet
  negotiate.version = device->version_;
  negotiate.watchdog_ms = static_cast<std::uint16_t>(watchdog_ms);
  const SessionAnswer answer = ExchangeSession(device->handle_, negotiate, info.watchdog_ms);
  const std::string protocol = "HaptiCAD HID protocol " + hid::VersionString(device->version_);
  if (answer.unanswered) {
    throw DeviceError("the HID device " + path + " did not answer the " + protocol +
                      " session request: " + answer.why_not +
                      ". Unplug it, plug it in again and open it again");
  }
  if (!answer.taken) {
    throw DeviceError("the HID device " + path + " refused " + protocol + ", which it lists (" +
                      hid::VersionString(info.version_min) + "-" +
                      hid::VersionString(info.version_max) + "): " + answer.why_not +
                      ". Its firmware does not follow the protocol; update it");
  }
  // a device that took a shorter watchdog drops the force sooner: the host's stall bound
  device->command_stall_s_ = answer.watchdog_ms * 1e-3;
  return device;
}

HidDevice::HidDevice(hid_device* handle, HidProbe probe)
    : handle_(handle),
      info_(std::move(probe.info)),
      report_(probe.report),
      version_(SelectVersion(report_)) {
  const Vec3 margin =
      kWorkspaceMargin * (info_.limits.workspace_max_d - info_.limits.workspace_min_d);
  allowed_min_d_ = info_.limits.workspace_min_d - margin;
  allowed_max_d_ = info_.limits.workspace_max_d + margin;
}

HidDevice::~HidDevice() {
  if (session_open_) EndSession();
  writer_.reset();  // at most HidOutputWriter::kAbandonAfterS
  hid_close(handle_);
}

void HidDevice::BeginSession() {
  if (unplugged()) {
    throw DeviceError("the HID device " + info_.path + " was unplugged; open it again");
  }
  // the last session's close, or a write stuck in the kernel, must be over: a barrier
  if (!writer_->Run([](hid_device*) {}, kEndSessionWaitS)) {
    char waited[32];
    std::snprintf(waited, sizeof waited, "%.1f s", writer_->busy_s());
    throw DeviceError("the HID device " + info_.path +
                      " is not taking commands: a write to it has waited " + waited +
                      " in the USB stack. Unplug it, plug it in again and open it again");
  }
  // old reports say nothing about now, but for the last force command the device applied:
  // it applies only commands newer than that one, which may be another session's (a
  // device left plugged in between two Feel sessions), so the sequence goes on from there
  bool echo_known = false;
  std::uint16_t echo = 0;
  for (int i = 0; i < 4096; ++i) {
    const int n = hid_read_timeout(handle_, buffer_, sizeof buffer_, 0);
    if (n <= 0) break;
    hid::InputReport r;
    if (hid::DecodeInput(buffer_, static_cast<std::size_t>(n), &r)) {
      echo = r.output_sequence_echo;
      echo_known = true;
    }
  }
  // none queued (the handle opened just now): the device sends one within its report period
  for (int waited_ms = 0; !echo_known && waited_ms < kEchoWaitMs; waited_ms += 5) {
    const int n = hid_read_timeout(handle_, buffer_, sizeof buffer_, 5);
    hid::InputReport r;
    if (n > 0 && hid::DecodeInput(buffer_, static_cast<std::size_t>(n), &r)) {
      echo = r.output_sequence_echo;
      echo_known = true;
    }
  }
  if (echo_known) output_sequence_ = echo;  // the next command is echo + 1: newer
  // the session request goes through the writer's handle, this thread waiting a bounded
  // time: a device that does not answer held it 5 s per request in usbhid (Start froze)
  hid::SessionReport session;
  session.flags = hid::kSessionOpen;
  session.version = version_;
  session.watchdog_ms = static_cast<std::uint16_t>(watchdog_ms_);
  auto answer = std::make_shared<SessionAnswer>();  // the job owns what it uses
  const int default_watchdog_ms = report_.watchdog_ms;
  if (!writer_->Run(
          [session, answer, default_watchdog_ms](hid_device* h) {
            *answer = ExchangeSession(h, session, default_watchdog_ms);
          },
          kBeginSessionWaitS)) {
    char waited[32];
    std::snprintf(waited, sizeof waited, "%.1f s", kBeginSessionWaitS);
    throw DeviceError("the HID device " + info_.path +
                      " did not answer the request to open a session within " + waited +
                      ". Unplug it, plug it in again and open it again");
  }
  if (!answer->taken) {
    throw DeviceError("the HID device " + info_.path +
                      " did not open a session: " + answer->why_not);
  }
  command_stall_s_ = answer->watchdog_ms * 1e-3;
  session_open_ = true;
  have_report_ = false;
  have_good_ = false;
  verdict_ = ReadStatus::kNoData;
  first_posted_ = static_cast<std::uint16_t>(output_sequence_ + 1);
  posted_ = false;
  echo_applied_ = false;
  commands_ignored_.store(false, std::memory_order_relaxed);
  velocity_filter_.Reset();
  last_now_s_ = clock_();
  command_delay_s_.store(0.0, std::memory_order_relaxed);
  writer_->BeginSession();
}

void HidDevice::EndSession() {
  if (!session_open_) return;
  session_open_ = false;
  writer_->EndSession();
  const Lost lost = lost_.load(std::memory_order_acquire);
  if (lost == Lost::kRead || lost == Lost::kWrite) return;  // gone: nothing reaches it
  // the close goes through the writer, after the write under way: a device that stopped
  // taking commands gets it when (if) that write returns; this thread waits a bounded time
  hid::OutputReport zero;  // ENABLE = 0, zero force
  zero.sequence = ++output_sequence_;
  zero.input_sequence = last_sequence_;
  HidOutputWriter::Report out;
  hid::EncodeOutput(zero, out.data());
  hid::SessionReport closed;
  closed.flags = 0;
  closed.version = version_;
  closed.watchdog_ms = static_cast<std::uint16_t>(watchdog_ms_);
  writer_->Run(
      [out, closed](hid_device* handle) {
        hid_write(handle, out.data(), out.size());
        ExchangeSession(handle, closed, 0);
      },
      kEndSessionWaitS);
}

void HidDevice::Count(std::atomic<std::uint64_t>& counter, std::uint64_t n) {
  counter.store(counter.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
}

double HidDevice::MonotonicSeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);  // vDSO: no system call
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

ReadStatus HidDevice::ReadState(double /*loop_time_s*/, DeviceState* state) {
  if (unplugged()) return ReadStatus::kUnplugged;
  const double now = clock_();
  last_now_s_ = now;
  // the force commands: written, failing, or stuck in the USB stack
  if (writer_->failed()) {
    MarkLost(Lost::kWrite, writer_->failure_reason());
    return ReadStatus::kUnplugged;
  }
  const double command_delay_s = writer_->CommandDelayS(now);
  command_delay_s_.store(command_delay_s, std::memory_order_relaxed);
  if (command_delay_s >= kCommandTimeoutS) {
    MarkLost(Lost::kCommandsStuck, nullptr);
    return ReadStatus::kUnplugged;
  }
  bool fault_seen = false;  // a fault reported between two ticks is this tick's fault
  for (int i = 0; i < kMaxReadsPerTick; ++i) {
    errno = 0;  // hidapi 0.13 leaves errno alone when poll() reports a hang-up
    const int n = hid_read_timeout(handle_, buffer_, sizeof buffer_, 0);
    if (n < 0) {
      // a signal interrupted poll() or read(): no data this tick, not an unplug (an unplug
      // shows as POLLHUP/POLLERR or a failed read, and comes back at the next tick)
      if (errno == EINTR) {
        Count(reads_interrupted_);
        break;
      }
      MarkLost(Lost::kRead, hid_error(handle_));
      return ReadStatus::kUnplugged;
    }
    if (n == 0) break;
    Count(reports_read_);
    hid::InputReport r;
    if (!hid::DecodeInput(buffer_, static_cast<std::size_t>(n), &r)) {
      Count(malformed_);
      continue;
    }
    if (have_report_) {
      // unsigned difference: wraps every 71.6 min; "back" shows as a huge step
      const std::uint32_t dt_us = r.device_time_us - last_device_time_us_;
      const auto step = static_cast<std::uint16_t>(r.sequence - last_sequence_);
      std::int64_t ahead = static_cast<std::int16_t>(step);
      // after a long gap (the host stalled: hidraw kept the oldest reports and dropped
      // the rest) the 16-bit sequence may have moved on by more than half its range and
      // look like going back. The device's clock, 32 bits, moved forward: the advance is
      // the one of step + k 65536 that agrees with it at the device's rate
      const double expected = dt_us * 1e-6 * report_.report_rate_hz;
      if (dt_us < 0x80000000u && expected >= kSequenceUnwrapReports) {
        const double wraps = std::round((expected - step) / 65536.0);
        ahead = std::max<std::int64_t>(1, step + static_cast<std::int64_t>(wraps) * 65536);
      }
      if (ahead <= 0 || dt_us == 0 || dt_us >= 0x80000000u) {
        Count(not_newer_);
        continue;
      }
      if (ahead > 1) Count(dropped_, static_cast<std::uint64_t>(ahead - 1));
      device_time_s_ += dt_us * 1e-6;
    }
    have_report_ = true;
    echo_read_s_ = now;
    if (posted_ && static_cast<std::int16_t>(r.output_sequence_echo - first_posted_) >= 0 &&
        static_cast<std::int16_t>(output_sequence_ - r.output_sequence_echo) >= 0) {
      echo_applied_ = true;  // a command of this session got through (not one of an older one)
    }
    last_sequence_ = r.sequence;
    last_device_time_us_ = r.device_time_us;
    last_status_.store(r.status, std::memory_order_relaxed);
    if (r.status & hid::kStatusWatchdog) Count(watchdog_reports_);
    if (r.round_trip_us != 0) {
      round_trip_.Record(static_cast<std::int64_t>(r.round_trip_us) * 1000);
      round_trip_last_us_.store(r.round_trip_us, std::memory_order_relaxed);
    }
    const Vec3 p(hid::PositionFromWire(r.position_nm[0]), hid::PositionFromWire(r.position_nm[1]),
                 hid::PositionFromWire(r.position_nm[2]));
    // a tripped device watchdog is a fault too: the force must ramp in again, not jump
    // back when commands get through
    if (r.status & (hid::kStatusFault | hid::kStatusNotHomed | hid::kStatusWatchdog)) {
      Count(device_faults_);
      fault_seen = true;
      verdict_ = ReadStatus::kDeviceFault;
    } else if (!(p.array() >= allowed_min_d_.array()).all() ||
               !(p.array() <= allowed_max_d_.array()).all()) {
      Count(out_of_range_);
      verdict_ = ReadStatus::kOutOfRange;
    } else {
      Count(reports_used_);
      velocity_filter_.Update(device_time_s_, p);
      position_d_ = p;
      buttons_ = r.buttons;
      // how much later than the quickest recent report this one came
      const double offset = now - device_time_s_;
      if (!have_good_) {
        min_offset_s_ = offset;
      } else {
        min_offset_s_ =
            std::min(min_offset_s_ + kDriftAllowance * (now - min_offset_time_s_), offset);
      }
      min_offset_time_s_ = now;
      fresh_delay_s_ = offset - min_offset_s_;
      have_good_ = true;
      last_fresh_s_ = now;
      verdict_ = ReadStatus::kOk;
    }
  }
  // the force was zero for a while since the last tick (a fault that came and went
  // between two ticks): the newest report's position stands, but the force ramps in again
  if (fault_seen && verdict_ == ReadStatus::kOk) verdict_ = ReadStatus::kDeviceFault;
  // commands that waited over the device's watchdog: it has dropped the force by itself;
  // zero force here too, and a ramp-in once they flow again
  if (command_delay_s > command_stall_s_) {
    Count(commands_late_ticks_);
    return ReadStatus::kDeviceFault;
  }
  // commands written but none applied: the device ignores them (it applies only newer
  // sequences than its last, which may be one the host cannot know): zero force, and a
  // ramp-in once one gets through (the ENABLE the host sends is not what the device does)
  // (said by a report read that long after the first command: a silent device is no data)
  if (posted_ && !echo_applied_ && have_report_ &&
      echo_read_s_ - first_post_s_ > kCommandsIgnoredS) {
    Count(commands_ignored_ticks_);
    commands_ignored_.store(true, std::memory_order_relaxed);
    return ReadStatus::kDeviceFault;
  }
  if (echo_applied_) commands_ignored_.store(false, std::memory_order_relaxed);
  if (!have_good_) return verdict_ == ReadStatus::kOk ? ReadStatus::kNoData : verdict_;
  if (verdict_ != ReadStatus::kOk) return verdict_;
  state->time_s = device_time_s_;
  state->position_d = position_d_;
  state->velocity_d = velocity_filter_.velocity();
  state->buttons = buttons_;
  state->age_s = now - last_fresh_s_ + fresh_delay_s_;
  return ReadStatus::kOk;
}

void HidDevice::WriteForce(const Vec3& force_d) {
  if (unplugged()) return;
  hid::OutputReport r;
  r.flags = session_open_ ? hid::kOutputEnable : 0;
  r.sequence = ++output_sequence_;
  r.input_sequence = last_sequence_;
  if (session_open_ && !posted_) {
    posted_ = true;
    first_post_s_ = last_now_s_;
  }
  for (int a = 0; a < 3; ++a) r.force_un[a] = hid::ForceToWire(force_d[a]);
  HidOutputWriter::Report out;
  hid::EncodeOutput(r, out.data());
  writer_->Post(out, last_now_s_);  // wait-free: the writer thread does the USB write
}

void HidDevice::MarkLost(Lost how, const wchar_t* reason) {
  // hidapi's error text belongs to the handle's thread: keep it for DescribeFault() (any
  // thread) before saying unplugged. Unplugged is final: written once.
  if (reason) std::wcsncpy(unplug_reason_, reason, kReasonLength - 1);
  unplug_reason_[kReasonLength - 1] = L'\0';
  lost_.store(how, std::memory_order_release);
  unplugged_.store(true, std::memory_order_release);
}

std::string HidDevice::DescribeFault() const {
  const HidLinkStats s = CalcLinkStats();
  const std::uint8_t status = last_status_.load(std::memory_order_relaxed);
  std::string text;
  const double delay_ms = command_delay_s_.load(std::memory_order_relaxed) * 1e3;
  char ms[48];
  if (unplugged() && lost_.load(std::memory_order_acquire) == Lost::kCommandsStuck) {
    std::snprintf(ms, sizeof ms, "%.0f ms", kCommandTimeoutS * 1e3);
    text = std::string("it stopped taking force commands: one waited ") + ms +
           " in the USB stack without being sent (the write to the device did not return); "
           "its own watchdog drops the force after " +
           std::to_string(static_cast<int>(std::lround(command_stall_s_ * 1e3))) + " ms";
  } else if (unplugged()) {
    const std::string reason = hid::ToUtf8(unplug_reason_);
    text = "hidapi: " + (reason.empty() ? std::string("unknown error") : reason);
    if (lost_.load(std::memory_order_acquire) == Lost::kWrite) {
      text += " (writing force commands failed " +
              std::to_string(HidOutputWriter::kFailuresToGiveUp) + " times in a row)";
    }
  } else if (delay_ms > command_stall_s_ * 1e3) {
    std::snprintf(ms, sizeof ms, "%.0f ms", delay_ms);
    text = std::string("force commands are not getting through: one has waited ") + ms +
           " in the USB stack";
  } else if (status &
             hid::kStatusFault) {  // the device's own word first: it may apply nothing then
    text = "the device reports a fault (amplifier, encoder or temperature)";
  } else if (status & hid::kStatusNotHomed) {
    text = "the device is not calibrated (homed) yet";
  } else if (commands_ignored_.load(std::memory_order_relaxed)) {
    std::snprintf(ms, sizeof ms, "%.0f ms", kCommandsIgnoredS * 1e3);
    text = std::string("the device applied none of the force commands sent in ") + ms +
           " (it reports the last it applied, and it is none of them): its firmware may not "
           "follow the protocol's sequence rule; update it";
  } else if (status & hid::kStatusWatchdog) {
    text = "the device's watchdog cut the force (no command reached it in time)";
  }
  if (s.malformed + s.not_newer + s.dropped + s.out_of_range > 0) {
    if (!text.empty()) text += "; ";
    text += "link: " + std::to_string(s.reports_read) + " reports read, " +
            std::to_string(s.malformed) + " malformed, " + std::to_string(s.not_newer) +
            " out of order or repeated, " + std::to_string(s.dropped) + " dropped, " +
            std::to_string(s.out_of_range) + " out of range";
  }
  return text;
}

HidLinkStats HidDevice::CalcLinkStats() const {
  HidLinkStats s;
  auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
  s.reports_read = get(reports_read_);
  s.reports_used = get(reports_used_);
  s.malformed = get(malformed_);
  s.not_newer = get(not_newer_);
  s.dropped = get(dropped_);
  s.out_of_range = get(out_of_range_);
  s.device_faults = get(device_faults_);
  s.watchdog_reports = get(watchdog_reports_);
  const HidWriterStats w = writer_->Stats();
  s.reads_interrupted = get(reads_interrupted_);
  s.writes = w.writes;
  s.writes_failed = w.writes_failed;
  s.writes_superseded = w.superseded;
  s.commands_late_ticks = get(commands_late_ticks_);
  s.commands_ignored_ticks = get(commands_ignored_ticks_);
  s.write_max_us = w.write_max_s * 1e6;
  s.round_trip_last_us = round_trip_last_us_.load(std::memory_order_relaxed);
  s.round_trip_p50_us = round_trip_.Percentile(0.5) * 1e-3;
  s.round_trip_p99_us = round_trip_.Percentile(0.99) * 1e-3;
  s.round_trip_count = round_trip_.count();
  return s;
}

}  // namespace hapticad
