// SPDX-License-Identifier: GPL-3.0-or-later
// SurfaceProperties: what a designer put on one CAD face, in SI units, ready for the
// servo tick; SurfaceTable: those properties by CAD face id.
//
// Untagged faces get kUntaggedSurface: mu_s 0.5, mu_d 0.4 (the low end of hard
// plastics and metals against a dry fingertip, resources/materials/materials.csv) and
// 0.4 N/mm, the largest stiffness the most common desktop device (3D Systems Touch)
// renders stably.
//
// The table is immutable once built; the renderer reads it on every tick (cheap, safe).
#pragma once

#include <cstdint>
#include <vector>

#include "hapticad/core/surfaces/friction.h"

namespace hapticad {

struct SurfaceProperties {
  FrictionParams friction;
  double stiffness_n_per_m = 400.0;  // contact stiffness asked for, N/m (> 0)
};

inline const SurfaceProperties kUntaggedSurface{};

// Throws std::invalid_argument naming the field if a value is negative, zero where it
// must be positive, or not finite.
void ValidateSurfaceProperties(const SurfaceProperties& surface);

class SurfaceTable {
 public:
  // `by_face[i]` belongs to CAD face i; faces beyond the vector are untagged.
  // Validates every entry (see ValidateSurfaceProperties).
  explicit SurfaceTable(std::vector<SurfaceProperties> by_face = {});

  const SurfaceProperties& surface(std::int32_t face) const {
    return face >= 0 && static_cast<std::size_t>(face) < by_face_.size() ? by_face_[face]
                                                                         : kUntaggedSurface;
  }
  std::size_t size() const { return by_face_.size(); }

 private:
  std::vector<SurfaceProperties> by_face_;
};

}  // namespace hapticad
