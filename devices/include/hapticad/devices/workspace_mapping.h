// SPDX-License-Identifier: GPL-3.0-or-later
// WorkspaceMapping: where the device's workspace sits in the world (the CAD model).
//
//   p_w = offset_w + scale * R_wd p_d        v_w = scale * R_wd v_d
//   f_d = R_wd^T f_w                          (forces are not scaled)
//
// `scale` is world metres per device metre: 1.2 lets a 160 mm workspace reach across a
// 190 mm part, and the clutch (clutch.h) moves `offset_w` to reach further still.
// Because forces are not scaled, a world spring k_w feels like scale * k_w at the
// handle. What a face is given to feel (its stiffness, damping, a stiffness study's
// force-travel law) is meant at the handle, so RenderLimitsFor() hands the renderer the
// scale with the device's own limits, and the renderer divides the face's stiffness by
// the scale in the world (force_renderer.h): the hand feels the designer's N/mm
// whatever the scale, and never more than the device renders stably. Forces in newtons
// are felt as given; what belongs to the part (a grating's period, speeds across it) is
// scaled with the part.
//
// Units: m, m/s, N. Servo-tick safe (plain arithmetic).
#pragma once

#include <Eigen/Core>

#include "hapticad/core/rendering/force_renderer.h"
#include "hapticad/core/vec3.h"
#include "hapticad/devices/device.h"

namespace hapticad {

struct WorkspaceMapping {
  double scale = 1.0;                                         // > 0
  Eigen::Matrix3d rotation_wd = Eigen::Matrix3d::Identity();  // proper rotation
  Vec3 offset_w = Vec3::Zero();                               // m

  Vec3 DeviceToWorld(const Vec3& p_d) const { return offset_w + scale * (rotation_wd * p_d); }
  Vec3 WorldToDevice(const Vec3& p_w) const {
    return rotation_wd.transpose() * (p_w - offset_w) / scale;
  }
  Vec3 VelocityToWorld(const Vec3& v_d) const { return scale * (rotation_wd * v_d); }
  Vec3 ForceToDevice(const Vec3& f_w) const { return rotation_wd.transpose() * f_w; }
  Vec3 ForceToWorld(const Vec3& f_d) const { return rotation_wd * f_d; }
};

// Throws std::invalid_argument for a non-positive or non-finite scale, a rotation that
// is not orthonormal with determinant +1 (to 1e-9), or a non-finite offset.
void ValidateWorkspaceMapping(const WorkspaceMapping& mapping);

// The renderer's limits for a device seen through `mapping`: the device's maximum
// force, stiffness and (where it states one) damping, felt at the handle as the device
// states them, and the mapping's scale (RenderLimits::workspace_scale), by which the
// renderer divides stiffness and damping in the world.
RenderLimits RenderLimitsFor(const DeviceLimits& limits, const WorkspaceMapping& mapping);

// The mapping (no rotation) that centres the device's workspace on the world box
// [world_min_w, world_max_w] and scales it just enough to cover the box on every axis
// (never below `min_scale`, so small parts are not magnified unless asked).
// Throws std::invalid_argument for an empty or non-finite box or min_scale <= 0.
WorkspaceMapping FitWorkspace(const DeviceLimits& limits, const Vec3& world_min_w,
                              const Vec3& world_max_w, double min_scale = 1.0);

}  // namespace hapticad
