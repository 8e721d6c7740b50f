// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/device.h"

#include <cmath>
#include <string>

namespace hapticad {
namespace {

void RequirePositive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("device limits: ") + name + " = " +
                                std::to_string(value) + " must be a positive number");
  }
}

void RequireNonNegative(double value, const char* name) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw std::invalid_argument(std::string("device limits: ") + name + " = " +
                                std::to_string(value) + " must be zero (not stated) or positive");
  }
}

}  // namespace

void ValidateDeviceLimits(const DeviceLimits& limits) {
  RequirePositive(limits.max_force_n, "max_force_n");
  RequireNonNegative(limits.continuous_force_n, "continuous_force_n");
  RequirePositive(limits.max_stiffness_n_per_m, "max_stiffness_n_per_m");
  RequireNonNegative(limits.max_damping_n_s_per_m, "max_damping_n_s_per_m");
  RequireNonNegative(limits.position_resolution_m, "position_resolution_m");
  if (!limits.workspace_min_d.allFinite() || !limits.workspace_max_d.allFinite() ||
      !(limits.workspace_min_d.array() < limits.workspace_max_d.array()).all()) {
    throw std::invalid_argument(
        "device limits: the workspace must be a finite box with min < max on every axis");
  }
}

}  // namespace hapticad
