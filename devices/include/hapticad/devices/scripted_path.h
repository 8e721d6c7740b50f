// SPDX-License-Identifier: GPL-3.0-or-later
// ScriptedPath: waypoints (time s, position m) with strictly increasing times; a point
// following it moves linearly between them and rests at the ends. A recorded
// trajectory (a trace's times and positions) is a ScriptedPath with many waypoints.
//
// PathCursor samples a path at times that mostly move forward (a servo session's
// clock): amortised O(1) per sample, O(log n) after a rewind. Servo-tick safe.
#pragma once

#include <cstddef>
#include <vector>

#include "hapticad/core/vec3.h"

namespace hapticad {

struct ScriptedPath {
  std::vector<double> times_s;
  std::vector<Vec3> positions;  // in the frame of whoever follows the path, m

  // Throws std::invalid_argument if empty, of unequal lengths, with non-finite values
  // or with times that do not strictly increase.
  void Validate() const;
  double duration_s() const { return times_s.empty() ? 0.0 : times_s.back(); }
};

struct PathSample {
  Vec3 position = Vec3::Zero();  // m
  Vec3 velocity = Vec3::Zero();  // m/s: the slope of the current segment, zero at rest
};

class PathCursor {
 public:
  // `path` must be valid (Validate()) and outlive the cursor.
  explicit PathCursor(const ScriptedPath* path) : path_(path) {}

  PathSample Sample(double t_s);

 private:
  const ScriptedPath* path_;
  std::size_t segment_ = 0;
};

}  // namespace hapticad
