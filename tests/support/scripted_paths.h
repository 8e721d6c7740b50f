// SPDX-License-Identifier: GPL-3.0-or-later
// A small scripted device path for tests of the path and of the device that plays it.
#pragma once

#include "hapticad/devices/scripted_path.h"

namespace hapticad::testing {

// Three waypoints: 0.1 m along x in the first second, then 0.2 m along y in the next two.
inline ScriptedPath ThreeWaypointPath() {
  ScriptedPath p;
  p.times_s = {0.0, 1.0, 3.0};
  p.positions = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.2, 0)};
  return p;
}

}  // namespace hapticad::testing
