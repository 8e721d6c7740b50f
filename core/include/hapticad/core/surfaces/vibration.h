// SPDX-License-Identifier: GPL-3.0-or-later
// Vibration of a powered part, as the electric razor of seed 000: while the part is
// touched and powered, a sinusoidal force along a fixed axis,
//   F(t) = amplitude sin(2 pi frequency t) axis.
// Mains solenoid shavers run at 100/120 Hz, sonic ones near 170-230 Hz (field notes);
// touch is most sensitive near 250-300 Hz. World frame, SI. Pure, servo-tick safe.
#pragma once

#include "hapticad/core/vec3.h"

namespace hapticad {

struct Vibration {
  double frequency_hz = 100.0;  // > 0
  double amplitude_n = 0.3;     // >= 0
  Vec3 axis_w = Vec3::UnitZ();  // unit
  bool powered = true;
};

// Zero when unpowered or for a non-finite time.
Vec3 CalcVibrationForce(const Vibration& vibration, double time_s);

}  // namespace hapticad
