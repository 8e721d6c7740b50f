// SPDX-License-Identifier: GPL-3.0-or-later
// Device: the narrow interface every haptic device backend implements (simulated, HID).
//
// Frames and units: the device frame `_d`, SI (m, m/s, N, s). A device reports where
// its handle is in its own workspace and takes a force in that frame; the servo loop
// maps both to and from the world (workspace_mapping.h, clutch.h).
//
// Threads: BeginSession() is called on the thread that starts the servo loop;
// ReadState(), WriteForce() and EndSession() on the servo thread. ReadState() and
// WriteForce() run once per tick: they must not allocate, lock or block beyond the
// device I/O itself (tests/devices/*_test.cc count their allocations).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "hapticad/core/vec3.h"

namespace hapticad {

// What a device can do. Zero in a field marked "0: not stated" means the device did
// not state it (the safety layer then does not apply that limit).
struct DeviceLimits {
  double max_force_n = 3.3;         // peak force the device can render, N (> 0)
  double continuous_force_n = 0.0;  // force it can hold indefinitely (thermal), N; 0: not stated
  double max_stiffness_n_per_m = 400.0;  // largest stable contact stiffness, N/m (> 0)
  double max_damping_n_s_per_m = 0.0;    // largest stable virtual damping, N s/m; 0: not stated
  Vec3 workspace_min_d = Vec3::Constant(-0.08);  // reachable box, device frame, m
  Vec3 workspace_max_d = Vec3::Constant(0.08);
  double position_resolution_m = 0.0;  // encoder step at the handle, m; 0: continuous
};

// Throws std::invalid_argument naming the first field that is not physical (non-finite,
// a maximum that is not positive, an empty workspace, a negative resolution).
void ValidateDeviceLimits(const DeviceLimits& limits);

struct DeviceInfo {
  std::string kind;  // "sim", "hid"
  std::string name;  // for people: "Simulated hand", the USB product string
  std::string path;  // how to open it again: "sim:hand", "/dev/hidraw3"
  DeviceLimits limits;
};

struct DeviceState {
  double time_s = 0.0;             // device clock, s (its own; only differences matter)
  Vec3 position_d = Vec3::Zero();  // handle, device frame, m
  Vec3 velocity_d = Vec3::Zero();  // handle, m/s, filtered by the device layer
  std::uint32_t buttons = 0;       // bit i = button i pressed
  double age_s = 0.0;              // how old the data is when read (staleness), s
};

// Outcome of one ReadState(). Anything but kOk means the state must not be rendered:
// the loop commands zero force that tick and counts it.
enum class ReadStatus : std::uint8_t {
  kOk = 0,
  kNoData,       // nothing valid received yet this session
  kOutOfRange,   // the device sent values outside what it can physically report
  kDeviceFault,  // the device itself reports a fault (amplifier, calibration)
  kUnplugged,    // the device is gone; every later read returns this too
};

// Thrown when a device cannot be opened or used; what() is a message for the user.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Device {
 public:
  virtual ~Device() = default;

  virtual const DeviceInfo& info() const = 0;

  // Prepares a session (flushes old data, enables the motors). May throw DeviceError.
  virtual void BeginSession() {}

  // The latest state. `loop_time_s` is the servo loop's clock (s since the session
  // started: the tick's scheduled time), which a simulated device uses as its own; a
  // real one may ignore it (HidDevice ages its data on the host's monotonic clock, which
  // a late tick does not skew). On anything but kOk, `state` keeps the last good values.
  virtual ReadStatus ReadState(double loop_time_s, DeviceState* state) = 0;

  // Commands a force (N, device frame) until the next call.
  virtual void WriteForce(const Vec3& force_d) = 0;

  // Ends a session: zero force, motors disabled. Must not throw.
  virtual void EndSession() {}

  // A sentence for the user about the last fault (why it was unplugged, what was
  // wrong); empty when there was none. Allocates: call it off the servo tick.
  virtual std::string DescribeFault() const { return {}; }

  // True for a device whose world advances only with the loop's clock (a simulation,
  // read at `loop_time_s`): when the host holds the servo thread off its core, that
  // world waits with it, and no command acts on its handle for longer than a tick. For
  // such a device the loop's clock goes a period a tick (no ticks skipped after a late
  // one) and its watchdog sees that clock's gap; a real device (false) goes on pushing
  // with its last command in real time, so a late tick is a fault.
  virtual bool runs_on_loop_time() const { return false; }

  // True when a kUnplugged read means the device is still attached but stopped taking
  // commands (the session ends the same way; the words for the user differ). Off the tick.
  virtual bool stopped_answering() const { return false; }
};

}  // namespace hapticad
