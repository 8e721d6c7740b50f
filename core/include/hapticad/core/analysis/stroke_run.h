// SPDX-License-Identifier: GPL-3.0-or-later
// RunStroke: renders a precomputed stroke tick by tick, timing each tick. For the
// speed/accuracy table (plugin/HaptiCAD/hapticad/accuracy_table.py) and benchmarks: the
// path is made before the timed loop, and each Render() is timed on its own with the
// steady clock (some 20 ns of the clock's own cost included).
//
// Units as in ForceRenderer (world frame, SI); tick times in microseconds. Allocates the
// result once, before the loop; not for the servo thread.
#pragma once

#include <vector>

#include "hapticad/core/rendering/force_renderer.h"

namespace hapticad {

struct StrokeRun {
  std::vector<RenderOutput> outputs;  // one per input
  std::vector<double> tick_us;        // one per input
};

StrokeRun RunStroke(ForceRenderer& renderer, const std::vector<RenderInput>& inputs);

}  // namespace hapticad
