// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: PathCursor::Sample runs on the servo tick (simulated devices).
#include "hapticad/devices/scripted_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hapticad {

void ScriptedPath::Validate() const {
  if (times_s.empty()) throw std::invalid_argument("scripted path: no waypoints");
  if (times_s.size() != positions.size()) {
    throw std::invalid_argument("scripted path: " + std::to_string(times_s.size()) + " times for " +
                                std::to_string(positions.size()) + " positions");
  }
  for (std::size_t i = 0; i < times_s.size(); ++i) {
    if (!std::isfinite(times_s[i]) || !positions[i].allFinite()) {
      throw std::invalid_argument("scripted path: waypoint " + std::to_string(i) +
                                  " is not finite");
    }
    if (i > 0 && !(times_s[i] > times_s[i - 1])) {
      throw std::invalid_argument("scripted path: time of waypoint " + std::to_string(i) +
                                  " does not increase");
    }
  }
}

PathSample PathCursor::Sample(double t) {
  const auto& times = path_->times_s;
  const auto& points = path_->positions;
  PathSample out;
  if (times.size() == 1 || t <= times.front()) {
    out.position = points.front();
    return out;
  }
  if (t >= times.back()) {
    out.position = points.back();
    return out;
  }
  if (t < times[segment_]) {  // rewound: search again
    segment_ =
        static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) -
        1;
  }
  while (segment_ + 1 < times.size() && times[segment_ + 1] <= t) ++segment_;
  const double t0 = times[segment_];
  const double t1 = times[segment_ + 1];
  out.velocity = (points[segment_ + 1] - points[segment_]) / (t1 - t0);
  out.position = points[segment_] + (t - t0) * out.velocity;
  return out;
}

}  // namespace hapticad
