// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/surfaces/surface_properties.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hapticad {
namespace {

void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("surface: ") + field + " = " + std::to_string(value) +
                                " must be " + rule);
  }
}

}  // namespace

void ValidateSurfaceProperties(const SurfaceProperties& s) {
  const FrictionParams& f = s.friction;
  Require(std::isfinite(f.static_coefficient) && f.static_coefficient >= 0.0, "static friction",
          f.static_coefficient, "finite and >= 0");
  Require(std::isfinite(f.dynamic_coefficient) && f.dynamic_coefficient >= 0.0, "dynamic friction",
          f.dynamic_coefficient, "finite and >= 0");
  Require(std::isfinite(f.stick_speed_mps) && f.stick_speed_mps > 0.0, "stick speed",
          f.stick_speed_mps, "finite and > 0 m/s");
  Require(std::isfinite(f.transition_speed_mps) && f.transition_speed_mps >= 0.0,
          "transition speed", f.transition_speed_mps, "finite and >= 0 m/s");
  Require(std::isfinite(s.stiffness_n_per_m) && s.stiffness_n_per_m > 0.0, "stiffness",
          s.stiffness_n_per_m, "finite and > 0 N/m");
}

SurfaceTable::SurfaceTable(std::vector<SurfaceProperties> by_face) : by_face_(std::move(by_face)) {
  for (std::size_t i = 0; i < by_face_.size(); ++i) {
    try {
      ValidateSurfaceProperties(by_face_[i]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("CAD face " + std::to_string(i) + ": " + e.what());
    }
  }
}

}  // namespace hapticad
