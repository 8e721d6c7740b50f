// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/stroke_run.h"

#include <chrono>

namespace hapticad {

StrokeRun RunStroke(ForceRenderer& renderer, const std::vector<RenderInput>& inputs) {
  using Clock = std::chrono::steady_clock;
  StrokeRun run;
  run.outputs.resize(inputs.size());
  run.tick_us.resize(inputs.size());
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const auto start = Clock::now();
    renderer.Render(inputs[k], &run.outputs[k]);
    run.tick_us[k] = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  }
  return run;
}

}  // namespace hapticad
