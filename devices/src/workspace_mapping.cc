// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/workspace_mapping.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace hapticad {

void ValidateWorkspaceMapping(const WorkspaceMapping& m) {
  if (!(std::isfinite(m.scale) && m.scale > 0.0)) {
    throw std::invalid_argument("workspace mapping: scale " + std::to_string(m.scale) +
                                " must be a positive number");
  }
  if (!m.offset_w.allFinite())
    throw std::invalid_argument("workspace mapping: offset is not finite");
  const Eigen::Matrix3d& r = m.rotation_wd;
  if (!r.allFinite() || !(r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-9) ||
      std::abs(r.determinant() - 1.0) > 1e-9) {
    throw std::invalid_argument("workspace mapping: rotation is not a proper rotation matrix");
  }
}

RenderLimits RenderLimitsFor(const DeviceLimits& limits, const WorkspaceMapping& mapping) {
  RenderLimits out;
  out.max_force_n = limits.max_force_n;
  out.max_stiffness_n_per_m = limits.max_stiffness_n_per_m;  // felt at the handle
  // a damping limit the device states (else the renderer's default), felt as stiffness
  if (limits.max_damping_n_s_per_m > 0.0) out.max_damping_n_s_per_m = limits.max_damping_n_s_per_m;
  out.workspace_scale = mapping.scale;  // the renderer divides them by it in the world
  return out;
}

WorkspaceMapping FitWorkspace(const DeviceLimits& limits, const Vec3& world_min_w,
                              const Vec3& world_max_w, double min_scale) {
  if (!world_min_w.allFinite() || !world_max_w.allFinite() ||
      !(world_min_w.array() <= world_max_w.array()).all()) {
    throw std::invalid_argument("fit workspace: the world box must be finite with min <= max");
  }
  if (!(std::isfinite(min_scale) && min_scale > 0.0)) {
    throw std::invalid_argument("fit workspace: min_scale must be positive");
  }
  ValidateDeviceLimits(limits);
  const Vec3 device_extent = limits.workspace_max_d - limits.workspace_min_d;
  const Vec3 world_extent = world_max_w - world_min_w;
  WorkspaceMapping m;
  m.scale = std::max(min_scale, (world_extent.array() / device_extent.array()).maxCoeff());
  const Vec3 device_centre = 0.5 * (limits.workspace_min_d + limits.workspace_max_d);
  const Vec3 world_centre = 0.5 * (world_min_w + world_max_w);
  m.offset_w = world_centre - m.scale * device_centre;
  return m;
}

}  // namespace hapticad
