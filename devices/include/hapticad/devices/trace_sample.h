// SPDX-License-Identifier: GPL-3.0-or-later
// TraceSample: what the servo loop records each tick. Plain data (the Python binding
// exposes an array of them as a NumPy structured array). World frame, SI units.
#pragma once

#include <cstdint>

namespace hapticad {

struct TraceSample {
  double time_s;           // loop clock at the start of the tick
  double device_m[3];      // device position
  double velocity_mps[3];  // device velocity
  double proxy_m[3];       // proxy position
  double force_n[3];       // force sent to the device
  double normal_force_n;   // along the contact normal
  double tangential_force_n;
  double friction_force_n;  // parts of the force, before clamping (RenderOutput)
  double texture_force_n;
  double vibration_force_n;
  std::int32_t cad_face;  // touched face, -1 when free
  std::uint32_t flags;    // RenderFlags, plus kDeviceFault below
  double tick_us;         // compute time of this tick: read, render, write
};

// The device returned no valid state this tick (zero force was commanded).
constexpr std::uint32_t kDeviceFault = 1u << 8;

}  // namespace hapticad
