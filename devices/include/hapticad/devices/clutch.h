// SPDX-License-Identifier: GPL-3.0-or-later
// Clutch (indexing): while held, the handle moves and the tool stays where it was in
// the world, at zero force; on release the mapping's offset shifts so the tool carries
// on from where it was. Like lifting a mouse off the desk: a small workspace can walk
// across a large part.
//
// Servo-tick safe (plain arithmetic). Frames: `_d` device, `_w` world; m.
#pragma once

#include "hapticad/core/vec3.h"
#include "hapticad/devices/workspace_mapping.h"

namespace hapticad {

class Clutch {
 public:
  enum class Event { kNone, kEngaged, kReleased };

  // Advances the clutch with this tick's `held` and handle position. On release it
  // moves `mapping->offset_w` so that the handle maps to the frozen tool position.
  Event Update(bool held, const Vec3& handle_d, WorkspaceMapping* mapping);

  bool engaged() const { return engaged_; }
  // The tool's world position while engaged.
  const Vec3& frozen_tool_w() const { return frozen_tool_w_; }
  void Reset() { engaged_ = false; }

 private:
  bool engaged_ = false;
  Vec3 frozen_tool_w_ = Vec3::Zero();
};

}  // namespace hapticad
