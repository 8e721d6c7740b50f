// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: Clutch::Update runs on the servo tick.
#include "hapticad/devices/clutch.h"

namespace hapticad {

Clutch::Event Clutch::Update(bool held, const Vec3& handle_d, WorkspaceMapping* mapping) {
  if (held && !engaged_) {
    engaged_ = true;
    frozen_tool_w_ = mapping->DeviceToWorld(handle_d);
    return Event::kEngaged;
  }
  if (!held && engaged_) {
    engaged_ = false;
    mapping->offset_w = frozen_tool_w_ - mapping->scale * (mapping->rotation_wd * handle_d);
    return Event::kReleased;
  }
  return Event::kNone;
}

}  // namespace hapticad
