// SPDX-License-Identifier: GPL-3.0-or-later
// The hidapi emulator: a library that implements hidapi's C API (hid_init,
// hid_enumerate, hid_open_path, hid_read_timeout, hid_write, hid_get_feature_report,
// hid_send_feature_report, hid_close, hid_error, ... every function of hidapi 0.13)
// over emulated devices, so that the test build links it instead of libhidapi and
// exercises the shipped HID backend unchanged.
//
// Each emulated device runs the device side of devices/hid/PROTOCOL.md (firmware.h):
// a 3-DOF mass pushed by the commanded force and held by a model of the user's hand,
// input reports at the device's rate, the device watchdog, version negotiation, and
// faults injected in time windows. Devices advance lazily on the emulator's clock
// whenever hidapi is called (the real monotonic clock, or a manual one for
// deterministic tests), as if a USB host controller queued their reports meanwhile.
//
// Thread-safe (one lock, as a kernel would serialise; a write that blocks, kSlowWrite,
// waits without it). A device may be opened by several handles, as hidraw allows; they
// share its one queue of input reports. hid_read_timeout and hid_write do not allocate
// (the backend's tick is allocation-counted through them).
//
// The same library built as a shared object (libhapticad_hidapi_emulator_preload.so)
// can be LD_PRELOADed in front of libhidapi; it then creates the devices described in
// the environment variable HAPTICAD_HIDEMU (see ConfigureFromSpec).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hapticad/core/vec3.h"

namespace hapticad::hidemu {

enum class Fault {
  kUnplug,       // at start_s the device disappears: reads and writes fail, enumerate drops it
  kStall,        // [start, end): the device sends no input reports
  kLate,         // [start, end): input reports arrive `param` s late
  kReorder,      // [start, end): input reports swapped in pairs
  kDrop,         // [start, end): each input report lost with probability `param`
  kTruncate,     // [start, end): input reports cut to `param` bytes
  kGarbage,      // [start, end): input reports replaced by random bytes (half with ID 1, 32 bytes)
  kExtreme,      // [start, end): positions at the ends of the i32 range (about +-2.1 m)
  kFreezeClock,  // [start, end): the device time stops advancing
  kDeviceFault,  // [start, end): the FAULT status bit (and no force)
  kNotHomed,     // [start, end): the NOT_HOMED status bit
  kDropOutput,   // [start, end): the host's output reports are lost
  kDuplicate,    // [start, end): every input report is sent twice
  // [start, end): a host write blocks for `param` s (emulator clock) and then fails with
  // ETIMEDOUT ("Connection timed out"), the report lost: what Linux usbhid does for 5 s
  // (USB_CTRL_SET_TIMEOUT) when the device stops taking output reports
  kSlowWrite,
  // [start, end): a host write blocks for `param` s (emulator clock) and then succeeds: a
  // device slow to take output reports
  kLateWrite,
  // [start, end): hid_read_timeout fails with errno EINTR ("Interrupted system call"), as
  // hidapi does when a signal interrupts its poll(); the device is fine
  kInterruptRead,
  // [start, end): a host feature-report request (send or get) blocks for `param` s
  // (emulator clock) and then fails with ETIMEDOUT: a control transfer the device never
  // answers, which usbhid gives up on after 5 s
  kSlowFeature,
  // [start, end): input reports give 0 as the last output sequence applied (offset 26), as a
  // firmware that does not fill it in
  kZeroEcho,
  // [start, end): as kSlowFeature, for the session report (0x04) only: the device answers
  // its information report and then not the session request
  kSlowSession,
};

struct FaultWindow {
  Fault fault;
  double start_s = 0.0;  // device time since it was plugged in
  double end_s = std::numeric_limits<double>::infinity();
  double param = 0.0;
};

struct FirmwareConfig {
  std::string path = "emu:0";
  std::string product = "HaptiCAD emulated 3-DOF device";
  std::uint16_t vendor_id = 0x1209;
  std::uint16_t product_id = 0x0001;
  std::uint16_t usage_page = 0xFF48;
  std::uint16_t usage = 0x01;
  // feature report 0x03, as sent (bad values test the host's checks)
  std::uint8_t dof = 3;
  std::uint16_t magic = 0x4348;
  std::uint16_t version_min = 0x0100;
  std::uint16_t version_max = 0x0100;
  std::uint16_t watchdog_ms = 20;
  std::uint16_t report_rate_hz = 1000;
  double max_force_n = 8.0;
  double continuous_force_n = 4.0;
  double max_stiffness_n_per_m = 2500.0;
  double max_damping_n_s_per_m = 5.0;
  Vec3 workspace_min_m = Vec3::Constant(-0.08);
  Vec3 workspace_max_m = Vec3::Constant(0.08);
  double position_resolution_m = 10e-6;
  // the handle: a mass with damping, held by the user's hand (a spring-damper toward a
  // target moving piecewise linearly through hand_positions_m at hand_times_s)
  double mass_kg = 0.1;
  double damping_n_s_per_m = 2.0;
  double hand_stiffness_n_per_m = 300.0;
  double hand_damping_n_s_per_m = 5.0;
  std::vector<double> hand_times_s;  // empty: the hand holds the handle at the origin
  std::vector<Vec3> hand_positions_m;
  double transport_latency_s = 0.0;  // each way
  std::uint32_t seed = 1;
  std::vector<FaultWindow> faults;
  // refuses every session request (answers SESSION = 0, version 0) although it lists
  // its versions: a faulty firmware
  bool refuse_sessions = false;
  // takes (and answers) this watchdog whatever the host asks for, ms (0: the host's): a
  // firmware with a fixed watchdog
  std::uint16_t fixed_watchdog_ms = 0;
  // hid_open_path fails with EACCES and hidapi 0.13.1's words ("Failed to open a device
  // with path '...': Permission denied"), as without a udev rule; it is still enumerated
  bool deny_open = false;
};

struct Snapshot {
  bool plugged = false;
  bool session_open = false;
  std::uint16_t version = 0;
  double time_s = 0.0;  // device time since plugged in
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_m = Vec3::Zero();
  Vec3 commanded_force_n = Vec3::Zero();
  Vec3 applied_force_n = Vec3::Zero();  // after session, enable, watchdog, fault, clamp
  double max_applied_force_n = 0.0;     // the largest |force| ever applied
  bool watchdog_tripped = false;
  std::uint64_t watchdog_trips = 0;
  std::uint64_t reports_generated = 0;
  std::uint64_t reports_read = 0;  // by the host
  std::uint64_t outputs_received = 0;
  std::uint64_t outputs_applied = 0;
  std::uint64_t outputs_rejected = 0;   // malformed, bad CRC or not newer
  std::uint64_t outputs_timed_out = 0;  // host writes that blocked and failed (kSlowWrite)
  std::uint64_t round_trips = 0;
  double round_trip_last_s = 0.0;
  double round_trip_p50_s = 0.0;
  double round_trip_p99_s = 0.0;
  double round_trip_max_s = 0.0;
};

// Removes every device and returns to the real clock.
void Reset();
// Plugs in a device; returns its id. It appears in hid_enumerate() at once.
int AddDevice(const FirmwareConfig& config);
// A HID device that is not a haptic device (a keyboard): enumerated, never ours.
void AddOtherDevice(const std::string& path, std::uint16_t vendor_id, std::uint16_t product_id,
                    std::uint16_t usage_page, std::uint16_t usage, const std::string& product);
// Pulls the cable now.
void Unplug(int id);
// Moves the user's hand target (overrides the trajectory from now on).
void SetHandTarget(int id, const Vec3& target_m);
Snapshot GetSnapshot(int id);

// The emulator clock, s. Manual mode: time stands still unless set.
void UseManualClock(double t_s);
void SetTime(double t_s);
void UseRealClock();
double Now();

// How many times hid_error() was called, on any handle (hidapi's error text is not
// thread-safe: a backend must not ask for it from another thread while it runs).
std::uint64_t HidErrorCalls();

// hidapi's global state is not thread-safe: hidapi 0.13 keeps one process-wide error
// string that hid_init, hid_enumerate and hid_open_path (and hid_exit) free and replace, and
// hid_error(NULL) reads, with no lock, so a backend must never be inside two of those calls
// at once. The emulator counts the threads inside them (hid_open, which opens through
// hid_open_path, is one call) and keeps the most there ever were at once, since the last
// Reset(). SetGlobalCallDelay makes each such call first sleep `seconds` of real time,
// outside the emulator's own lock (which would otherwise serialise them and hide the
// overlap), so that calls a backend lets overlap do overlap. Reset() sets the delay back to
// 0 and forgets the maximum.
void SetGlobalCallDelay(double seconds);
int MaxConcurrentGlobalCalls();

// hidapi handles open now on the device at `path` (hid_open_path minus hid_close; a
// handle stays counted after a Reset() until it is closed), and host writes blocked now
// (kSlowWrite, kLateWrite) whose time to end has not come on the emulator's clock (one
// whose time has come counts no more, even before its thread wakes up): what a test
// waits for instead of sleeping.
int OpenHandles(const std::string& path);
int BlockedWrites();

// Parses a device list like "path=emu:0,product=My arm;path=emu:1,version=2.0-2.1" and
// adds the devices. Keys: path, product, version (min-max), max_force (N; the continuous
// force becomes half of it), rate (Hz),
// unplug_at (s), stall (start-end s), slow_feature and slow_session (s: from the
// plug-in on, every feature request, or the session request only, blocks that long and
// then times out), kind=other (a non-haptic HID device). Throws std::invalid_argument
// for anything else.
void ConfigureFromSpec(const std::string& spec);

}  // namespace hapticad::hidemu
