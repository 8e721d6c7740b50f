// SPDX-License-Identifier: GPL-3.0-or-later
// TraceSample: what the servo loop records each tick. Plain data (the Python binding
// exposes an array of them as a NumPy structured array). World frame and SI units
// unless the name says otherwise (`_d`: device frame).
#pragma once

#include <cstdint>

namespace hapticad {

struct TraceSample {
  double time_s;           // loop clock at the start of the tick
  double device_m[3];      // the tool in the world (handle through mapping and clutch)
  double velocity_mps[3];  // the tool's velocity in the world
  double proxy_m[3];       // proxy position
  double force_n[3];       // force sent to the device, in the world frame, after safety
  double normal_force_n;   // along the contact normal
  double tangential_force_n;
  double friction_force_n;  // parts of the force, before clamping (RenderOutput)
  double texture_force_n;
  double vibration_force_n;
  std::int32_t cad_face;  // touched face, -1 when free
  std::uint32_t flags;    // RenderFlags (bits 0-7) and the servo flags below
  double tick_us;         // compute time of this tick: read, render, write
  double handle_d_m[3];   // the handle in the device frame, as read
  double period_us;       // time since the previous tick started (0 for the first)
  std::uint32_t buttons;  // bit i = device button i
  std::uint32_t reserved;
};

// Servo flags (bits 8 and up; the renderer's RenderFlags use bits 0-7).
// Zero force was commanded this tick because of one of the kFault* reasons below.
constexpr std::uint32_t kDeviceFault = 1u << 8;
constexpr std::uint32_t kFaultNoData = 1u << 9;       // nothing received yet
constexpr std::uint32_t kFaultStale = 1u << 10;       // data older than the stale limit
constexpr std::uint32_t kFaultOutOfRange = 1u << 11;  // position or speed impossible
constexpr std::uint32_t kFaultNonFinite = 1u << 12;   // NaN or Inf from device or renderer
constexpr std::uint32_t kFaultReported = 1u << 13;    // the device reports a fault
constexpr std::uint32_t kFaultWatchdog = 1u << 14;    // the loop missed its watchdog
constexpr std::uint32_t kFaultUnplugged = 1u << 15;   // the device is gone
// The renderer refused the tick (its kInputFault: the tool beyond its reach or speed
// bounds in the world, or a force that would not be finite). Bit 20: bits 16-19 below
// were taken when it came.
constexpr std::uint32_t kFaultRenderer = 1u << 20;
constexpr std::uint32_t kFaultMask = kFaultNoData | kFaultStale | kFaultOutOfRange |
                                     kFaultNonFinite | kFaultReported | kFaultWatchdog |
                                     kFaultUnplugged | kFaultRenderer;
// Force shaping by the safety layer (the force was sent, reduced).
constexpr std::uint32_t kRamping = 1u << 16;         // ramping in after start or a fault
constexpr std::uint32_t kSafetyClamped = 1u << 17;   // clamped to the device's maximum
constexpr std::uint32_t kThermalLimited = 1u << 18;  // held to the continuous force
constexpr std::uint32_t kClutched = 1u << 19;        // clutch held: tool frozen, no force

}  // namespace hapticad
